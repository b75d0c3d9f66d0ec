#!/usr/bin/env python3
"""Friction on an incline: a 0.2 m, 1 kg cube on a 30 degree slope for several Coulomb
coefficients. Below tan 30 = 0.577 it slides with a = g (sin30 - mu cos30); above, the
regularized friction holds it up to a creep at the speed where mu cos30 rho'(v) = sin30.

Usage: PYTHONPATH=build/python /usr/bin/python3 examples/example_incline.py [PNG]
"""
import math
import os
import sys

import numpy as np

import superdex as sd
from plotting import save_figure


def run(mu, duration=1.5, dt=1e-3):
    th = math.pi / 6
    n = np.array([math.sin(th), 0.0, math.cos(th)])
    down = np.array([math.cos(th), 0.0, -math.sin(th)])
    scene = sd.Scene()
    ground = sd.RigidActorDesc("incline", sd.RigidShape.plane(n), dynamic=False)
    cube = sd.RigidActorDesc("cube", sd.RigidShape.box([0.2, 0.2, 0.2], surface_resolution=2))
    cube.mass = 1.0
    cube.orientation = [0.0, math.sin(th / 2), 0.0, math.cos(th / 2)]
    cube.position = n * (0.1 + 1e-5)
    for d in (ground, cube):
        d.contact.coulomb_friction_coefficient = mu
        d.contact.normal_viscous_damping_coefficient = 1.0
    scene.add_rigid_actor(ground)
    scene.add_rigid_actor(cube)
    traj = scene.run(duration, dt, every=10)
    return traj["t"], (traj["p"][:, 1] - traj["p"][0, 1]) @ down, th


def main():
    png = sys.argv[1] if len(sys.argv) > 1 else os.path.join("out", "example_incline.png")
    import matplotlib
    matplotlib.use("Agg")
    import matplotlib.pyplot as plt
    fig, ax = plt.subplots(figsize=(6, 4.5))
    for mu in (0.2, 0.4, 0.5, 0.7):
        t, s, th = run(mu)
        a = 9.81 * (math.sin(th) - mu * math.cos(th))
        print(f"mu = {mu}: {s[-1] * 1000:.1f} mm in {t[-1]:.1f} s"
              + (f" (Coulomb: {0.5 * a * t[-1] ** 2 * 1000:.1f} mm)" if a > 0 else " (holds)"))
        ax.plot(t, s, label=f"mu = {mu}")
    ax.set_xlabel("t [s]")
    ax.set_ylabel("distance down the slope [m]")
    save_figure(fig, png, [ax])


if __name__ == "__main__":
    main()
