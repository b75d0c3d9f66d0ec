#!/usr/bin/env python3
"""Fitting friction and normal damping to measured motion: the thrown box of
scenes/data/fit_throw.json against its shipped measurement (centres of mass every 0.02 s with
1 mm noise, made at mu = 0.4, c_n = 4 s/m). Starts from the scene's guess (0.6, 1), fits both with
the trajectory gradient, prints the values with their standard errors, and plots the measured
positions against the simulations before and after the fit.

Usage: PYTHONPATH=build/python /usr/bin/python3 examples/example_fit.py [PNG]
"""
import json
import os
import sys

import numpy as np

import superdex as sd
from plotting import save_figure

ROOT = os.path.join(os.path.dirname(os.path.abspath(__file__)), "..")
SCENE = os.path.join(ROOT, "scenes", "data", "fit_throw.json")
OBSERVED = os.path.join(ROOT, "scenes", "data", "fit_throw_observed.jsonl")
PARAMS = ["box.coulomb_friction_coefficient", "box.normal_viscous_damping_coefficient"]


def simulate(values):
    """Centre of mass of the box every step, with the box's (mu, c_n) set to `values`."""
    f = sd.load_scene(SCENE)
    box = f.scene.actor("box")
    c = box.contact_params
    c.coulomb_friction_coefficient, c.normal_viscous_damping_coefficient = values
    box.contact_params = c
    t, p = [0.0], [box.position]
    for _ in range(int(round(f.duration / f.dt))):
        f.scene.step(f.dt)
        t.append(f.scene.time)
        p.append(box.position)
    return np.array(t), np.array(p)


def main():
    png = sys.argv[1] if len(sys.argv) > 1 else os.path.join("out", "example_fit.png")
    with open(OBSERVED) as fh:
        frames = [json.loads(line) for line in fh][1:]
    t_obs = np.array([fr["t"] for fr in frames])
    p_obs = np.array([fr["actors"][1]["p"] for fr in frames])

    r = sd.fit(sd.load_scene(SCENE), PARAMS, observed=OBSERVED)
    for name, v0, v, e in zip(r.names, r.initial, r.fitted, r.standard_error):
        print(f"{name}: {v0:g} -> {v:.4f} +- {e:.4f}")
    print(f"rms residual {r.rms_residual * 1000:.2f} mm, {r.iterations} iterations, "
          f"{r.simulations} simulations, {r.wall_seconds:.2f} s")
    if not r.converged:
        raise SystemExit("fit did not converge: " + r.message)
    # Made at (0.4, 4): the fit must land within three standard errors of it.
    for v, e, truth in zip(r.fitted, r.standard_error, (0.4, 4.0)):
        if abs(v - truth) > 3 * e:
            raise SystemExit(f"fitted {v} is more than 3 sigma from {truth}")

    import matplotlib
    matplotlib.use("Agg")
    import matplotlib.pyplot as plt
    fig, axes = plt.subplots(1, 2, figsize=(10, 4))
    for label, values, style in (("guess", r.initial, "--"), ("fitted", r.fitted, "-")):
        t, p = simulate(values)
        axes[0].plot(t, p[:, 0], style, label=f"{label} mu={values[0]:.3f} c_n={values[1]:.2f}")
        axes[1].plot(t, p[:, 2], style, label=label)
    axes[0].plot(t_obs, p_obs[:, 0], "k.", label="measured (1 mm noise)")
    axes[1].plot(t_obs, p_obs[:, 2], "k.", label="measured")
    axes[0].set_ylabel("x [m]")
    axes[1].set_ylabel("z [m]")
    for ax in axes:
        ax.set_xlabel("t [s]")
    save_figure(fig, png, axes, legend_size=8)


if __name__ == "__main__":
    main()
