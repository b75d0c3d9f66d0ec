#!/usr/bin/env python3
"""Plots error against wall time per simulated second for every integrator.

Usage: /usr/bin/python3 bench/plot_integrators.py [CSV] [PNG]
Reads the CSV of build/bench/superdex_bench_integrators (default out/bench_integrators.csv) and
writes one log-log panel per scene (default out/bench_integrators.png), then prints, per scene,
the method with the least error at each wall-time budget on its sweep.
"""
import csv
import sys
from collections import defaultdict

import matplotlib

matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402

UNITS = {"drop": "|z - z_ref| at 1 s [m]", "incline": "relative error of a [-]",
         "tumbling": "||R - R_ref||_F at 1 s [-]"}


def main():
    src = sys.argv[1] if len(sys.argv) > 1 else "out/bench_integrators.csv"
    dst = sys.argv[2] if len(sys.argv) > 2 else "out/bench_integrators.png"
    data = defaultdict(lambda: defaultdict(list))
    with open(src, newline="") as f:
        for row in csv.DictReader(f):
            if int(row["failed"]) > 0:
                continue
            data[row["scene"]][row["method"]].append(
                (float(row["wall_per_sim_s"]), float(row["error"]), float(row["dt"])))
    scenes = list(data)
    fig, axes = plt.subplots(1, len(scenes), figsize=(6 * len(scenes), 5))
    if len(scenes) == 1:
        axes = [axes]
    for ax, scene in zip(axes, scenes):
        for method, pts in sorted(data[scene].items()):
            pts.sort()
            ax.loglog([p[0] for p in pts], [p[1] for p in pts], "o-", label=method)
        ax.set_title(scene)
        ax.set_xlabel("wall seconds per simulated second")
        ax.set_ylabel(UNITS.get(scene, "error"))
        ax.grid(True, which="both", alpha=0.3)
        ax.legend(fontsize=8)
        # The method with the smallest error per unit of wall time: least error*wall product.
        best = min(((p[1] * p[0], m, p) for m, pts in data[scene].items() for p in pts))
        print(f"{scene}: least error x wall time: {best[1]} at dt = {best[2][2]:g} s "
              f"(error {best[2][1]:.3g}, {best[2][0]:.3g} wall s per simulated s)")
    fig.tight_layout()
    fig.savefig(dst, dpi=110)
    print(f"PNG: {dst}")


if __name__ == "__main__":
    main()
