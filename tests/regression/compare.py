#!/usr/bin/env python3
"""Compares two trajectory recordings of superdex_regression_record (tests/regression/README.md).

    python3 tests/regression/compare.py BASELINE_DIR CURRENT_DIR [--tol 1e-9]

Per step: the Newton iterations, stages, free stages, fallbacks and status must be equal, and the
packed state (positions and velocities of every dynamic actor) must agree to
max|a - b| <= tol * max|a| (relative to the largest entry of the baseline's state at that step).
Prints one line per recording and exits 1 if any differs.
"""
import argparse
import os
import sys


def load(path):
    rows = []
    with open(path) as f:
        for line in f:
            parts = line.split()
            rows.append(([int(x) for x in parts[:5]], [float(x) for x in parts[5:]]))
    return rows


def main():
    ap = argparse.ArgumentParser()
    ap.add_argument("baseline")
    ap.add_argument("current")
    ap.add_argument("--tol", type=float, default=1e-9)
    a = ap.parse_args()
    names = sorted(n for n in os.listdir(a.baseline) if n.endswith(".txt"))
    bad = 0
    for name in names:
        cur = os.path.join(a.current, name)
        if not os.path.exists(cur):
            print(f"MISSING {name}")
            bad += 1
            continue
        base, now = load(os.path.join(a.baseline, name)), load(cur)
        worst, first_count, first_state = 0.0, None, None
        if len(base) != len(now):
            print(f"DIFFER  {name}: {len(base)} vs {len(now)} steps")
            bad += 1
            continue
        for i, ((cb, sb), (cn, sn)) in enumerate(zip(base, now)):
            if cb != cn and first_count is None:
                first_count = (i, cb, cn)
            if len(sb) != len(sn):
                first_state = first_state or i
                continue
            scale = max((abs(x) for x in sb), default=0.0) or 1.0
            err = max((abs(x - y) for x, y in zip(sb, sn)), default=0.0) / scale
            worst = max(worst, err)
            if err > a.tol and first_state is None:
                first_state = i
        ok = first_count is None and first_state is None
        bad += not ok
        msg = f"{'same   ' if ok else 'DIFFER '} {name}: {len(base)} steps, max relative state difference {worst:.2e}"
        if first_count is not None:
            i, cb, cn = first_count
            msg += f"; counts differ first at step {i}: {cb} vs {cn} (iterations, stages, free, fallbacks, status)"
        if first_state is not None:
            msg += f"; state beyond {a.tol:g} first at step {first_state}"
        print(msg)
    print(f"{len(names) - bad} of {len(names)} recordings match")
    return 1 if bad else 0


if __name__ == "__main__":
    sys.exit(main())
