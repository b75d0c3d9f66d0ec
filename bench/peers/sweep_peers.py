#!/usr/bin/env python3
"""Speed against error: superdex, MuJoCo and Bullet on the reference scenes, in one command.

    python3 bench/peers/sweep_peers.py --build BUILD [--quick] [--scenes drop,stack] [--out out/peers]

Sweeps the time step of every engine (superdex: BDF2 and BackwardEuler, each with the default
reconstructed-load dissipation, with explicit normals and with the current load; on the drop and
the pile also with the spheres' penalty integrated exactly, surface_integral ExactSphere),
computes each scene's error metric,
and writes per scene a Markdown table (printed, and saved to OUT/SCENE.md), the raw results
(OUT/SCENE.json) and a log-log plot of error against wall time per simulated second
(OUT/SCENE.png). Each table ends with superdex's wall time over each peer's at equal error,
interpolated log-log along the Pareto fronts of the sweeps.

The peer adapters (BUILD/bench/peers/superdex_peer_*) print their own metrics; superdex's are
computed here from its trajectory with the same definitions (bench/peers/peer_run.cpp).
Standard library and matplotlib only.
"""
import argparse
import json
import math
import os
import re
import subprocess
import sys
import tempfile
import time

HERE = os.path.dirname(os.path.abspath(__file__))
SOURCE = os.path.dirname(os.path.dirname(HERE))

# Dissipation modes (README, "Dissipation modes"): the scene file's experimental_eval_params.
MODES = {"reconstructed": ("reconstructed load", None),
         "explicit": ("explicit normals", {"explicit_normals": True}),
         "current": ("current load", {"implicit_normal_force_for_dissipation": True}),
         # The same modes with every sphere's penalty integrated exactly (surface_integral
         # ExactSphere, docs/scene-format.md), its dissipation on its contact cap where the mode
         # allows.
         "reconstructed_exact": ("reconstructed load, exact spheres", None),
         "explicit_exact": ("explicit normals, exact spheres", {"explicit_normals": True})}
EXACT_SPHERES = {"reconstructed_exact", "explicit_exact"}
SUPERDEX_CURVES = [(i, m) for i in ("BDF2", "BackwardEuler")
                   for m in ("reconstructed", "explicit", "current")]

# Per scene: the error plotted, durations (full, quick), dt sweeps (full, quick) for superdex
# and the peers, and the superdex curves run (all six unless limited).
SCENES = {
    "drop": dict(label="|1 - e| (restitution of the first bounce)", duration=(0.6, 0.6),
                 # Between 1e-2 and 1e-3 the first bounce's error changes by 3-4 decades for
                 # every engine: the full sweep samples that range finely.
                 sdx=([1e-2, 5e-3, 3e-3, 2e-3, 1.5e-3, 1e-3, 5e-4, 3e-4, 1e-4, 3e-5],
                      [1e-2, 3e-3, 1e-3, 3e-4, 1e-4]),
                 # The drop has no damping: the energy-conserving symplectic methods, and BDF2.
                 sdx_curves=([("SymplecticDIRK12", "reconstructed"), ("SymplecticDIRK22", "reconstructed"),
                              ("SymplecticDIRK22", "explicit"), ("BDF2", "reconstructed"),
                              ("SymplecticDIRK22", "reconstructed_exact")],
                             [("SymplecticDIRK12", "reconstructed"), ("SymplecticDIRK22", "reconstructed"),
                              ("BDF2", "reconstructed"), ("SymplecticDIRK22", "reconstructed_exact")]),
                 peer=([1e-2, 5e-3, 3e-3, 2e-3, 1.5e-3, 1e-3, 5e-4, 3e-4, 1e-4, 3e-5],
                       [1e-2, 3e-3, 1e-3, 3e-4, 1e-4])),
    "incline": dict(label="relative error of the sliding acceleration", duration=(2.0, 1.5),
                    sdx=([2e-1, 1e-1, 5e-2, 2e-2, 1e-2, 3e-3, 1e-3, 3e-4], [5e-2, 1e-2, 3e-3, 1e-3]),
                    peer=([5e-2, 2e-2, 1e-2, 3e-3, 1e-3, 3e-4, 1e-4], [2e-2, 1e-2, 3e-3, 1e-3, 3e-4])),
    # Creep speed once settled; the regularized friction creeps at v = V_f (1 - sqrt(1 - tan θ/μ))
    # = 0.58 V_f here, so V_f is a curve parameter (the scene's 1 cm/s and smaller).
    "incline_creep": dict(label="creep speed over [T/2, T] [m/s]", duration=(2.0, 2.0),
                          sdx=([1e-2, 3e-3, 1e-3, 3e-4], [1e-2, 3e-3, 1e-3]),
                          sdx_curves=([(i, "reconstructed", vf) for i in ("BackwardEuler", "BDF2")
                                       for vf in (None, 1e-3, 1e-4, 1e-5)],
                                      [("BackwardEuler", "reconstructed", vf) for vf in (None, 1e-4)]),
                          peer=([1e-2, 3e-3, 1e-3, 3e-4, 1e-4], [1e-2, 3e-3, 1e-3, 3e-4])),
    "stack": dict(label="top-box drift [m]", duration=(5.0, 2.0),
                  sdx=([1e-1, 5e-2, 2e-2, 1e-2, 5e-3, 2e-3], [5e-2, 1e-2, 5e-3]),
                  peer=([2e-2, 1e-2, 3e-3, 1e-3, 3e-4], [2e-2, 1e-2, 3e-3, 1e-3])),
    # The full run is the whole 2 s pile (landing and rest), the quick one its landing.
    "pile": dict(label="max penetration [m]", duration=(2.0, 0.3),
                 sdx=([2e-2, 1e-2], [2e-2, 1e-2]), peer=([1e-2, 5e-3, 2e-3], [1e-2, 5e-3]),
                 sdx_curves=([("BDF2", "reconstructed"), ("BDF2", "explicit"),
                              ("BDF2", "reconstructed_exact"), ("BDF2", "explicit_exact")],) * 2),
    "tumble": dict(label="relative energy drift after 5 s", duration=(5.0, 5.0),
                   sdx=([4e-2, 2e-2, 1e-2, 5e-3, 2e-3], [4e-2, 1e-2, 2e-3]),
                   peer=([4e-2, 1e-2, 3e-3, 1e-3, 3e-4, 1e-4], [1e-2, 1e-3, 1e-4]),
                   # No contact: the dissipation mode does not apply.
                   sdx_curves=([("BDF2", "reconstructed"), ("BackwardEuler", "reconstructed")],) * 2),
}


def curve_name(integrator, mode, vf=None):
    return f"superdex {integrator} {MODES[mode][0]}" + (f" V_f={vf:g}" if vf else "")


def peers_for(scene):
    """(curve name, adapter, extra arguments). MuJoCo's Newton solver is its recommended one; on
    the 6000-dof pile MuJoCo 2.2's Newton takes over 10 minutes per simulated second, so CG."""
    mujoco = ("MuJoCo CG", "superdex_peer_mujoco", ["--solver", "cg"]) if scene == "pile" else \
        ("MuJoCo Newton", "superdex_peer_mujoco", ["--solver", "newton"])
    return [mujoco, ("Bullet", "superdex_peer_bullet", [])]


# ---------------------------------------------------------------------------------------------
# Metrics of a superdex trajectory (the definitions of bench/peers/peer_run.cpp)

def sub(a, b): return [x - y for x, y in zip(a, b)]
def dot(a, b): return sum(x * y for x, y in zip(a, b))
def norm(a): return math.sqrt(dot(a, a))
def scale(a, s): return [x * s for x in a]


def rotation(q):
    x, y, z, w = q
    return [[1 - 2 * (y * y + z * z), 2 * (x * y - z * w), 2 * (x * z + y * w)],
            [2 * (x * y + z * w), 1 - 2 * (x * x + z * z), 2 * (y * z - x * w)],
            [2 * (x * z - y * w), 2 * (y * z + x * w), 1 - 2 * (x * x + y * y)]]


def matvec(m, v): return [dot(row, v) for row in m]


def scene_bodies(scene_json):
    """Actors as (name, dynamic, shape, contact) in file order, grids expanded."""
    out = []
    for a in scene_json["actors"]:
        g = a.get("grid")
        n = 1
        if g:
            c = g.get("count", [1, 1, 1])
            n = int(c[0] * c[1] * c[2])
        out += [a] * n
    return out


def superdex_metrics(scene, scene_json, frames, gravity):
    actors = scene_bodies(scene_json)
    tracked = max(i for i, a in enumerate(actors) if a.get("dynamic", True))
    body = actors[tracked]
    static = next((a for a in actors if not a.get("dynamic", True)), None)
    track = [dict(t=f["t"], **f["actors"][tracked]) for f in frames]
    g = norm(gravity)
    mu = lambda a: a.get("contact", {}).get("coulomb_friction_coefficient", 0.5)
    n = [0.0, 0.0, 1.0]
    if static and static["shape"]["type"] == "plane":
        n = static["shape"].get("normal", n)
        n = scale(n, 1 / norm(n))
    if scene == "drop":
        r = body["shape"]["radius"]
        height = lambda x: dot(x["p"], n) - r
        energy = lambda x: 0.5 * dot(x["v"], x["v"]) + g * height(x)
        before = after = None
        bounced = False
        for x in track:
            free, vn = height(x) > 0.01, dot(x["v"], n)
            if not bounced and free and vn < 0:
                before = energy(x)
            if not free and vn > 0:
                bounced = True
            if bounced and free and vn > 0:
                after = energy(x)
                break
        if before is None or after is None:
            return {"restitution": None, "error": 1.0}
        e = math.sqrt(max(0.0, after) / before)
        return {"restitution": e, "error": abs(1 - e)}
    if scene in ("incline", "incline_creep"):
        gn = dot(gravity, n)
        down = sub(gravity, scale(n, gn))
        down = scale(down, 1 / norm(down))
        s = lambda x: dot(sub(x["p"], track[0]["p"]), down)
        if scene == "incline_creep":
            T = track[-1]["t"]
            at = lambda time: [s(x) for x in track if x["t"] <= time + 1e-9][-1]
            speed = abs(at(T) - at(0.5 * T)) / (0.5 * T)
            return {"creep_speed": speed, "creep_1s": abs(at(1.0)), "error": speed}
        cos_t = abs(gn) / g
        exact = g * (math.sqrt(1 - cos_t * cos_t) - math.sqrt(mu(body) * mu(static)) * cos_t)
        rows = [(x["t"], s(x)) for x in track if x["t"] >= 0.5 - 1e-12]
        ata = [[sum(t ** (i + j) for t, _ in rows) for j in range(3)] for i in range(3)]
        atb = [sum(t ** i * y for t, y in rows) for i in range(3)]
        a = 2 * solve3(ata, atb)[2]
        return {"acceleration": a, "exact_acceleration": exact, "error": abs(a - exact) / abs(exact)}
    if scene == "stack":
        T = track[-1]["t"]
        ts = min(1.0, 0.5 * T)
        settled = [x for x in track if x["t"] <= ts + 1e-9][-1]
        sizes = [a["shape"]["size"][2] for a in actors if a.get("dynamic", True)]
        z_geom = sum(sizes) - 0.5 * sizes[-1]
        end = track[-1]["p"]
        h = norm(sub(end[:2], track[0]["p"][:2]))
        v = abs(end[2] - settled["p"][2])
        return {"horizontal_drift": h, "vertical_drift": v, "sag": z_geom - end[2],
                "settle_time": ts, "error": math.hypot(h, v)}
    if scene == "tumble":
        m = body["mass"]
        lx, ly, lz = body["shape"]["size"]
        inertia = [m / 12 * (ly * ly + lz * lz), m / 12 * (lx * lx + lz * lz), m / 12 * (lx * lx + ly * ly)]

        def momentum(x):
            R = rotation(x["q"])
            wb = [sum(R[k][i] * x["w"][k] for k in range(3)) for i in range(3)]  # R^T w
            return matvec(R, [inertia[i] * wb[i] for i in range(3)]), 0.5 * sum(inertia[i] * wb[i] ** 2 for i in range(3))
        l0, e0 = momentum(track[0])
        l1, e1 = momentum(track[-1])
        de = abs(e1 - e0) / e0
        return {"energy_drift": de, "momentum_drift": norm(sub(l1, l0)) / norm(l0), "error": de}
    return {}


def solve3(a, b):
    """Gaussian elimination with partial pivoting for the 3x3 normal equations."""
    m = [row[:] + [bb] for row, bb in zip(a, b)]
    for c in range(3):
        p = max(range(c, 3), key=lambda r: abs(m[r][c]))
        m[c], m[p] = m[p], m[c]
        for r in range(c + 1, 3):
            f = m[r][c] / m[c][c]
            m[r] = [x - f * y for x, y in zip(m[r], m[c])]
    x = [0.0] * 3
    for r in (2, 1, 0):
        x[r] = (m[r][3] - sum(m[r][k] * x[k] for k in range(r + 1, 3))) / m[r][r]
    return x


# ---------------------------------------------------------------------------------------------
# Runs

def run_superdex(build, scene, integrator, mode, dt, duration, tmp, timeout, vf=None):
    src = os.path.join(SOURCE, "scenes", "data", scene + ".json")
    with open(src) as f:
        sj = json.load(f)
    settings = sj.setdefault("settings", {})
    if MODES[mode][1]:
        settings["experimental_eval_params"] = MODES[mode][1]
    if mode in EXACT_SPHERES:
        for actor in sj["actors"]:
            if actor.get("shape", {}).get("type") == "sphere":
                actor["surface_integral"] = "ExactSphere"
    if vf:  # every actor's friction fall-off speed
        for actor in sj["actors"]:
            actor.setdefault("contact", {})["friction_falloff_vel"] = vf
    traj = os.path.join(tmp, f"{scene}_{integrator}_{mode}_{vf or 0:g}_{dt:g}.jsonl")
    # The drop's restitution needs every step; elsewhere about 100 samples per second suffice.
    every = 1 if scene == "drop" else max(1, int(round(0.01 / dt)))
    sj["output"] = {"path": traj, "every": every}
    sj.pop("expect", None)
    variant = os.path.join(tmp, f"{scene}_{mode}_{vf or 0:g}.json")
    with open(variant, "w") as f:
        json.dump(sj, f)
    cmd = [os.path.join(build, "scenes", "superdex"), "run", variant, "--dt", repr(dt), "--duration",
           repr(duration), "--integrator", integrator, "--out", traj, "--quiet"]
    res = dict(engine=curve_name(integrator, mode, vf), scene=scene, dt=dt)
    try:
        p = subprocess.run(cmd, capture_output=True, text=True, timeout=timeout)
    except subprocess.TimeoutExpired:
        return dict(res, failed=True, failure=f"timeout after {timeout} s")
    out = p.stdout
    wall = re.search(r"wall time\s+([0-9.eE+-]+) s", out)
    pen = re.search(r"max penetration\s+([0-9.eE+-]+) mm", out)
    stages = re.search(r"(\d+) converged, (\d+) stopped, (\d+) diverged", out)
    if p.returncode not in (0, 3, 4) or not wall:
        return dict(res, failed=True, failure=(p.stderr.strip() or out.strip())[-300:])
    with open(traj) as f:
        header = json.loads(f.readline())
        frames = [json.loads(line) for line in f if line.strip()]
    os.remove(traj)
    sim = frames[-1]["t"]
    try:
        metrics = superdex_metrics(scene, sj, frames, header["gravity"])
    except (ValueError, ZeroDivisionError, KeyError, IndexError, TypeError) as e:
        metrics = {"error": None, "metric_failure": str(e)}
    res.update(wall_seconds=float(wall.group(1)), simulated_seconds=sim,
               wall_per_simulated_second=float(wall.group(1)) / sim,
               max_penetration=float(pen.group(1)) * 1e-3 if pen else None, metrics=metrics)
    if "error" not in metrics:
        metrics["error"] = res["max_penetration"]
    unconverged = int(stages.group(2)) + int(stages.group(3)) if stages else 0
    bad = metrics.get("error") is None or not math.isfinite(metrics["error"])
    res["failed"] = bad or unconverged > 0
    if unconverged:
        res["failure"] = f"{unconverged} stages did not converge"
    return res


def run_peer(build, adapter, args, scene, dt, duration, timeout):
    cmd = [os.path.join(build, "bench", "peers", adapter), "--scene", scene, "--dt", repr(dt),
           "--duration", repr(duration)] + args
    try:
        p = subprocess.run(cmd, capture_output=True, text=True, timeout=timeout)
    except subprocess.TimeoutExpired:
        return dict(scene=scene, dt=dt, failed=True, failure=f"timeout after {timeout} s")
    lines = [line for line in p.stdout.splitlines() if line.startswith("{")]
    if p.returncode != 0 or not lines:
        return dict(scene=scene, dt=dt, failed=True, failure=p.stderr.strip()[-300:])
    return json.loads(lines[-1])


# ---------------------------------------------------------------------------------------------
# Comparison at equal error

FLOOR = 1e-12


def front(points):
    """Pareto front (wall, error) sorted by increasing wall and strictly decreasing error."""
    best, out = math.inf, []
    for w, e in sorted(points):
        if e < best:
            out.append((w, e))
            best = e
    return out


def wall_at(fr, e):
    """log-log interpolation of the wall time reaching error e along a front."""
    pts = sorted((math.log(max(err, FLOOR)), math.log(w)) for w, err in fr)
    le = math.log(max(e, FLOOR))
    for (e0, w0), (e1, w1) in zip(pts, pts[1:]):
        if e0 <= le <= e1:
            return math.exp(w0 + (w1 - w0) * (le - e0) / (e1 - e0)) if e1 > e0 else math.exp(min(w0, w1))
    if len(pts) == 1 or abs(le - pts[0][0]) < 1e-12:
        return math.exp(pts[0][1])
    return None


def cheapest(points, e):
    """Least wall time among the runs with error <= e."""
    return min((w for w, err in points if err <= e * (1 + 1e-9)), default=None)


def ratio_line(name, sdx, peer_name, peer):
    if not sdx or not peer:
        return f"- {name} / {peer_name}: n/a (no successful run on one side)"
    rs = (min(e for _, e in sdx), max(e for _, e in sdx))
    rp = (min(e for _, e in peer), max(e for _, e in peer))
    lo, hi = max(rs[0], rp[0]), min(rs[1], rp[1])
    ranges = f"superdex errors {rs[0]:.3g}..{rs[1]:.3g}, {peer_name} {rp[0]:.3g}..{rp[1]:.3g}"
    if lo > hi:
        # Also say what reaching the accuracy both can reach costs each side.
        e = max(rs[0], rp[0])
        ws, wp = cheapest(sdx, e), cheapest(peer, e)
        return (f"- {name} / {peer_name}: n/a (error ranges do not overlap: {ranges}; cheapest runs "
                f"with error <= {e:.3g}: {ws:.3g} vs {wp:.3g} wall s per simulated s, {ws / wp:.3g}x)")
    e = math.exp(0.5 * (math.log(max(lo, FLOOR)) + math.log(max(hi, FLOOR))))
    ws, wp = wall_at(sdx, e), wall_at(peer, e)
    if ws is None or wp is None:
        return f"- {name} / {peer_name}: n/a ({ranges})"
    return f"- {name} / {peer_name}: **{ws / wp:.3g}x** at error {e:.3g} ({ws:.3g} vs {wp:.3g} wall s per simulated s; {ranges})"


# ---------------------------------------------------------------------------------------------
# Report

def fmt(x, digits=3):
    return "-" if x is None else f"{x:.{digits}g}"


EXTRA = {"drop": ["restitution"], "incline": ["acceleration"], "incline_creep": ["creep_1s"],
         "stack": ["horizontal_drift", "vertical_drift", "sag"], "pile": [],
         "tumble": ["energy_drift", "momentum_drift"]}


def table(scene, cfg, runs, curves, quick, duration):
    extra = EXTRA[scene]
    head = ["curve", "dt [s]", "wall s / sim s", "error", "max pen. [mm]"] + extra + ["status"]
    lines = [f"## {scene} ({'quick' if quick else 'full'}: {duration:g} s simulated)", "",
             f"error = {cfg['label']}", "",
             "| " + " | ".join(head) + " |", "|" + "---|" * len(head)]
    for r in runs:
        m = r.get("metrics", {})
        pen = r.get("max_penetration")
        status = "FAILED: " + r.get("failure", "nan" if r.get("nan") else "no metric") if r.get("failed") else "ok"
        cells = [r["curve"], f"{r['dt']:g}", fmt(r.get("wall_per_simulated_second")), fmt(m.get("error")),
                 fmt(pen * 1e3 if pen is not None else None)] + [fmt(m.get(k), 4) for k in extra] + [status]
        lines.append("| " + " | ".join(cells) + " |")
    lines += ["", "superdex wall time / peer wall time at equal error (log-log interpolation at the "
              "geometric middle of the overlapping error range, along each sweep's Pareto front):", ""]
    sdx_names = [c for c in curves if c.startswith("superdex")]
    peer_names = [c for c in curves if not c.startswith("superdex")]
    for s in sdx_names:
        for p in peer_names:
            lines.append(ratio_line(s, curves[s], p, curves[p]))
    return "\n".join(lines) + "\n"


def plot(scene, cfg, curves, path):
    try:
        import matplotlib
        matplotlib.use("Agg")
        import matplotlib.pyplot as plt
    except ImportError:
        print("matplotlib missing (bash bench/peers/install-peers): no plot", file=sys.stderr)
        return
    fig, ax = plt.subplots(figsize=(8, 5.5))
    styles = {"MuJoCo": dict(color="tab:red", marker="s"), "Bullet": dict(color="tab:green", marker="^")}
    sdx_colors = iter(["tab:blue", "tab:cyan", "tab:purple", "tab:pink", "tab:olive", "tab:brown",
                       "tab:gray", "black"])
    dashes = {"explicit normals": "--", "current load": ":"}
    for name, pts in curves.items():
        if not pts:
            continue
        pts = sorted(pts)
        st = next((v for k, v in styles.items() if name.startswith(k)), None)
        if st is None:
            st = dict(color=next(sdx_colors), marker="o",
                      linestyle=next((d for k, d in dashes.items() if k in name), "-"))
        ax.plot([w for w, _ in pts], [max(e, FLOOR) for _, e in pts], label=name, **st)
    ax.set_xscale("log")
    ax.set_yscale("log")
    ax.set_xlabel("wall seconds per simulated second (2 cores)")
    ax.set_ylabel(cfg["label"])
    ax.set_title(f"{scene}: error against cost")
    ax.grid(True, which="both", alpha=0.3)
    ax.legend(fontsize=8)
    fig.tight_layout()
    fig.savefig(path, dpi=110)
    plt.close(fig)


def main():
    ap = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    ap.add_argument("--build", required=True, help="CMake build directory (with the peers built)")
    ap.add_argument("--quick", action="store_true", help="fewer dt values, shorter runs, short pile")
    ap.add_argument("--scenes", default=",".join(SCENES), help="comma-separated subset")
    ap.add_argument("--out", default=os.path.join(SOURCE, "out", "peers"))
    ap.add_argument("--timeout", type=float, default=None, help="per run [s] (quick 300, full 3600)")
    ap.add_argument("--repeat", type=int, default=5,
                    help="runs of each configuration whose wall time is below 1 s, three times "
                         "as many below 20 ms; the least wall time is reported (default 5)")
    a = ap.parse_args()
    if a.repeat < 1:
        ap.error("--repeat: must be >= 1")

    def timed(run):
        """The run's result with the least wall time over up to a.repeat runs (3 a.repeat for runs
        under 20 ms): a run of a few milliseconds scatters by tens of percent with the machine's
        load, the same way for every engine (a sub-millisecond incline run of MuJoCo or superdex
        reads 0.45-0.78 ms in twelve runs, two clusters). Runs of a second or more, and failed
        runs, are not repeated."""
        best = run()
        runs = 1
        while runs < (3 * a.repeat if best.get("wall_seconds", 1.0) < 0.02 else a.repeat):
            if best.get("failed") or best.get("wall_seconds", 1.0) >= 1.0:
                break
            runs += 1
            r = run()
            if not r.get("failed") and r["wall_seconds"] < best["wall_seconds"]:
                best["wall_seconds"] = r["wall_seconds"]
                best["wall_per_simulated_second"] = r["wall_per_simulated_second"]
        return best

    build = os.path.abspath(a.build)
    os.makedirs(a.out, exist_ok=True)
    timeout = a.timeout or (300 if a.quick else 3600)
    k = 1 if a.quick else 0
    start = time.time()
    with tempfile.TemporaryDirectory() as tmp:
        for scene in a.scenes.split(","):
            cfg = SCENES[scene]
            duration = cfg["duration"][k]
            runs = []
            for spec in cfg["sdx_curves"][k] if "sdx_curves" in cfg else SUPERDEX_CURVES:
                integrator, mode, vf = (tuple(spec) + (None,))[:3]  # vf: the scene's unless given
                for dt in cfg["sdx"][k]:
                    r = timed(lambda: run_superdex(build, scene, integrator, mode, dt, duration,
                                                   tmp, timeout, vf))
                    r["curve"] = curve_name(integrator, mode, vf)
                    runs.append(r)
                    print(f"  {scene} {r['curve']} dt={dt:g}: {fmt(r.get('metrics', {}).get('error'))}"
                          f" in {fmt(r.get('wall_per_simulated_second'))} s/s", file=sys.stderr)
            for name, adapter, args in peers_for(scene):
                if not os.path.exists(os.path.join(build, "bench", "peers", adapter)):
                    print(f"  {adapter} not built (bash bench/peers/install-peers, then re-run cmake)",
                          file=sys.stderr)
                    continue
                for dt in cfg["peer"][k]:
                    r = timed(lambda: run_peer(build, adapter, args, scene, dt, duration, timeout))
                    r["curve"] = name
                    runs.append(r)
                    print(f"  {scene} {name} dt={dt:g}: {fmt(r.get('metrics', {}).get('error'))}"
                          f" in {fmt(r.get('wall_per_simulated_second'))} s/s", file=sys.stderr)
            curves = {}
            for r in runs:
                pts = curves.setdefault(r["curve"], [])
                if not r.get("failed"):
                    pts.append((r["wall_per_simulated_second"], r["metrics"]["error"]))
            curves = {n: front(p) if p else [] for n, p in curves.items()}
            # Plots show every successful run; the ratios use the fronts.
            all_pts = {}
            for r in runs:
                if not r.get("failed"):
                    all_pts.setdefault(r["curve"], []).append((r["wall_per_simulated_second"], r["metrics"]["error"]))
            md = table(scene, cfg, runs, curves, a.quick, duration)
            print(md)
            with open(os.path.join(a.out, scene + ".md"), "w") as f:
                f.write(md)
            with open(os.path.join(a.out, scene + ".json"), "w") as f:
                json.dump(runs, f, indent=1)
            plot(scene, cfg, all_pts, os.path.join(a.out, scene + ".png"))
    print(f"total {time.time() - start:.0f} s; tables and plots in {a.out}", file=sys.stderr)


if __name__ == "__main__":
    main()
