#!/usr/bin/env python3
"""Sweep wall time: serial against dask.distributed workers (docs/benchmarks.md, "Sweeps").

Runs the same variants of a scene back to back: serially in this process, on a LocalCluster of
worker processes (its start inside the timed call, as `superdex sweep` pays it), on the same
kind of cluster already running, and on one worker process with that many threads (whether the
runs hold the GIL). Prints a table of wall times, their ratio to the serial time and whether
every row equals the serial one bit for bit (all columns but the wall times), the load average
before and after, and a control: the same pure-Python loop twice in one process against once in
each of two processes (about 0.5x on two free cores; near 1x or above when other work holds
the cores, and then no sweep can gain either). The must-hold: 20 variants on 2 workers in at most 0.6x the serial
wall time.

Usage: PYTHONPATH=build/python /usr/bin/python3 bench/bench_sweep.py
           [--scene scenes/data/stack.json] [--runs 20] [--workers 2] [--dt 0.001]
           [--duration 5]
"""
import argparse
import logging
import multiprocessing
import os
import time

import superdex as sd

HERE = os.path.dirname(os.path.abspath(__file__))


def deterministic(rows):
    return [{k: v for k, v in r.items() if not k.endswith("wall_s")} for r in rows]


def spin(n):
    x = 0
    for i in range(n):
        x += i
    return x


def control(workers, n=20_000_000):
    """Wall time of `workers` loops in `workers` processes over that of the same loops in one."""
    start = time.perf_counter()
    for _ in range(workers):
        spin(n)
    serial = time.perf_counter() - start
    with multiprocessing.get_context("spawn").Pool(workers) as pool:
        pool.map(spin, [1] * workers)  # processes started before timing
        start = time.perf_counter()
        pool.map(spin, [n] * workers)
        return (time.perf_counter() - start) / serial


def timed(label, call):
    start = time.perf_counter()
    rows = call()
    return label, time.perf_counter() - start, rows


def main():
    ap = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    ap.add_argument("--scene", default=os.path.join(HERE, "..", "scenes", "data", "stack.json"))
    ap.add_argument("--runs", type=int, default=20)
    ap.add_argument("--workers", type=int, default=2)
    ap.add_argument("--dt", type=float, default=0.001)
    ap.add_argument("--duration", type=float, default=5.0)
    args = ap.parse_args()
    from distributed import Client, LocalCluster

    # The stack of ten boxes with its top box pushed sideways at 0 ... 0.95 m/s.
    grid = {"box9.velocity.x": [0.05 * i for i in range(args.runs)]}
    common = dict(dt=args.dt, duration=args.duration, progress=False)
    load_before, control_before = os.getloadavg(), control(args.workers)
    results = [timed("serial, in this process", lambda: sd.sweep(args.scene, grid, workers=0,
                                                                  **common))]
    results.append(timed(f"{args.workers} worker processes, cluster started in the call",
                         lambda: sd.sweep(args.scene, grid, workers=args.workers, **common)))
    kinds = ((f"{args.workers} worker processes, cluster already running",
              dict(n_workers=args.workers, threads_per_worker=1, processes=True,
                   host="127.0.0.1")),
             (f"1 worker process with {args.workers} threads, already running",
              dict(n_workers=1, threads_per_worker=args.workers, processes=False)))
    for label, kind in kinds:
        # (threads: the in-process transport, no network)
        with LocalCluster(dashboard_address=None, silence_logs=logging.ERROR,
                          **kind) as cluster, Client(cluster) as client:
            results.append(timed(label, lambda: sd.sweep(args.scene, grid, client=client,
                                                         **common)))
    load_after, control_after = os.getloadavg(), control(args.workers)

    serial_time, serial_rows = results[0][1], deterministic(results[0][2])
    ok = sum(r["status"] == "ok" for r in results[0][2])
    print(f"{args.runs} variants of {os.path.basename(args.scene)} (dt {args.dt} s, "
          f"{args.duration} s each; {ok} ok), {os.cpu_count()} cores\n")
    print(f"| {'mode':<58} | wall [s] | x serial | rows equal serial |")
    print(f"|{'-' * 60}|---------:|---------:|:------------------|")
    for label, wall, rows in results:
        same = "yes" if deterministic(rows) == serial_rows else "NO"
        print(f"| {label:<58} | {wall:8.2f} | {wall / serial_time:8.3f} | {same:<17} |")
    print(f"\nload average (1, 5, 15 min) before {load_before[0]:.2f} {load_before[1]:.2f} "
          f"{load_before[2]:.2f}, after {load_after[0]:.2f} {load_after[1]:.2f} "
          f"{load_after[2]:.2f}")
    print(f"control: {args.workers} pure-Python loops in {args.workers} processes take "
          f"{control_before:.2f}x (before), {control_after:.2f}x (after) their serial time")
    ratio = results[1][1] / serial_time
    print(f"must hold: {args.workers} workers (cluster start included) at most 0.6x serial: "
          f"{ratio:.3f}x {'holds' if ratio <= 0.6 else 'DOES NOT HOLD'}")


if __name__ == "__main__":
    main()
