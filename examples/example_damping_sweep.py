#!/usr/bin/env python3
"""Damping parameter sweep (the spec's example): normal viscous damping and restitution.

A 0.2 m, 1 kg cube (k = 1e6 Pa/m, frictionless) is dropped flat from 0.4 m onto a plane for a
sweep of normal_viscous_damping_coefficient c_n. Each run measures the coefficient of
restitution e = rebound speed / impact speed; the plot compares the measured e with the spec's
rational Hunt-Crossley formula at the measured impact speed. The formula is exact for a free
impact; here gravity acts during the contact and takes g T_c off the rebound speed, which
matters most at high damping (long contacts, slow rebounds): measured -1% at c_n = 0.1 s/m,
-9% at 0.8, -28% at 1.6. With gravity off the tests find agreement within 1.1%.

The seven drops run as one superdex.sweep on dask.distributed worker processes (docs/sweeps.md);
a measure object records each run's impact and rebound speeds in its worker.

Usage: PYTHONPATH=build/python /usr/bin/python3 examples/example_damping_sweep.py [PNG]
"""
import os
import sys

import numpy as np

import superdex as sd
from plotting import save_figure

CN = "normal_viscous_damping_coefficient"
CONTACT = {"penalty_coefficient": 1e6, "coulomb_friction_coefficient": 0.0}
SCENE = {
    "format": "superdex-scene/1",
    "description": "A 0.2 m, 1 kg cube dropped flat from 0.4 m onto a plane",
    # BDF2 (second order) is needed to see restitution; the rebound ends by 0.36 s.
    "settings": {"dt": 1e-4, "duration": 0.36, "integrator": "BDF2"},
    "actors": [
        {"name": "ground", "dynamic": False, "shape": {"type": "plane"}, "contact": CONTACT},
        {"name": "cube", "shape": {"type": "box", "size": [0.2, 0.2, 0.2],
                                   "surface_resolution": 2},
         "mass": 1.0, "position": [0.0, 0.0, 0.1 + 0.4], "contact": CONTACT},
    ],
}


class Restitution:
    """Called once per run in the worker: the cube's speed before the first contact step and
    its vertical velocity after the last one."""

    def __init__(self, scene_file):
        self.cube = scene_file.scene.actor("cube")
        self.before = self.cube.velocity[2]
        self.impact = self.rebound = None

    def step(self, report):
        if report.active_samples > 0 and self.impact is None:
            self.impact = -self.before
        elif report.active_samples == 0 and self.impact is not None and self.rebound is None:
            self.rebound = self.cube.velocity[2]
        self.before = self.cube.velocity[2]

    def figures(self):
        if self.rebound is None:
            raise RuntimeError("no rebound within the run")
        return {"impact_speed": self.impact, "restitution": self.rebound / self.impact}


def main():
    png = sys.argv[1] if len(sys.argv) > 1 else os.path.join("out", "example_damping_sweep.png")
    sweep = [0.0, 0.05, 0.1, 0.2, 0.4, 0.8, 1.6]
    # The pair's c_n is the geometric mean of the two actors' values: give both the same.
    rows = sd.sweep(SCENE, [{f"ground.{CN}": cn, f"cube.{CN}": cn} for cn in sweep],
                    measure=Restitution, workers=2, progress=False)
    results = []
    for r in rows:
        if r["status"] != "ok":
            raise RuntimeError(f"c_n = {r[f'cube.{CN}']}: {r['status']} {r['error']}")
        cn, v, e = r[f"cube.{CN}"], r["impact_speed"], r["restitution"]
        formula = sd.hunt_crossley_restitution_from_damping(cn, v)
        results.append((cn, v, e, formula))
        print(f"c_n = {cn:5.2f} s/m: impact {v:.3f} m/s, e measured {e:.4f}, "
              f"formula {formula:.4f} ({100 * (e - formula) / formula:+.2f}%)")
    import matplotlib
    matplotlib.use("Agg")
    import matplotlib.pyplot as plt
    v = float(np.mean([r[1] for r in results]))
    grid = np.linspace(0.0, max(sweep), 200)
    fig, ax = plt.subplots(figsize=(6, 4.5))
    ax.plot(grid, [sd.hunt_crossley_restitution_from_damping(c, v) for c in grid],
            label=f"rational formula at v = {v:.2f} m/s")
    ax.plot([r[0] for r in results], [r[2] for r in results], "o", label="superdex (BDF2)")
    ax.set_xlabel("normal_viscous_damping_coefficient c_n [s/m]")
    ax.set_ylabel("coefficient of restitution e")
    save_figure(fig, png, [ax])


if __name__ == "__main__":
    main()
