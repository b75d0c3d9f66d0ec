"""superdex.sweep and superdex.fit_batch: many runs of one scene file on dask.distributed.

Each variant (or fit) is one task; a worker loads the scene from its JSON text, runs it as
`superdex run` does (scenes/runner.h) and returns one row of plain numbers and strings. Rows
come back in the order of the variants whatever the order the workers finish in.
"""
import hashlib
import json
import math
import os
import time

import numpy as np

from . import _cluster, _report, _superdex, _variants

# The figures of a run, in the order of the CSV columns (docs/sweeps.md says what each is).
SWEEP_FIGURES = ("steps", "simulated_time_s", "newton_per_step", "max_newton", "converged",
                 "steps_stopped", "steps_diverged", "fallbacks", "max_penetration_m", "min_det_f",
                 "initial_energy_J", "final_energy_J", "energy_drift_rel", "expectations",
                 "state_digest")
FIT_FIGURES = ("initial_cost", "final_cost", "rms_residual_m", "iterations", "simulations",
               "converged", "message")


def _scene_source(scene):
    """(JSON dict, directory for relative mesh paths, short name) of a scene path or dict."""
    if isinstance(scene, (str, os.PathLike)):
        path = os.fspath(scene)
        try:
            with open(path) as f:
                data = json.load(f)
        except OSError as e:
            raise ValueError(f"scene: cannot read {path}: {e.strerror}") from None
        except ValueError as e:
            raise ValueError(f"scene: {path}: not JSON: {e}") from None
        name = os.path.splitext(os.path.basename(path))[0]
        return data, os.path.dirname(os.path.abspath(path)), name
    if isinstance(scene, dict):
        return json.loads(json.dumps(scene)), os.getcwd(), "scene"
    raise ValueError(f"scene: must be a scene file path or a dict (the file's JSON), got "
                     f"{type(scene).__name__}")


def state_digest(scene):
    """The first 16 hex digits of SHA-256 over every actor's state at full precision: rigid
    position, orientation, velocity, angular velocity; soft node positions and velocities."""
    h = hashlib.sha256()
    for a in scene.actors:
        parts = ((a.node_positions, a.node_velocities) if a.is_soft else
                 (a.position, a.orientation, a.velocity, a.angular_velocity))
        for x in parts:
            h.update(np.ascontiguousarray(x, dtype=np.float64).tobytes())
    return h.hexdigest()[:16]


def _summary_figures(f, s, has_expectations):
    converged = s.stopped + s.diverged == 0
    failures = list(s.expectation_failures)
    e0, e1 = s.initial_energy, s.final_energy
    return {
        "status": "not_converged" if not converged else
                  "expectation_failed" if failures else "ok",
        "steps": s.steps, "simulated_time_s": s.simulated_seconds,
        "newton_per_step": s.newton_iterations / max(s.steps, 1),
        "max_newton": s.max_newton_iterations, "converged": converged,
        "steps_stopped": s.stopped, "steps_diverged": s.diverged, "fallbacks": s.fallbacks,
        "max_penetration_m": s.max_penetration,
        "min_det_f": s.min_det_f if math.isfinite(s.min_det_f) else None,
        "initial_energy_J": e0, "final_energy_J": e1,
        "energy_drift_rel": (e1 - e0) / max(abs(e0), 1e-300),
        "expectations": "; ".join(failures) if failures else
                        "all hold" if has_expectations else "none given",
        "state_digest": state_digest(f.scene), "step_wall_s": s.wall_seconds,
    }


def _tracked(f, names):
    out = {}
    for name in names:
        a = f.scene.actor(name)
        p, v = a.position, a.velocity
        out.update({f"{name}.final_x": p[0], f"{name}.final_y": p[1], f"{name}.final_z": p[2],
                    f"{name}.final_speed": float(np.linalg.norm(v))})
    return {k: float(v) for k, v in out.items()}


def _measured(observer):
    figures = observer.figures() if hasattr(observer, "figures") else {}
    if not isinstance(figures, dict):
        raise TypeError(f"measure: figures() must return a dict, got {type(figures).__name__}")
    return {str(k): v.item() if hasattr(v, "item") else v for k, v in figures.items()}


def _run_variant(task):
    """One variant, in a worker: its row (parameters, status, error, figures, wall time)."""
    start = time.perf_counter()
    row = {"run": task["index"], **task["params"], "status": "error", "error": ""}
    try:
        f = _superdex.load_scene_text(task["text"], task["base_dir"])
        observer = task["measure"](f) if task["measure"] is not None else None
        step = getattr(observer, "step", None)
        s = _superdex.run_scene(f, dt=task["dt"], duration=task["duration"], out=task["out"],
                                vtk="", progress=(lambda r, _: step(r)) if step else None)
        row.update(_summary_figures(f, s, task["has_expectations"]))
        row.update(_tracked(f, task["track"]))
        if observer is not None:
            row.update(_measured(observer))
        if task["out"]:
            row["trajectory"] = task["out"]
    except Exception as e:  # noqa: BLE001  (a failed run is a row with its error)
        row["status"], row["error"] = "error", f"{type(e).__name__}: {e}"
    row["wall_s"] = time.perf_counter() - start
    return row


def _ordered(rows, first, last):
    """The rows with the columns `first`, then the others as they first appear, then `last`;
    a row without a column gets None (an empty CSV cell)."""
    middle = [c for c in _report.columns(rows) if c not in first and c not in last]
    order = list(first) + middle + [c for c in last if any(c in r for r in rows)]
    return [{c: r.get(c) for c in order} for r in rows]


def _sweep_tasks(scene, grid, dt, duration, track, measure, trajectories):
    data, base_dir, name = _scene_source(scene)
    variants = _variants.expand(grid)
    params = _report.columns(variants)
    paths = {n: _variants.resolve(data, n) for n in params}
    for value, label in ((dt, "dt"), (duration, "duration")):
        if value is not None and not (isinstance(value, (int, float)) and value > 0
                                      and math.isfinite(value)):
            raise ValueError(f"{label}: must be a number > 0 [s], got {value!r}")
    if measure is not None and not callable(measure):
        raise ValueError("measure: must be callable as measure(scene_file) (a class with step(report) "
                         "and figures())")
    if isinstance(track, str):
        track = [track]
    expect = data.get("expect") if isinstance(data, dict) else None
    tasks = []
    for i, v in enumerate(variants):
        out = os.path.join(os.path.abspath(trajectories), f"run_{i:04d}.jsonl") if trajectories else ""
        tasks.append({"index": i, "params": v, "base_dir": base_dir, "dt": dt,
                      "duration": duration, "out": out, "track": list(track), "measure": measure,
                      "has_expectations": bool(expect),
                      "text": json.dumps(_variants.apply(data, paths, v))})
    if trajectories:
        os.makedirs(trajectories, exist_ok=True)
    return tasks, params, name


def _check_first(task, track):
    """Loads the first variant here before anything runs: a misspelt actor or field, or a bad
    value in it, fails at once with the loader's JSON path and rule."""
    try:
        f = _superdex.load_scene_text(task["text"], task["base_dir"])
    except ValueError as e:
        raise ValueError(f"the first variant {task['params']} does not load: {e}") from None
    for name in task["track"]:
        if name not in f.actor_names:
            raise ValueError(f"track: no actor named {name!r} (actors: "
                             f"{', '.join(f.actor_names)})")


def sweep(scene, grid, *, workers=None, scheduler=None, client=None, dt=None, duration=None,
          track=(), measure=None, trajectories=None, csv=None, png=None, x=None,
          y="max_penetration_m", progress=True):
    """Runs every variant of a scene file and returns one row (a dict) per run, in grid order.

    scene: a scene file path or its JSON as a dict. grid: {"ACTOR.FIELD": [values]} for every
    combination (the last parameter varies fastest), or a list of {"ACTOR.FIELD": value}
    variants. ACTOR is an actor's name or "settings"; FIELD a path in that object, e.g.
    "ball.normal_viscous_damping_coefficient", "ball.position.z", "settings.integrator".

    Runs on dask.distributed: a LocalCluster of `workers` single-threaded processes (default:
    the CPU count), the scheduler at address `scheduler`, or an existing `client`; workers=0
    runs serially in this process. dt, duration [s] override the file's. track: actor names
    whose final position and speed become columns. measure: a picklable callable, called once
    per run in the worker as measure(scene_file); the object it returns gets step(report) after
    every step, and its figures() dict adds columns. trajectories: a directory for one trajectory
    per run (run_0000.jsonl, ...). csv, png: files to write; the plot shows column y against the
    parameter x (default: the first). A run that fails is a row with status "error" and its
    error; bad parameters raise ValueError before anything runs.
    """
    tasks, params, name = _sweep_tasks(scene, grid, dt, duration, track, measure, trajectories)
    if png and (x or params[0]) not in params:
        raise ValueError(f"x: must be a swept parameter ({', '.join(params)}), got {x!r}")
    _check_first(tasks[0], tasks[0]["track"])

    def failed(i, message):
        return {"run": i, **tasks[i]["params"], "status": "error", "error": message}

    rows = _cluster.run_tasks(_run_variant, tasks, failed, workers=_workers(workers),
                              scheduler=scheduler, client=client, progress=progress, label="runs")
    rows = _ordered(rows, ["run", *params, "status", "error", *SWEEP_FIGURES],
                    ["trajectory", "step_wall_s", "wall_s"])
    if csv:
        _report.write_csv(rows, csv)
    if png:
        _report.plot_sweep(rows, x or params[0], y, params, png, f"superdex sweep: {name}")
    return rows


def _workers(workers):
    return (os.cpu_count() or 1) if workers is None else workers


def _fit_one(task):
    """One fit, in a worker: its row (fitted values, standard errors, costs, convergence)."""
    start = time.perf_counter()
    row = {"run": task["index"], "observed": task["observed"], "status": "error", "error": ""}
    try:
        f = _superdex.load_scene_text(task["text"], task["base_dir"])
        r = _superdex.fit(f, task["parameters"], observed=task["observed"], dt=task["dt"],
                          max_iterations=task["max_iterations"], method=task["method"])
        for n, a, b, se in zip(r.names, r.initial, r.fitted, r.standard_error):
            row.update({n: b, f"{n}.std_error": se, f"{n}.initial": a})
        row.update({"status": "ok" if r.converged else "not_converged",
                    "initial_cost": r.initial_cost, "final_cost": r.final_cost,
                    "rms_residual_m": r.rms_residual,
                    "iterations": r.iterations, "simulations": r.simulations,
                    "converged": r.converged, "message": r.message})
    except Exception as e:  # noqa: BLE001  (a failed fit is a row with its error)
        row["status"], row["error"] = "error", f"{type(e).__name__}: {e}"
    row["wall_s"] = time.perf_counter() - start
    return row


def _fit_tasks(scene, observed, parameters, method, max_iterations, dt):
    data, base_dir, name = _scene_source(scene)
    if isinstance(observed, (str, os.PathLike)):
        observed = [observed]
    observed = [os.path.abspath(os.fspath(p)) for p in observed]
    if not observed:
        raise ValueError("observed: must name at least one trajectory file")
    for p in observed:
        if not os.path.isfile(p):
            raise ValueError(f"observed: no file {p}")
    if isinstance(parameters, str) or not parameters:
        raise ValueError("parameters: must be a non-empty list of 'ACTOR.NAME' strings")
    if method not in ("lm", "lbfgs"):
        raise ValueError(f"method: must be 'lm' or 'lbfgs', got {method!r}")
    if not isinstance(max_iterations, int) or max_iterations < 1:
        raise ValueError(f"max_iterations: must be an integer >= 1, got {max_iterations!r}")
    text = json.dumps(data)
    f = _superdex.load_scene_text(text, base_dir)
    _superdex.ForwardSensitivity(f.scene, list(parameters))  # ValueError naming a bad parameter
    tasks = [{"index": i, "observed": p, "text": text, "base_dir": base_dir,
              "parameters": list(parameters), "method": method,
              "max_iterations": max_iterations, "dt": dt} for i, p in enumerate(observed)]
    return tasks, name


def fit_batch(scene, observed, parameters, *, method="lm", max_iterations=50, dt=None,
              workers=None, scheduler=None, client=None, csv=None, png=None, progress=True):
    """Fits `parameters` of a scene file to each of several observed trajectories (files in the
    trajectory format) independently, one fit per task as superdex.fit does, and returns one row
    per trajectory: the fitted values (column NAME), NAME.std_error, NAME.initial, the costs, the
    RMS residual, iterations, simulations, convergence and wall time. Workers as for sweep; png
    plots each fitted value with its standard error per trajectory. A fit that fails is a row
    with status "error" and its error.
    """
    tasks, name = _fit_tasks(scene, observed, parameters, method, max_iterations, dt)

    def failed(i, message):
        return {"run": i, "observed": tasks[i]["observed"], "status": "error", "error": message}

    rows = _cluster.run_tasks(_fit_one, tasks, failed, workers=_workers(workers),
                              scheduler=scheduler, client=client, progress=progress, label="fits")
    first = ["run", "observed", "status", "error"]
    for p in parameters:
        first += [p, f"{p}.std_error", f"{p}.initial"]
    rows = _ordered(rows, first + list(FIT_FIGURES), ["wall_s"])
    if csv:
        _report.write_csv(rows, csv)
    if png:
        _report.plot_fits(rows, list(parameters), png, f"superdex fit-batch: {name}")
    return rows
