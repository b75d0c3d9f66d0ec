#!/usr/bin/env python3
"""A cloth dropped on a sphere, with self-contact (the PointCloud collider): wall seconds per
simulated second, Newton iterations per step and the stages' outcome, at two time steps, and how
the cost grows with the triangle count.

  /usr/bin/python3 bench/cloth_on_sphere.py [--build build] [--duration 0.2] [--sizes 35 71 141]

The scene: a 0.6 m square cloth (n × n cells, 2 n² triangles: 35 → 2450, 71 → 10082,
141 → 39762), E = 1e6 Pa, ν = 0.3, h = 0.5 mm, ρ = 200 kg/m³ (0.1 kg/m²), hinge bending, its
point cloud of radius L_B = max(6 mm, 1.2 h_cell) with self-contact, k = 1e7 Pa/m, ε = 2 mm,
μ = 0.3, released 2 cm above a static sphere of radius 0.15 m resting on the ground; BDF2 with
the current load for the dissipation (implicit_normal_force_for_dissipation, the spec's advice
for point clouds). The cloth lands at about 0.065 s: the default duration covers the landing and
the first draping. Prints one row per run; the first table at 10082 triangles (dt 5 ms and
2.5 ms), the second the sizes at dt 5 ms with the cost per triangle relative to the smallest.
"""
import argparse
import json
import os
import re
import subprocess
import sys
import tempfile
import time

ROOT = os.path.dirname(os.path.dirname(os.path.abspath(__file__)))


def scene(n, duration):
    """The scene file of an n × n-cell cloth, as a dict."""
    size = 0.6
    radius = max(0.006, 1.2 * size / n)
    ramp = {"penalty_smoothing_half_distance": 0.002}
    return {
        "format": "superdex-scene/1",
        "description": f"A {size} m cloth of {2 * n * n} triangles dropped on a sphere "
                       "(bench/cloth_on_sphere.py).",
        "settings": {"dt": 0.005, "duration": duration, "integrator": "BDF2",
                     "experimental_eval_params": {"implicit_normal_force_for_dissipation": True}},
        "actors": [
            {"name": "ground", "dynamic": False, "shape": {"type": "plane", "normal": [0, 0, 1]},
             "contact": ramp},
            {"name": "ball", "dynamic": False, "shape": {"type": "sphere", "radius": 0.15},
             "position": [0, 0, 0.15], "contact": ramp},
            {"name": "cloth", "type": "shell",
             "mesh": {"type": "rectangle", "size": [size, size], "cells": [n, n]},
             "material": {"youngs_modulus": 1e6, "poisson_ratio": 0.3, "density": 200,
                          "thickness": 0.0005},
             "bending": "Hinge", "position": [0, 0, 0.32],
             "contact": {"penalty_coefficient": 1e7, "penalty_smoothing_half_distance": 0.002,
                         "coulomb_friction_coefficient": 0.3},
             "point_cloud": {"radius": radius, "self_contact": True}},
        ],
    }


def run(build, n, dt, duration):
    """Runs the scene; returns (wall s per simulated s, Newton per step, (converged, stopped,
    diverged), max penetration [mm], fallbacks)."""
    with tempfile.TemporaryDirectory() as tmp:
        path = os.path.join(tmp, f"cloth_{n}.json")
        json.dump(scene(n, duration), open(path, "w"))
        cmd = [os.path.join(build, "scenes", "superdex"), "run", path, "--dt", str(dt),
               "--out", os.path.join(tmp, "t.jsonl"), "--quiet"]
        text = subprocess.run(cmd, capture_output=True, text=True).stdout
        wall = float(re.search(r"\(([0-9.e+-]+) s per simulated second", text).group(1))
        newton = float(re.search(r"Newton iterations ([0-9.e+-]+) per step", text).group(1))
        stages = re.search(r"stages\s+(\d+) converged, (\d+) stopped, (\d+) diverged", text)
        pen = re.search(r"max penetration\s+([0-9.e+-]+) mm", text)
        fallbacks = re.search(r"fallbacks\s+(\d+) stages", text)
        return (wall, newton, stages.groups(), float(pen.group(1)) if pen else 0.0,
                int(fallbacks.group(1)) if fallbacks else 0)


def main():
    p = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    p.add_argument("--build", default=os.path.join(ROOT, "build"))
    p.add_argument("--duration", type=float, default=0.2, help="simulated time [s]")
    p.add_argument("--sizes", type=int, nargs="+", default=[35, 71, 141],
                   help="cells per side (2 n² triangles)")
    args = p.parse_args()
    head = (f"{'triangles':>9} {'dt [s]':>7} {'wall s/s':>9} {'Newton/step':>11} "
            f"{'conv/stop/div':>13} {'fallbacks':>9} {'max pen. [mm]':>13}")
    print(f"Time steps (10082 triangles, {args.duration} s simulated)")
    print(head)
    for dt in (0.005, 0.0025):
        wall, newton, stages, pen, fb = run(args.build, 71, dt, args.duration)
        print(f"{2 * 71 * 71:9d} {dt:7.4f} {wall:9.1f} {newton:11.2f} {'/'.join(stages):>13} "
              f"{fb:9d} {pen:13.3f}")
        sys.stdout.flush()
    print(f"\nScaling (dt 0.005 s, {args.duration} s simulated)")
    print(head + f" {'per triangle (rel.)':>19}")
    base = None
    for n in args.sizes:
        wall, newton, stages, pen, fb = run(args.build, n, 0.005, args.duration)
        per = wall / (2 * n * n)
        base = base or per
        print(f"{2 * n * n:9d} {0.005:7.4f} {wall:9.1f} {newton:11.2f} {'/'.join(stages):>13} "
              f"{fb:9d} {pen:13.3f} {per / base:19.2f}")
        sys.stdout.flush()


if __name__ == "__main__":
    main()
