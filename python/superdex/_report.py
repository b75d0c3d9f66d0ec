"""The rows of a sweep or a batch fit as a CSV file and as PNG plots."""
import csv
import math
import numbers
import os


def columns(rows):
    """Every key of the rows, in the order of first appearance."""
    seen = {}
    for row in rows:
        for k in row:
            seen.setdefault(k, None)
    return list(seen)


def write_csv(rows, path):
    """One line per row; floats as Python's shortest round-trip text (bit-exact on reading)."""
    os.makedirs(os.path.dirname(path) or ".", exist_ok=True)
    with open(path, "w", newline="") as f:
        w = csv.DictWriter(f, fieldnames=columns(rows), restval="")
        w.writeheader()
        for row in rows:
            w.writerow({k: repr(v) if isinstance(v, float) else v for k, v in row.items()})


def _number(v):
    return isinstance(v, numbers.Real) and not isinstance(v, bool) and math.isfinite(v)


def _pyplot():
    import matplotlib
    matplotlib.use("Agg")
    import matplotlib.pyplot as plt
    return plt


def plot_sweep(rows, x, y, params, path, title):
    """y (a figure) against x (a parameter) for the rows with a number for y; one line per
    combination of the other parameters (those that do not follow x). Non-numeric x values are
    placed as categories."""
    if not rows or x not in rows[0]:
        raise ValueError(f"plot: x must be a swept parameter ({', '.join(params)}), got {x!r}")
    if y not in columns(rows):
        raise ValueError(f"plot: y must be a column of the rows ({', '.join(columns(rows))}), "
                         f"got {y!r}")
    # Parameters that follow x (zipped variants) make no line of their own.
    others = [p for p in params if p != x and
              len({(repr(r.get(x)), repr(r.get(p))) for r in rows}) >
              len({repr(r.get(x)) for r in rows})]
    xs = [r[x] for r in rows]
    categorical = not all(_number(v) for v in xs)
    categories = list(dict.fromkeys(map(str, xs)))
    groups = {}
    for r in rows:
        if _number(r.get(y)):
            key = tuple((p, r.get(p)) for p in others)
            xv = categories.index(str(r[x])) if categorical else r[x]
            groups.setdefault(key, []).append((xv, r[y]))
    plt = _pyplot()
    fig, ax = plt.subplots(figsize=(6.4, 4.5))
    for key, points in groups.items():
        points.sort()
        label = ", ".join(f"{p} = {v}" for p, v in key) or None
        ax.plot([p[0] for p in points], [p[1] for p in points], "o-", label=label)
    if categorical:
        ax.set_xticks(range(len(categories)), categories)
    missing = len(rows) - sum(len(p) for p in groups.values())
    ax.set_title(title + (f" ({missing} runs without a value)" if missing else ""), fontsize=9)
    ax.set_xlabel(x)
    ax.set_ylabel(y)
    ax.grid(alpha=0.3)
    if any(k for k in groups):
        ax.legend(fontsize=7)
    fig.tight_layout()
    os.makedirs(os.path.dirname(path) or ".", exist_ok=True)
    fig.savefig(path, dpi=110)
    plt.close(fig)


def plot_fits(rows, parameters, path, title):
    """Each fitted parameter with its standard error, one point per observed trajectory."""
    plt = _pyplot()
    fig, axes = plt.subplots(len(parameters), 1, figsize=(6.4, 1.0 + 2.2 * len(parameters)),
                             squeeze=False)
    labels = [os.path.basename(str(r["observed"])) for r in rows]
    for ax, name in zip(axes[:, 0], parameters):
        pts = [(i, r.get(name), r.get(name + ".std_error")) for i, r in enumerate(rows)
               if _number(r.get(name))]
        if pts:
            ax.errorbar([p[0] for p in pts], [p[1] for p in pts],
                        yerr=[p[2] if _number(p[2]) else 0.0 for p in pts], fmt="o", capsize=3)
        ax.set_xticks(range(len(rows)), labels, fontsize=7, rotation=20)
        ax.set_xlim(-0.5, len(rows) - 0.5)
        ax.set_ylabel(name, fontsize=8)
        ax.grid(alpha=0.3)
    failed = sum(r.get("status") != "ok" for r in rows)
    axes[0, 0].set_title(title + (f" ({failed} not ok)" if failed else ""), fontsize=9)
    fig.tight_layout()
    os.makedirs(os.path.dirname(path) or ".", exist_ok=True)
    fig.savefig(path, dpi=110)
    plt.close(fig)
