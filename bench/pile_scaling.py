#!/usr/bin/env python3
"""The 1000-sphere pile at 1000, 2000 and 4000 spheres: wall time per sphere and simulated second.

    /usr/bin/python3 bench/pile_scaling.py --build BUILD [--duration S] [--modes explicit_exact,default]

Each pile keeps the shipped one's ten layers and density of spheres (scenes/data/pile.json: a
10 x 10 x 10 grid, 0.11 m apart, in a 1.4 m box): 2000 spheres are a 10 x 20 x 10 grid in a
1.4 x 2.5 m box, 4000 a 20 x 20 x 10 grid in a 2.5 x 2.5 m box. Modes: explicit_exact (explicit
normals, ExactSphere), explicit (explicit normals, sampled spheres), default (the default
dissipation mode, sampled). Prints, per mode and size, superdex_bench_steps' numbers over the run
(wall s per simulated s, Newton median and mean, max penetration, stages not converged) and the
wall time per sphere and simulated second with its ratio to the 1000-sphere pile's.
"""
import argparse
import copy
import json
import os
import re
import subprocess
import tempfile

SOURCE = os.path.dirname(os.path.dirname(os.path.abspath(__file__)))
SIZES = {1000: (10, 10), 2000: (10, 20), 4000: (20, 20)}
MODES = {"explicit_exact": (True, True), "explicit": (True, False), "default": (False, False)}


def pile(n, explicit, exact):
    with open(os.path.join(SOURCE, "scenes", "data", "pile.json")) as f:
        scene = json.load(f)
    nx, ny = SIZES[n]
    sx, sy = 1.4 + 0.11 * (nx - 10), 1.4 + 0.11 * (ny - 10)  # inner width grows with the grid
    walls = {
        "floor": ([sx, sy, 0.1], [0, 0, -0.05]),
        "wall_x0": ([0.1, sy, 1.2], [-sx / 2, 0, 0.6]),
        "wall_x1": ([0.1, sy, 1.2], [sx / 2, 0, 0.6]),
        "wall_y0": ([sx - 0.1, 0.1, 1.2], [0, -sy / 2, 0.6]),
        "wall_y1": ([sx - 0.1, 0.1, 1.2], [0, sy / 2, 0.6]),
    }
    for actor in scene["actors"]:
        if actor["name"] in walls:
            actor["shape"]["size"], actor["position"] = walls[actor["name"]]
        if "grid" in actor:
            actor["grid"]["count"] = [nx, ny, 10]
            actor["position"] = [-0.055 * (nx - 1), -0.055 * (ny - 1), 0.1]
            if exact:
                actor["surface_integral"] = "ExactSphere"
    if explicit:
        scene["settings"]["experimental_eval_params"] = {"explicit_normals": True}
    scene.pop("output", None)
    scene.pop("expect", None)
    return scene


def run(build, path, duration):
    p = subprocess.run([os.path.join(build, "bench", "superdex_bench_steps"), path, "--duration",
                        repr(duration)], capture_output=True, text=True)
    row = next((line for line in p.stdout.splitlines() if line.startswith("all ")), None)
    if p.returncode != 0 or row is None:
        return None
    f = row.split()
    return dict(steps=int(f[1]), median=float(f[2]), mean=float(f[3]), max=int(f[4]),
                unconverged=int(f[7]), penetration_mm=float(f[8]), wall=float(f[9]))


def main():
    ap = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    ap.add_argument("--build", default="build")
    ap.add_argument("--duration", type=float, default=2.0)
    ap.add_argument("--modes", default="explicit_exact,default")
    a = ap.parse_args()
    print(f"| mode | spheres | wall s per sim s | per sphere [ms per sim s] | ratio to 1000 | Newton median / mean | max pen. [mm] | not converged |")
    print("|---|---|---|---|---|---|---|---|")
    with tempfile.TemporaryDirectory() as tmp:
        for mode in a.modes.split(","):
            base = None
            for n in SIZES:
                path = os.path.join(tmp, f"pile{n}_{mode}.json")
                with open(path, "w") as f:
                    json.dump(pile(n, *MODES[mode]), f)
                r = run(a.build, path, a.duration)
                if r is None:
                    print(f"| {mode} | {n} | failed | | | | | |")
                    continue
                per_sim = r["wall"] / a.duration
                per_sphere = per_sim / n
                base = base or per_sphere
                print(f"| {mode} | {n} | {per_sim:.3g} | {1e3 * per_sphere:.3g} | "
                      f"{per_sphere / base:.2f} | {r['median']:g} / {r['mean']:.2f} | "
                      f"{r['penetration_mm']:.2f} | {r['unconverged']} |", flush=True)


if __name__ == "__main__":
    main()
