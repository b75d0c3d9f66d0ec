"""`superdex sweep` and `superdex fit-batch` (the superdex executable runs `python3 -m superdex`).

Exit codes as `superdex run`: 0 every run ok; 2 invalid input; 3 a run failed or did not
converge; 4 a scene expectation failed.
"""
import argparse
import os
import sys
import time

from . import _sweep, _variants

WORKERS_HELP = ("worker processes of a LocalCluster on this machine (default: the CPU count; 0 "
                "runs serially in this process)")


def _add_cluster_options(p):
    g = p.add_mutually_exclusive_group()
    g.add_argument("--workers", type=int, default=None, metavar="N", help=WORKERS_HELP)
    g.add_argument("--scheduler", metavar="ADDRESS",
                   help="an existing dask.distributed scheduler (tcp://HOST:PORT); its workers "
                        "must import superdex and read the scene's files at the same paths")
    p.add_argument("--csv", metavar="FILE", help="the rows (default out/<command>_<scene>.csv)")
    p.add_argument("--png", metavar="FILE",
                   help="the plot (default out/<command>_<scene>.png; '' for none)")
    p.add_argument("--quiet", action="store_true", help="no progress bar")


def _parser():
    top = argparse.ArgumentParser(prog="superdex", description="Sweeps and batch fits on Dask.")
    sub = top.add_subparsers(dest="command", required=True)
    s = sub.add_parser("sweep", help="run variants of a scene file on Dask workers",
                       description="Runs every combination of the --set values (or, with --zip, "
                       "the i-th value of each) and writes one CSV row per run and a PNG plot.")
    s.add_argument("scene", help="scene file (JSON)")
    s.add_argument("--set", dest="sets", action="append", required=True,
                   metavar="ACTOR.FIELD=V1,V2,...",
                   help="values of one parameter: ACTOR is an actor's name or 'settings', FIELD "
                        "a field path (contact parameters and soft material parameters by bare "
                        "name; position.z indexes an array); repeat for more parameters")
    s.add_argument("--zip", action="store_true",
                   help="pair the values of the --set options instead of combining them")
    s.add_argument("--dt", type=float, help="time step [s] (overrides settings.dt)")
    s.add_argument("--duration", type=float, help="simulated time [s] (overrides the file's)")
    s.add_argument("--track", default="", metavar="ACTOR,...",
                   help="actors whose final position and speed become columns")
    s.add_argument("--plot", default="max_penetration_m", metavar="FIGURE",
                   help="the column plotted (default max_penetration_m)")
    s.add_argument("--against", metavar="PARAM", help="the x axis (default: the first --set)")
    s.add_argument("--trajectories", metavar="DIR", help="write each run's trajectory here")
    _add_cluster_options(s)
    f = sub.add_parser("fit-batch", help="fit parameters to several observed trajectories",
                       description="Fits the parameters to each observed trajectory on its own, "
                       "as `superdex fit` does, one fit per Dask task.")
    f.add_argument("scene", help="scene file (JSON): the model and the initial guess")
    f.add_argument("--observed", action="extend", nargs="+", required=True, metavar="TRAJ.jsonl",
                   help="observed trajectories (several, or comma-separated)")
    f.add_argument("--params", required=True, metavar="ACTOR.NAME,...",
                   help="parameters, comma-separated (as `superdex fit`)")
    f.add_argument("--method", default="lm", choices=["lm", "lbfgs"])
    f.add_argument("--max-iterations", type=int, default=50)
    f.add_argument("--dt", type=float, help="time step [s] (overrides settings.dt)")
    _add_cluster_options(f)
    return top


def _outputs(args, command):
    name = os.path.splitext(os.path.basename(args.scene))[0]
    csv = args.csv or os.path.join("out", f"{command}_{name}.csv")
    png = os.path.join("out", f"{command}_{name}.png") if args.png is None else args.png
    return csv, png


def _grid(args):
    sets = [_variants.parse_set(s) for s in args.sets]
    names = [n for n, _ in sets]
    if len(set(names)) != len(names):
        raise ValueError("--set: each parameter may be set once")
    if not args.zip:
        return dict(sets)
    lengths = {len(v) for _, v in sets}
    if len(lengths) != 1:
        raise ValueError("--zip: every --set needs the same number of values, got "
                         + ", ".join(f"{n}: {len(v)}" for n, v in sets))
    return [dict(zip(names, combo)) for combo in zip(*[v for _, v in sets])]


def _print_table(rows, columns):
    def cell(v):
        return f"{v:.6g}" if isinstance(v, float) else "" if v is None else str(v)
    table = [[cell(r.get(c)) for c in columns] for r in rows]
    widths = [max(len(c), *(len(t[i]) for t in table)) for i, c in enumerate(columns)]
    print("  ".join(c.ljust(w) for c, w in zip(columns, widths)))
    for t in table:
        print("  ".join(v.ljust(w) for v, w in zip(t, widths)))


def _exit_code(rows):
    status = {r["status"] for r in rows}
    if status & {"error", "not_converged"}:
        return 3
    return 4 if "expectation_failed" in status else 0


def _report(rows, csv, png, wall, errors):
    ok = sum(r["status"] == "ok" for r in rows)
    for r in rows:
        if r.get("error"):
            errors.append(f"run {r['run']}: {r['error']}")
    print(f"\n{len(rows)} runs: {ok} ok, {len(rows) - ok} not ok; {wall:.1f} s wall")
    print(f"CSV: {csv}")
    if png:
        print(f"PNG: {png}")


def _cmd_sweep(args):
    csv, png = _outputs(args, "sweep")
    grid = _grid(args)
    track = [t for t in args.track.split(",") if t]
    start = time.perf_counter()
    rows = _sweep.sweep(args.scene, grid, workers=args.workers, scheduler=args.scheduler,
                        dt=args.dt, duration=args.duration, track=track,
                        trajectories=args.trajectories, csv=csv, png=png or None,
                        x=args.against, y=args.plot, progress=not args.quiet)
    params = list(grid) if isinstance(grid, dict) else list(grid[0])
    _print_table(rows, ["run", *params, "status", args.plot, "wall_s"])
    errors = []
    _report(rows, csv, png, time.perf_counter() - start, errors)
    return rows, errors


def _cmd_fit_batch(args):
    csv, png = _outputs(args, "fit-batch")
    observed = [p for arg in args.observed for p in arg.split(",") if p]
    params = [p for p in args.params.split(",") if p]
    start = time.perf_counter()
    rows = _sweep.fit_batch(args.scene, observed, params, method=args.method,
                            max_iterations=args.max_iterations, dt=args.dt, workers=args.workers,
                            scheduler=args.scheduler, csv=csv, png=png or None,
                            progress=not args.quiet)
    cols = ["run", "observed"] + [c for p in params for c in (p, f"{p}.std_error")]
    _print_table([{**r, "observed": os.path.basename(r["observed"])} for r in rows],
                 cols + ["status", "rms_residual_m", "iterations", "wall_s"])
    errors = []
    _report(rows, csv, png, time.perf_counter() - start, errors)
    return rows, errors


def main(argv=None):
    args = _parser().parse_args(argv)
    if args.command == "sweep" and args.plot not in _sweep.SWEEP_FIGURES + ("wall_s", "step_wall_s") \
            and not any(args.plot.startswith(t + ".final_") for t in args.track.split(",") if t):
        print(f"error: --plot: must be a figure ({', '.join(_sweep.SWEEP_FIGURES)}, wall_s) or "
              f"ACTOR.final_x|y|z|speed of a --track actor, got {args.plot!r}", file=sys.stderr)
        return 2
    try:
        rows, errors = (_cmd_sweep if args.command == "sweep" else _cmd_fit_batch)(args)
    except ValueError as e:
        print(f"error: {e}", file=sys.stderr)
        return 2
    for e in errors:
        print(f"error: {e}", file=sys.stderr)
    return _exit_code(rows)


if __name__ == "__main__":
    sys.exit(main())
