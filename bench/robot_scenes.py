#!/usr/bin/env python3
"""The shipped robot scenes (links in contact) timed: wall seconds per simulated second and
Newton iterations per step, at the scene's time step and at two coarser ones, with the error
each time step gives against the scene's own expectation.

  /usr/bin/python3 bench/robot_scenes.py [--build build]

Scenes: gripper_lift.json (a URDF gripper lowers, grasps a 0.2 kg box with 10 N force-limited
fingers and lifts it 10 cm; error: the box's final height against 0.1296 m) and arm_push.json (a
URDF two-link arm pushes a 0.5 kg box along a straight path; error: the box's final x against the
finger's stop, 0.665 m) and soft_pad_grip.json (the gripper with soft-skinned pads on its fingers
lifts the box; error: its final height against 0.1295 m). Prints one table row per scene and
time step.
"""
import argparse
import json
import os
import re
import subprocess
import sys
import tempfile

ROOT = os.path.dirname(os.path.dirname(os.path.abspath(__file__)))
SCENES = [
    # scene, the actor, the coordinate measured, its expected final value [m]
    ("gripper_lift.json", "box", 2, 0.1296),
    ("arm_push.json", "box", 0, 0.665),
    ("soft_pad_grip.json", "box", 2, 0.1295),
]


def run(build, scene, dt):
    """Runs `superdex run` at dt; returns (wall s per simulated s, Newton per step, final frame)."""
    with tempfile.TemporaryDirectory() as tmp:
        out = os.path.join(tmp, "t.jsonl")
        cmd = [os.path.join(build, "scenes", "superdex"), "run",
               os.path.join(ROOT, "scenes", "data", scene), "--dt", str(dt), "--out", out]
        text = subprocess.run(cmd, capture_output=True, text=True).stdout
        wall = float(re.search(r"\(([0-9.e+-]+) s per simulated second", text).group(1))
        newton = float(re.search(r"Newton iterations ([0-9.e+-]+) per step", text).group(1))
        stages = re.search(r"stages\s+(\d+) converged, (\d+) stopped, (\d+) diverged", text)
        lines = open(out).read().splitlines()
        header, last = json.loads(lines[0]), json.loads(lines[-1])
        names = [a["name"] for a in header["actors"]]
        return wall, newton, stages.groups(), names, last


def main():
    p = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    p.add_argument("--build", default=os.path.join(ROOT, "build"))
    args = p.parse_args()
    print(f"{'scene':20} {'dt [s]':>8} {'wall s/s':>9} {'Newton/step':>11} "
          f"{'converged/stopped/diverged':>27} {'error [mm]':>10}")
    for scene, actor, axis, expected in SCENES:
        base = json.load(open(os.path.join(ROOT, "scenes", "data", scene)))["settings"]["dt"]
        for dt in (base, 2 * base, 5 * base):
            wall, newton, stages, names, last = run(args.build, scene, dt)
            value = last["actors"][names.index(actor)]["p"][axis]
            print(f"{scene:20} {dt:8.3g} {wall:9.3f} {newton:11.2f} {'/'.join(stages):>27} "
                  f"{abs(value - expected) * 1e3:10.3f}")
    return 0


if __name__ == "__main__":
    sys.exit(main())
