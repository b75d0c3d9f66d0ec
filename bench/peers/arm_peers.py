#!/usr/bin/env python3
"""superdex against MuJoCo on a swinging three-link URDF arm, speed against error.

    /usr/bin/python3 bench/peers/arm_peers.py --build BUILD [--quick] [--out DIR]

Both engines load scenes/data/robots/three_link_arm.urdf (MuJoCo compiles URDF; superdex reads it
with liburdfdom, scenes/data/arm_swing.json), release it horizontal and let it swing for 2 s
(quick: 1 s). The error of a run is the largest joint-angle difference [rad] from a reference,
over the three joints and the samples every 10 ms. The reference is superdex's SymplecticDIRK22
at dt = 1e-5 s; MuJoCo's RK4 at 1e-5 s is compared with it as a check of the two models (printed
first). Runs: superdex BDF2 and SymplecticDIRK22, MuJoCo RK4 and Euler (semi-implicit), dt from
2e-2 to 5e-4 s. Writes DIR/arm.md (the table, also printed) and DIR/arm.json; the ratio line
compares wall seconds per simulated second at equal error as sweep_peers.py does.
"""
import argparse
import json
import os
import re
import subprocess
import sys
import tempfile

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
import sweep_peers as sp  # noqa: E402  (the Pareto-front comparison)

SOURCE = os.path.dirname(os.path.dirname(os.path.dirname(os.path.abspath(__file__))))
URDF = os.path.join(SOURCE, "scenes", "data", "robots", "three_link_arm.urdf")
SCENE = os.path.join(SOURCE, "scenes", "data", "arm_swing.json")
EVERY = 0.01
DTS = [2e-2, 1e-2, 5e-3, 2e-3, 1e-3, 5e-4]
REF_DT = 1e-5


def run_superdex(build, integrator, dt, duration, tmp):
    traj = os.path.join(tmp, f"arm_{integrator}_{dt:g}.jsonl")
    with open(SCENE) as f:
        sj = json.load(f)
    sj["actors"][0]["urdf"] = URDF
    sj["output"] = {"path": traj, "every": max(1, int(round(EVERY / dt)))}
    variant = os.path.join(tmp, "arm.json")
    with open(variant, "w") as f:
        json.dump(sj, f)
    cmd = [os.path.join(build, "scenes", "superdex"), "run", variant, "--dt", repr(dt),
           "--duration", repr(duration), "--integrator", integrator, "--out", traj, "--quiet"]
    p = subprocess.run(cmd, capture_output=True, text=True)
    wall = re.search(r"wall time\s+([0-9.eE+-]+) s", p.stdout)
    newton = re.search(r"Newton iterations\s+([0-9.eE+-]+) per step", p.stdout)
    if p.returncode != 0 or not wall:
        return dict(engine=f"superdex {integrator}", dt=dt, failed=True,
                    failure=(p.stderr or p.stdout)[-300:])
    samples = []
    with open(traj) as f:
        f.readline()
        for line in f:
            fr = json.loads(line)
            samples.append([fr["t"]] + fr["actors"][0]["joint_positions"])
    os.remove(traj)
    return dict(engine=f"superdex {integrator}", dt=dt, wall=float(wall.group(1)),
                newton=float(newton.group(1)) if newton else None, samples=samples)


def run_mujoco(build, integrator, dt, duration):
    cmd = [os.path.join(build, "bench", "peers", "superdex_peer_mujoco_urdf"), "--urdf", URDF,
           "--dt", repr(dt), "--duration", repr(duration), "--every", repr(EVERY),
           "--integrator", integrator]
    p = subprocess.run(cmd, capture_output=True, text=True)
    if p.returncode != 0:
        return dict(engine=f"MuJoCo {integrator}", dt=dt, failed=True, failure=p.stdout[-300:])
    r = json.loads(p.stdout)
    return dict(engine=f"MuJoCo {integrator}", dt=dt, wall=r["wall_seconds"],
                samples=r["samples"])


def error(samples, ref):
    """Largest joint-angle difference at the reference's sample times (matched to 1e-9 s)."""
    at = {round(s[0] / EVERY): s[1:] for s in ref}
    worst = 0.0
    for s in samples:
        k = round(s[0] / EVERY)
        if k in at and abs(s[0] - k * EVERY) < 1e-9:
            worst = max(worst, max(abs(a - b) for a, b in zip(s[1:], at[k])))
    return worst


def main():
    ap = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    ap.add_argument("--build", default="build")
    ap.add_argument("--quick", action="store_true")
    ap.add_argument("--out", default="out/peers")
    a = ap.parse_args()
    duration = 1.0 if a.quick else 2.0
    os.makedirs(a.out, exist_ok=True)
    with tempfile.TemporaryDirectory() as tmp:
        ref = run_superdex(a.build, "SymplecticDIRK22", REF_DT, duration, tmp)
        if ref.get("failed"):
            sys.exit("reference failed: " + ref["failure"])
        check = run_mujoco(a.build, "rk4", REF_DT, duration)
        runs = []
        for dt in DTS:
            for integ in ("BDF2", "SymplecticDIRK22"):
                runs.append(run_superdex(a.build, integ, dt, duration, tmp))
            for integ in ("rk4", "euler"):
                runs.append(run_mujoco(a.build, integ, dt, duration))
    for r in runs:
        if not r.get("failed"):
            r["error"] = error(r["samples"], ref["samples"])
            r["wall_per_simulated_second"] = r["wall"] / duration
    lines = [f"# Swinging three-link URDF arm ({duration:g} s), error = largest joint-angle "
             f"difference [rad] from superdex SymplecticDIRK22 at dt = {REF_DT:g} s", ""]
    if not check.get("failed"):
        lines.append(f"Models agree: MuJoCo RK4 at dt = {REF_DT:g} s differs from the reference by "
                     f"{error(check['samples'], ref['samples']):.3g} rad at most.")
        lines.append("")
    lines += ["| engine | dt [s] | wall s per simulated s | Newton/step | error [rad] |",
              "|---|---|---|---|---|"]
    for r in runs:
        if r.get("failed"):
            lines.append(f"| {r['engine']} | {r['dt']:g} | failed: {r['failure'][:60]} | | |")
        else:
            lines.append(f"| {r['engine']} | {r['dt']:g} | {r['wall_per_simulated_second']:.3g} | "
                         f"{sp.fmt(r.get('newton'))} | {r['error']:.3g} |")
    lines.append("")
    curves = {}
    for r in runs:
        if not r.get("failed"):
            curves.setdefault(r["engine"], []).append((r["wall_per_simulated_second"], r["error"]))
    for s_name in ("superdex BDF2", "superdex SymplecticDIRK22"):
        for p_name in ("MuJoCo rk4", "MuJoCo euler"):
            lines.append(sp.ratio_line(s_name, sp.front(curves.get(s_name, [])), p_name,
                                       sp.front(curves.get(p_name, []))))
    text = "\n".join(lines) + "\n"
    print(text)
    with open(os.path.join(a.out, "arm.md"), "w") as f:
        f.write(text)
    with open(os.path.join(a.out, "arm.json"), "w") as f:
        json.dump(dict(reference=dict(dt=REF_DT), runs=[{k: v for k, v in r.items() if k != "samples"}
                                                          for r in runs]), f, indent=1)


if __name__ == "__main__":
    main()
