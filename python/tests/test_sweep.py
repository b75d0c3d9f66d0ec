"""Sweeps and batch fits on dask.distributed (superdex.sweep, superdex.fit_batch, the CLI)."""
import csv
import math
import os
import subprocess

import pytest
import superdex as sd

SRC = os.environ.get("SUPERDEX_SOURCE_DIR", os.path.join(os.path.dirname(__file__), "..", ".."))
DROP = os.path.join(SRC, "scenes", "data", "drop.json")
THROW = os.path.join(SRC, "scenes", "data", "fit_throw.json")
CN = "normal_viscous_damping_coefficient"

# Short drops (contact from t = 0.45 s): pair damping c_n from both actors' values, and one variant
# that cannot load.
VARIANTS = [{f"ball.{CN}": cn, f"ground.{CN}": cg} for cn in (0.5, 1.0) for cg in (0.5, 2.0)] + \
           [{"ball.penalty_coefficient": -3.0}]


def deterministic(rows):
    """The rows without their wall times (the only columns that may differ between runs)."""
    return [{k: v for k, v in r.items() if not k.endswith("wall_s")} for r in rows]


def test_sweep_on_two_workers_equals_serial_bit_for_bit():
    serial = sd.sweep(DROP, VARIANTS, workers=0, duration=0.55, progress=False)
    parallel = sd.sweep(DROP, VARIANTS, workers=2, duration=0.55, progress=False)
    assert deterministic(parallel) == deterministic(serial)
    assert [r["status"] for r in serial] == ["ok"] * 4 + ["error"]
    # The comparison has teeth: every variant ends in its own state, and penetration falls as
    # the pair's damping sqrt(c_ball c_ground) grows.
    assert len({r["state_digest"] for r in serial[:4]}) == 4
    depth = {math.sqrt(r[f"ball.{CN}"] * r[f"ground.{CN}"]): r["max_penetration_m"]
             for r in serial[:4]}
    assert [depth[c] for c in sorted(depth)] == sorted(depth.values(), reverse=True)
    assert all(r["steps"] == round(0.55 / 2e-4) and r["converged"] for r in serial[:4])
    assert all(r["expectations"] == "all hold" for r in serial[:4])


def test_a_failed_run_is_a_row_with_its_error():
    rows = sd.sweep(DROP, VARIANTS[-2:], workers=0, duration=0.5, progress=False)
    assert rows[0]["status"] == "ok" and rows[0]["error"] == ""
    assert rows[1]["status"] == "error"
    assert "actors[1].contact.penalty_coefficient: must be > 0, got -3" in rows[1]["error"]
    assert rows[1]["steps"] is None and rows[1]["ball.penalty_coefficient"] == -3.0


def test_bad_parameters_are_refused_before_running():
    cases = {"ball.colour": "actors[1].colour: unknown field",
             "bal.mass": "no actor named 'bal'",
             "ball.position.w": "'w' must index the array 'position'",
             "ball.mass.x": "'mass' is not an array",
             "mass": "must be ACTOR.FIELD"}
    for name, message in cases.items():
        with pytest.raises(ValueError, match=message.replace("[", r"\[").replace("]", r"\]")):
            sd.sweep(DROP, {name: [1.0]}, workers=0, progress=False)
    with pytest.raises(ValueError, match="must be a number, got string"):
        sd.sweep(DROP, {"ball.mass": ["heavy"]}, workers=0, progress=False)
    with pytest.raises(ValueError, match=r"grid\['ball.mass'\]: must be a list"):
        sd.sweep(DROP, {"ball.mass": 2.0}, workers=0, progress=False)
    with pytest.raises(ValueError, match="track: no actor named 'cube'"):
        sd.sweep(DROP, {"ball.mass": [1.0]}, workers=0, track=["cube"], progress=False)
    with pytest.raises(ValueError, match="workers: must be an integer >= 0"):
        sd.sweep(DROP, {"ball.mass": [1.0]}, workers=-1, duration=0.01, progress=False)


class StepCounter:
    """A measure: counts the steps with active contact samples and the largest sample count."""

    def __init__(self, scene_file):
        self.actors = len(scene_file.actor_names)
        self.contact_steps = self.most_samples = 0

    def step(self, report):
        self.contact_steps += report.active_samples > 0
        self.most_samples = max(self.most_samples, report.active_samples)

    def figures(self):
        return {"contact_steps": self.contact_steps, "most_samples": self.most_samples,
                "actors": self.actors}


def test_csv_png_track_measure_and_settings(tmp_path):
    grid = {"settings.integrator": ["BDF2", "BackwardEuler"], "ball.position.z": [0.6, 1.5]}
    rows = sd.sweep(DROP, grid, workers=0, duration=0.5, track=["ball"], measure=StepCounter,
                    csv=tmp_path / "s.csv", png=tmp_path / "s.png", x="ball.position.z",
                    y="ball.final_z", trajectories=tmp_path / "traj", progress=False)
    assert [(r["settings.integrator"], r["ball.position.z"]) for r in rows] == \
           [("BDF2", 0.6), ("BDF2", 1.5), ("BackwardEuler", 0.6), ("BackwardEuler", 1.5)]
    # Dropped from 0.5 m above the plane the ball lands at t = 0.32 s; from 1.4 m it is still
    # falling at 0.5 s (free fall from 1.4 m lasts 0.53 s).
    assert [r["contact_steps"] > 0 for r in rows] == [True, False, True, False]
    assert all(r["actors"] == 2 for r in rows)
    assert rows[1]["ball.final_z"] == pytest.approx(1.5 - 9.81 * 0.5 ** 2 / 2, abs=1e-3)
    with open(tmp_path / "s.csv") as f:
        read = list(csv.DictReader(f))
    assert [float(r["ball.final_z"]) for r in read] == [r["ball.final_z"] for r in rows]
    assert [r["state_digest"] for r in read] == [r["state_digest"] for r in rows]
    assert (tmp_path / "s.png").read_bytes()[:8] == b"\x89PNG\r\n\x1a\n"
    assert sorted(os.listdir(tmp_path / "traj")) == [f"run_000{i}.jsonl" for i in range(4)]


def test_fit_batch_on_two_workers_recovers_each_trajectory(tmp_path):
    # Two synthetic measurements of the thrown box (friction 0.3 and 0.5), as trajectories.
    truth = [0.3, 0.5]
    made = sd.sweep(THROW, {"box.coulomb_friction_coefficient": truth}, workers=0,
                    trajectories=tmp_path, progress=False)
    observed = [r["trajectory"] for r in made] + [str(tmp_path / "missing.jsonl")]
    with pytest.raises(ValueError, match="observed: no file"):
        sd.fit_batch(THROW, observed, ["box.coulomb_friction_coefficient"], workers=0)
    with pytest.raises(ValueError, match="box.friction"):
        sd.fit_batch(THROW, observed[:2], ["box.friction"], workers=0)
    params = ["box.coulomb_friction_coefficient"]
    parallel = sd.fit_batch(THROW, observed[:2], params, workers=2, csv=tmp_path / "f.csv",
                            png=tmp_path / "f.png", progress=False)
    assert [r["status"] for r in parallel] == ["ok", "ok"]
    assert [r[params[0]] for r in parallel] == pytest.approx(truth, rel=1e-6)
    assert all(r[params[0] + ".initial"] == 0.6 for r in parallel)
    serial = sd.fit_batch(THROW, observed[:2], params, workers=0, progress=False)
    assert deterministic(parallel) == deterministic(serial)
    assert (tmp_path / "f.png").stat().st_size > 0


CLI = os.environ.get("SUPERDEX_CLI")


@pytest.mark.skipif(not CLI, reason="SUPERDEX_CLI (the superdex executable) is not set")
def test_cli_sweep_runs_the_python_package_on_workers(tmp_path):
    args = [CLI, "sweep", DROP, "--set", f"ball.{CN}=0.5,2", "--set", f"ground.{CN}=0.5,2",
            "--zip", "--duration", "0.5", "--workers", "2", "--csv", str(tmp_path / "c.csv"),
            "--png", str(tmp_path / "c.png"), "--quiet"]
    p = subprocess.run(args, capture_output=True, text=True, timeout=300)
    assert p.returncode == 0, p.stderr
    assert f"CSV: {tmp_path / 'c.csv'}" in p.stdout
    with open(tmp_path / "c.csv") as f:
        rows = list(csv.DictReader(f))
    assert [(r[f"ball.{CN}"], r["status"]) for r in rows] == [("0.5", "ok"), ("2", "ok")]
    bad = subprocess.run([CLI, "sweep", DROP, "--set", "ball.colour=1", "--workers", "0"],
                         capture_output=True, text=True, timeout=300)
    assert bad.returncode == 2
    assert "actors[1].colour: unknown field" in bad.stderr
    failing = subprocess.run([CLI, "sweep", DROP, "--set", "ball.penalty_coefficient=1e9,-1",
                              "--duration", "0.01", "--workers", "0", "--quiet",
                              "--csv", str(tmp_path / "f.csv"), "--png", ""],
                             capture_output=True, text=True, timeout=300)
    assert failing.returncode == 3
    assert "run 1: ValueError: actors[1].contact.penalty_coefficient: must be > 0" in \
        failing.stderr
