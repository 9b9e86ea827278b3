#!/usr/bin/python3
"""Charts and tables of docs/BENCHMARKS.md from the CSVs of one `make bench` run.

    /usr/bin/python3 bench/plot_charts.py [docs/bench] [docs/images/bench] [docs/BENCHMARKS.md] [--only NAME]

Draws PNGs and rewrites the text between <!-- bench:NAME --> and <!-- /bench:NAME --> markers of
BENCHMARKS.md, so every figure in the document comes from the files.
"""
import csv
import math
import os
import re
import sys

import matplotlib

matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402
import matplotlib.ticker  # noqa: E402

ARGS = [a for a in sys.argv[1:] if not a.startswith("--")]
ONLY = sys.argv[sys.argv.index("--only") + 1] if "--only" in sys.argv else None
if ONLY:
    ARGS.remove(ONLY)
    if ONLY not in ("wall_time", "fold", "meshers", "user_path"):
        sys.exit("plot_charts.py: --only takes wall_time, fold, meshers or user_path")
BENCH = ARGS[0] if len(ARGS) > 0 else "docs/bench"
IMAGES = ARGS[1] if len(ARGS) > 1 else "docs/images/bench"
DOC = ARGS[2] if len(ARGS) > 2 else "docs/BENCHMARKS.md"
COLORS = {"newton": "C0", "shape_matching": "C1", "seed_spring": "C3", "rigid_kinematics": "C2"}


def rows(name):
    path = os.path.join(BENCH, name)
    if not os.path.exists(path):
        return None
    with open(path) as f:
        return list(csv.DictReader(f))


def num(x):
    try:
        return float(x)
    except (TypeError, ValueError):
        return math.nan


def fmt(x, digits=3):
    if x is None or (isinstance(x, float) and not math.isfinite(x)):
        return "–"
    return f"{x:.{digits}g}"


def pareto(points):
    """Points (time, error) not beaten in both by another point, sorted by time."""
    front, best = [], math.inf
    for t, e in sorted(points):
        if e < best:
            front.append((t, e))
            best = e
    return front


def save(fig, name):
    os.makedirs(IMAGES, exist_ok=True)
    fig.tight_layout()
    fig.savefig(os.path.join(IMAGES, name), dpi=110)
    plt.close(fig)


def finish(fig, ax, xlabel, ylabel, title, name):
    """The close of a one-panel chart: axis labels, a grid on both scales, the legend, the title,
    and the PNG."""
    ax.set_xlabel(xlabel)
    ax.set_ylabel(ylabel)
    ax.grid(True, which="both", alpha=0.3)
    ax.legend(fontsize=8)
    ax.set_title(title)
    save(fig, name)


def chart_error_time(tables):
    data = rows("error_time.csv")
    if not data:
        return
    floor = 1e-16  # strain/position of exact zero drawn at the axis floor
    fig, axes = plt.subplots(1, 2, figsize=(11, 4.2))
    all_points = {"max_strain": [], "position_error": []}
    for ax, key, label in ((axes[0], "max_strain", "max edge strain"),
                           (axes[1], "position_error", "max vertex distance to rigid_kinematics")):
        for solver in COLORS:
            pts = [(num(r["seconds"]), max(num(r[key]), floor)) for r in data
                   if r["solver"] == solver and r["diverged"] == "0"]
            if not pts:
                continue
            all_points[key] += [(t, e, solver) for t, e in pts]
            ax.loglog([p[0] for p in pts], [p[1] for p in pts], "o-", ms=3, color=COLORS[solver], label=solver,
                      alpha=0.8)
        front = pareto([(t, e) for t, e, _ in all_points[key]])
        ax.step([p[0] for p in front], [p[1] for p in front], "k--", where="post", lw=1, label="Pareto front")
        ax.set_xlabel("wall time per solve [s]")
        ax.set_ylabel(label)
        ax.grid(True, which="both", alpha=0.3)
        ax.legend(fontsize=8)
    fig.suptitle("miura_12x10 fold step: error against time over iteration budgets")
    save(fig, "error_time.png")

    # Table: time each solver needs to reach strain 1e-3, 1e-6, 1e-9.
    lines = ["| solver | time to strain < 1e-3 | < 1e-6 | < 1e-9 | best strain reached |",
             "|---|---|---|---|---|"]
    times = {}
    for solver in COLORS:
        sr = [r for r in data if r["solver"] == solver and r["diverged"] == "0"]
        if not sr:
            continue
        cells = []
        for target in (1e-3, 1e-6, 1e-9):
            hits = [num(r["seconds"]) for r in sr if num(r["max_strain"]) < target]
            times[(solver, target)] = min(hits) if hits else math.nan
            cells.append(fmt(min(hits) * 1e3) + " ms" if hits else "not reached")
        lines.append(f"| {solver} | " + " | ".join(cells) + f" | {fmt(min(num(r['max_strain']) for r in sr))} |")
    front = pareto([(t, e) for t, e, _ in all_points["max_strain"]])
    owners = []
    for t, e in front:
        for pt, pe, s in all_points["max_strain"]:
            if pt == t and max(pe, floor) == e:
                owners.append(s)
                break
    # The tightest strain both reach: the seed's scheme often stops short of 1e-6.
    target = next((t for t in (1e-9, 1e-6, 1e-3) if math.isfinite(times.get(("seed_spring", t), math.nan))), 1e-3)
    ratio = times.get(("seed_spring", target), math.nan) / times.get(("newton", target), math.nan)
    lines.append("")
    lines.append(f"Solvers on the strain Pareto front, fastest first: {', '.join(dict.fromkeys(owners))}. "
                 f"To strain < {target:g} newton is {fmt(ratio)}× faster than the seed's spring scheme "
                 f"(at its largest stable d).")
    tables["error_time"] = "\n".join(lines)


def chart_stability(tables):
    data = rows("stability_map.csv")
    if not data:
        return
    seed = [r for r in data if r["solver"] == "seed_spring"]
    fig, ax = plt.subplots(figsize=(7, 4.5))
    styles = {"converged": ("o", "C2"), "stalled": ("s", "C1"), "diverged": ("x", "C3")}
    for state, (marker, color) in styles.items():
        pts = [r for r in seed if (state == "converged" and r["converged"] == "1") or
               (state == "diverged" and r["diverged"] == "1") or
               (state == "stalled" and r["converged"] == "0" and r["diverged"] == "0")]
        ax.scatter([num(r["dt"]) for r in pts], [num(r["stiffness"]) for r in pts], marker=marker, c=color, s=18,
                   label=f"seed_spring {state}")
    d = num(seed[0]["d"])
    dts = [0.5 + 0.01 * k for k in range(241)]
    ax.plot(dts, [2 / (d * t * t) for t in dts], "k-", lw=1, label="bound d·λ·Δt² = 2")
    lam = sorted({num(r["stiffness"]) for r in seed})
    ax.set_ylim(min(lam) - 1, max(lam) + 1)
    ax.set_xlabel("step Δt (d = %g)" % d)
    ax.set_ylabel("spring stiffness λ_max (= face vertex count)")
    ax.legend(fontsize=8, loc="upper right")
    ax.set_title("Stability map of the seed's explicit spring scheme")
    save(fig, "stability_map.png")

    bad = [r for r in seed if r["converged"] == "1" and num(r["bound"]) >= 2]
    unexpected = [r for r in seed if r["diverged"] == "1" and num(r["bound"]) < 2]
    implicit = {}
    for r in data:
        if r["solver"] != "seed_spring":
            implicit.setdefault(r["solver"], []).append(r)
    lines = [f"{len(seed)} (Δt, λ) cells of the seed scheme: "
             f"{sum(r['converged'] == '1' for r in seed)} converged, {sum(r['diverged'] == '1' for r in seed)} "
             f"diverged, {sum(r['converged'] == '0' and r['diverged'] == '0' for r in seed)} stalled "
             f"(at the bound, neither). Converged beyond the bound d·λ·Δt² < 2: {len(bad)}; diverged inside "
             f"it: {len(unexpected)}."]
    for name, rs in implicit.items():
        lines.append(f"{name} (no step size) on the same {len(rs)} faces (λ {fmt(min(num(r['stiffness']) for r in rs))}"
                     f"–{fmt(max(num(r['stiffness']) for r in rs))}): {sum(r['converged'] == '1' for r in rs)} "
                     f"converged, {sum(r['diverged'] == '1' for r in rs)} diverged, at most "
                     f"{max(int(r['iterations']) for r in rs)} iterations.")
    tables["stability"] = "\n\n".join(lines)


def chart_scaling(tables):
    data = rows("scaling.csv")
    floor = rows("machine_floor.csv")
    if not data:
        return
    bandwidth = num(floor[0]["value"]) if floor else math.nan
    v = [num(r["vertices"]) for r in data]
    fig, ax = plt.subplots(figsize=(7, 4.5))
    ax.loglog(v, [num(r["explicit_step_seconds"]) for r in data], "o-", c="C3", label="seed_spring: one step")
    ax.loglog(v, [num(r["explicit_floor_seconds"]) for r in data], "--", c="C3",
              label="floor: bytes per step / triad bandwidth")
    nv = [(num(r["vertices"]), num(r["newton_iteration_seconds"])) for r in data
          if math.isfinite(num(r["newton_iteration_seconds"]))]
    ax.loglog([p[0] for p in nv], [p[1] for p in nv], "o-", c="C0", label="newton: one iteration")
    ax.loglog(v, [num(r["ldlt_seconds"]) for r in data], "--", c="C0", label="floor: one SimplicialLDLT")
    finish(fig, ax, "vertices (grid sheet of square faces)",
           "seconds",
           "Time per step against vertex count (triad %.1f GB/s)" % (bandwidth / 1e9), "scaling.png")

    lines = [f"Triad bandwidth: {fmt(bandwidth / 1e9)} GB/s.", "",
             "| vertices | explicit step | its floor | ratio | newton iteration | one LDLT | ratio |",
             "|---|---|---|---|---|---|---|"]
    for r in data:
        e, f, n, l = (num(r[k]) for k in ("explicit_step_seconds", "explicit_floor_seconds",
                                           "newton_iteration_seconds", "ldlt_seconds"))
        lines.append(f"| {int(num(r['vertices']))} | {fmt(e * 1e3)} ms | {fmt(f * 1e3)} ms | {fmt(e / f)}× | "
                     f"{fmt(n * 1e3)} ms | {fmt(l * 1e3)} ms | {fmt(n / l)}× |")
    tables["scaling"] = "\n".join(lines)


def chart_seed_accuracy(tables):
    data = rows("solvers.csv")
    if not data:
        return
    lines = ["| scene | vertices | solver | converged | iterations | time | max strain | fold-angle error | "
             "speed-up vs seed |", "|---|---|---|---|---|---|---|---|---|"]
    for r in data:
        lines.append(f"| {r['scene']} | {r['vertices']} | {r['solver']} | {r['converged']} | {r['iterations']} | "
                     f"{fmt(num(r['seconds']) * 1e3)} ms | {fmt(num(r['max_strain']))} | "
                     f"{fmt(num(r['fold_angle_error']))} | {fmt(num(r['speedup_vs_seed']))} |")
    tables["solvers"] = "\n".join(lines)


def chart_curved(tables):
    data = rows("curved_solvers.csv")
    if not data:
        return
    steps = [r for r in data if r["case"] == "pull_step"]
    fig, ax = plt.subplots(figsize=(7, 4.5))
    for method, color in (("newton", "C0"), ("rk4", "C3")):
        pts = [r for r in steps if r["method"] == method]
        ax.scatter([num(r["seconds"]) for r in pts], [max(num(r["max_force"]), 1e-16) for r in pts], c=color,
                   label=method)
        for r in pts:
            ax.annotate(f"s{r['scene']}/{r['nodes']}", (num(r["seconds"]), max(num(r["max_force"]), 1e-16)),
                        fontsize=6)
    front = pareto([(num(r["seconds"]), max(num(r["max_force"]), 1e-16)) for r in steps])
    ax.step([p[0] for p in front], [p[1] for p in front], "k--", where="post", lw=1, label="Pareto front")
    ax.set_xscale("log")
    ax.set_yscale("log")
    finish(fig, ax, "wall time per solve [s]",
           "max residual force at the end",
           "Curved paper: seed RK4 against implicit Newton (scene/nodes)", "curved_error_time.png")
    lines = ["| scene | nodes | newton time | newton residual | rk4 time | rk4 residual | rk4 time / newton |",
             "|---|---|---|---|---|---|---|"]
    for r in steps:
        if r["method"] != "newton":
            continue
        rk = [q for q in steps if q["method"] == "rk4" and q["scene"] == r["scene"] and q["nodes"] == r["nodes"]]
        rk = rk[0] if rk else {}
        lines.append(f"| {r['scene']} | {r['nodes']} | {fmt(num(r['seconds']) * 1e3)} ms | {fmt(num(r['max_force']))} | "
                     f"{fmt(num(rk.get('seconds')) * 1e3)} ms{'' if rk.get('converged') == '1' else ' (budget, not converged)'} | "
                     f"{fmt(num(rk.get('max_force')))} | {fmt(num(r['rk4_time_over_newton']))}× |")
    tables["curved"] = "\n".join(lines)
    chart_curved_elastica(tables)


def chart_curved_elastica(tables):
    """curved_bench's elastica part: each method's error against Euler's elastica (a converged
    reference: RK4 in 4000 steps, halving them moves no point by 1e-10 of the length) against
    its CPU time per solve, at four spacings and two tolerances, and the Pareto front."""
    data = rows("curved_elastica.csv")
    if not data:
        return
    fig, ax = plt.subplots(figsize=(7.5, 5))
    styles = {"newton": ("C0", "o"), "quasi_newton": ("C2", "s"), "rk4": ("C3", "^")}
    for method, (color, marker) in styles.items():
        pts = [r for r in data if r["method"] == method]
        for done, label in (("1", f"{method} (balanced)"), ("0", f"{method} (budget or iterations ran out)")):
            sel = [r for r in pts if r["converged"] == done]
            if sel:
                ax.scatter([num(r["cpu_seconds"]) for r in sel], [num(r["error"]) for r in sel], c=color if done == "1"
                           else "none", edgecolors=color, marker=marker, label=label)
        for r in pts:
            ax.annotate(f"b/{r['per_width']}", (num(r["cpu_seconds"]), num(r["error"])), textcoords="offset points",
                        xytext=(4, 3), fontsize=6)
    front = pareto([(num(r["cpu_seconds"]), num(r["error"])) for r in data])
    ax.step([p[0] for p in front], [p[1] for p in front], "k--", where="post", lw=1, label="Pareto front")
    ax.set_xscale("log")
    ax.set_yscale("log")
    finish(fig, ax, "CPU time per solve [s] (one core)", "mid-line's largest distance from the elastica / length",
           "Curved paper against Euler's elastica (45° strip): error against time", "curved_elastica.png")
    lines = ["| spacing | nodes | method | tolerance (× D/L) | balanced | iterations | CPU time | error / length |",
             "|---|---|---|---|---|---|---|---|"]
    for r in data:
        lines.append(f"| b/{r['per_width']} | {r['nodes']} | {r['method']} | {r['tolerance']} | "
                     f"{'yes' if r['converged'] == '1' else 'no'} | {r['iterations']} | "
                     f"{fmt(num(r['cpu_seconds']) * 1e3)} ms | {fmt(num(r['error']))} |")
    on_front = [r for r in data if (num(r["cpu_seconds"]), num(r["error"])) in front]
    lines.append("")
    lines.append("On the Pareto front: " + ", ".join(f"{r['method']} b/{r['per_width']} (tolerance {r['tolerance']})"
                                                     for r in sorted(on_front, key=lambda r: num(r["cpu_seconds"]))) + ".")
    tables["curved_elastica"] = "\n".join(lines)


def chart_meshers(tables):
    """Mesh quality of both meshers (meshers.csv), and mesh resolution against error and time on
    seed scene 1 bending (mesh_resolution.csv): each solution's distance from its mesher's finest
    (balanced, stability checked) solution and from the next finer one, over the side."""
    quality = rows("meshers.csv")
    if quality:
        lines = ["| pattern | mesher | spacing | nodes | triangles | min angle | mean 2r/R | share 45–75° | time |",
                 "|---|---|---|---|---|---|---|---|---|"]
        for r in quality:
            lines.append(f"| {r['pattern']} | {r['mesher']} | {fmt(num(r['spacing']))} | {r['nodes']} | {r['triangles']} | "
                         f"{fmt(num(r['min_angle_deg']))}° | {fmt(num(r['mean_radius_ratio']))} | "
                         f"{fmt(num(r['share_45_75']), 2)} | {fmt(num(r['mesh_ms']))} ms |")
        tables["meshers"] = "\n".join(lines)
    scaling = rows("mesh_scaling.csv")
    if scaling:
        lines = ["| pattern | mesher | vertices | nodes | triangles | time | per node |",
                 "|---|---|---|---|---|---|---|"]
        for r in scaling:
            lines.append(f"| {r['pattern']} | {r['mesher']} | {int(num(r['vertices'])):,} | {int(num(r['nodes'])):,} | "
                         f"{int(num(r['triangles'])):,} | {fmt(num(r['mesh_ms']))} ms | {fmt(num(r['per_node_us']))} µs |")
        tables["mesh_scaling"] = "\n".join(lines)
    data = rows("mesh_resolution.csv")
    if not data:
        return
    fig, (left, right) = plt.subplots(1, 2, figsize=(11, 4.5))
    for mesher, color in (("bubble", "C1"), ("cgal", "C0")):
        # The finest row is the reference (its distance to itself is round-off): left out.
        pts = sorted((r for r in data if r["mesher"] == mesher and math.isfinite(num(r["rms_to_next"]))),
                     key=lambda r: -num(r["spacing"]))
        if not pts:
            continue
        left.plot([num(r["spacing"]) for r in pts], [num(r["rms_to_finest"]) for r in pts], "o-", c=color,
                  label=mesher)
        right.plot([num(r["cpu_seconds"]) for r in pts], [num(r["rms_to_finest"]) for r in pts], "o-", c=color,
                   label=mesher)
        for r in pts:  # bubble's labels below its points, CGAL's above: the two lines run close
            right.annotate(f"h {r['spacing']}", (num(r["cpu_seconds"]), num(r["rms_to_finest"])),
                           textcoords="offset points", xytext=(4, -9 if mesher == "bubble" else 4), fontsize=6,
                           color=color)
    measured = [r for r in data if math.isfinite(num(r["rms_to_next"]))]
    if measured:
        # First order: the distance in proportion to the spacing, through the coarsest points' mean.
        h = sorted({num(r["spacing"]) for r in measured})
        coarsest = [num(r["rms_to_finest"]) for r in measured if num(r["spacing"]) == h[-1]]
        e0 = sum(coarsest) / len(coarsest)
        left.plot([h[0], h[-1]], [e0 * h[0] / h[-1], e0], "k--", lw=1, label="first order (∝ spacing)")
    for ax in (left, right):
        ax.set_xscale("log")
        ax.set_yscale("log")
        ax.yaxis.set_minor_formatter(matplotlib.ticker.LogFormatterSciNotation(labelOnlyBase=False,
                                                                               minor_thresholds=(2, 0.5)))
        ax.set_ylabel("RMS distance to the mesher's finest solution / side")
        ax.margins(0.08)
        ax.grid(True, which="both", alpha=0.3)
        ax.legend(fontsize=8)
    spacings = sorted({num(r["spacing"]) for r in measured})
    left.xaxis.set_major_locator(matplotlib.ticker.FixedLocator(spacings))
    left.xaxis.set_major_formatter(matplotlib.ticker.FixedFormatter([f"{h:g}" for h in spacings]))
    left.xaxis.set_minor_locator(matplotlib.ticker.NullLocator())
    left.set_xlabel("mesh spacing / side")
    right.set_xlabel("CPU time of the pull [s] (one solve per spacing)")
    finest = sorted({min(num(r["spacing"]) for r in data if r["mesher"] == m) for m in {r["mesher"] for r in data}})
    turned = 180 * num(data[0]["pull"])
    fig.suptitle(f"Seed scene 1, corner turned {turned:g}°, bending q/k = {data[0]['bend_q_over_k']}: mesh resolution "
                 "against error and time\nReference: each "
                 f"mesher's own finest solution (spacing {', '.join(f'{h:g}' for h in finest)}), not drawn",
                 fontsize=10)
    save(fig, "mesh_resolution.png")
    lines = ["| mesher | spacing | nodes | balanced | largest force | CPU time | RMS to finest | max to finest | "
             "RMS to next | max to next |",
             "|---|---|---|---|---|---|---|---|---|---|"]
    for r in data:
        reference = not math.isfinite(num(r["rms_to_next"]))
        lines.append(f"| {r['mesher']} | {r['spacing']} | {r['nodes']} | {'yes' if r['balanced'] == '1' else 'no'} | "
                     f"{fmt(num(r['largest_force']))} | {fmt(num(r['cpu_seconds']))} s | "
                     f"{'reference' if reference else fmt(num(r['rms_to_finest']))} | "
                     f"{'–' if reference else fmt(num(r['max_to_finest']))} | "
                     f"{fmt(num(r['rms_to_next']))} | {fmt(num(r['max_to_next']))} |")
    tables["mesh_resolution"] = "\n".join(lines)


def table_replay(tables):
    data = rows("replay.csv")
    if not data:
        return
    lines = ["| model | operations | recorded | replayed | per operation | slowest operation | faster than recorded |",
             "|---|---|---|---|---|---|---|"]
    for r in data:
        lines.append(f"| {r['model']} | {r['operations']} | {fmt(num(r['recorded_s']))} s | {fmt(num(r['replay_ms']))} ms | "
                     f"{fmt(num(r['per_operation_us']))} µs | {fmt(num(r['slowest_operation_us']))} µs | "
                     f"{fmt(num(r['speedup']))}× |")
    tables["replay"] = "\n".join(lines)


def chart_curved_speed(tables):
    """curved_speed_bench: small pulls on the 10,000-vertex sheet, time per step against vertex
    count with the floor, and RK4's stability map."""
    speed = rows("curved_speed.csv")
    if speed:
        lines = ["| vertices | solves | converged | predicted | Newton iterations | factorisations | "
                 "conjugate-gradient steps | solves/s (wall) | solves per CPU second | median solve (CPU) | tolerance |",
                 "|---|---|---|---|---|---|---|---|---|---|---|"]
        for r in speed:
            lines.append(f"| {r['vertices']} | {r['solves']} | {r['converged']} | {r['predicted']} | "
                         f"{r['iterations']} | {r['factorizations']} | {r['krylov_steps']} | "
                         f"{fmt(num(r['solves_per_second']))} | "
                         f"{fmt(num(r['solves_per_cpu_second']))} | {fmt(num(r['median_solve_cpu_ms']))} ms | "
                         f"{r['tolerance']} |")
        tables["curved_speed"] = "\n".join(lines)
        v = [num(r["vertices"]) for r in speed]
        fig, ax = plt.subplots(figsize=(7, 4.5))
        ax.loglog(v, [num(r["solves_per_cpu_second"]) for r in speed], "o-", c="C0",
                  label="newton: small pulls per CPU second")
        ax.loglog(v, [1000 / num(r["median_solve_cpu_ms"]) for r in speed], "s--", c="C0", alpha=0.6,
                  label="newton: 1 / median solve (the drag without its snaps)")
        ax.axhline(30, c="k", lw=1, ls=":", label="target: 30 per second at 10,000 vertices")
        finish(fig, ax, "vertices (grid sheet, seed scene 1's pull, 200 pulls of 1/2000)",
               "static solves per CPU second (one core)",
               "Curved paper dragged by a corner: solves per second against sheet size", "curved_speed.png")

    acc = rows("curved_drag_accuracy.csv")
    if acc:
        fig, ax = plt.subplots(figsize=(7, 4.5))
        errors = [num(r["median_error"]) for r in acc]
        rates = [num(r["solves_per_cpu_second"]) for r in acc]
        ax.semilogx(errors, rates, "o-", c="C0", label=f"newton, {acc[0]['vertices']} vertices")
        for r, e, q in zip(acc, errors, rates):
            ax.annotate(f"tolerance {r['tolerance']}", (e, q), textcoords="offset points", xytext=(6, 6), fontsize=8)
        ax.set_ylim(0, max(rates) * 1.25)
        finish(fig, ax, "median error of a balance (largest node distance to the exact one) / side",
               "small pulls per CPU second (one core)",
               "Curved paper dragged by a corner: speed against accuracy", "curved_drag_accuracy.png")
        lines = ["| vertices | tolerance | solves | converged | solves per CPU second | balances checked | "
                 "median error / side | largest error / side |",
                 "|---|---|---|---|---|---|---|---|"]
        for r in acc:
            lines.append(f"| {r['vertices']} | {r['tolerance']} | {r['solves']} | {r['converged']} | "
                         f"{fmt(num(r['solves_per_cpu_second']))} | {r['checked']} | {fmt(num(r['median_error']))} | "
                         f"{fmt(num(r['max_error']))} |")
        tables["curved_drag_accuracy"] = "\n".join(lines)

    data = rows("curved_scaling.csv")
    if data:
        v = [num(r["vertices"]) for r in data]
        fig, ax = plt.subplots(figsize=(7, 4.5))
        # CPU time: the machine is shared, and wall time there is noise on top of one core's work.
        ax.loglog(v, [num(r["newton_iteration_cpu_seconds"]) for r in data], "o-", c="C0",
                  label="newton: one iteration")
        ax.loglog(v, [num(r["factorization_cpu_seconds"]) for r in data], "--", c="C0",
                  label="floor: one CHOLMOD factorisation")
        ax.loglog(v, [num(r["rk4_step_cpu_seconds"]) for r in data], "o-", c="C3", label="rk4: one step")
        ax.loglog(v, [num(r["rk4_floor_seconds"]) for r in data], "--", c="C3",
                  label="floor: bytes per step / triad bandwidth")
        finish(fig, ax, "vertices (grid sheet, seed scene 1's pull)", "CPU seconds (one core)",
               "Curved paper: time per step against vertex count (triad %.1f GB/s)"
               % (num(data[0]["triad_bytes_per_second"]) / 1e9), "curved_scaling.png")
        lines = ["CPU time of one core (wall time in brackets, shared machine).", "",
                 "| vertices | newton iteration | one CHOLMOD factorisation | ratio | rk4 step | its floor | ratio |",
                 "|---|---|---|---|---|---|---|"]
        for r in data:
            n, nc, f, fc, k, kc, kf = (num(r[c]) for c in (
                "newton_iteration_seconds", "newton_iteration_cpu_seconds", "factorization_seconds",
                "factorization_cpu_seconds", "rk4_step_seconds", "rk4_step_cpu_seconds", "rk4_floor_seconds"))
            lines.append(f"| {r['vertices']} | {fmt(nc * 1e3)} ms ({fmt(n * 1e3)}) | {fmt(fc * 1e3)} ms "
                         f"({fmt(f * 1e3)}) | {fmt(nc / fc)}× | {fmt(kc * 1e3)} ms ({fmt(k * 1e3)}) | "
                         f"{fmt(kf * 1e3)} ms | {fmt(kc / kf)}× |")
        tables["curved_scaling"] = "\n".join(lines)

    stab = rows("curved_stability.csv")
    if stab:
        fig, ax = plt.subplots(figsize=(7, 4.5))
        styles = {"converged": ("o", "C2"), "stalled": ("s", "C1"), "diverged": ("x", "C3")}
        for state, (marker, color) in styles.items():
            pts = [r for r in stab if (state == "diverged" and r["diverged"] == "1") or
                   (state == "converged" and r["diverged"] == "0" and r["converged"] == "1") or
                   (state == "stalled" and r["diverged"] == "0" and r["converged"] == "0")]
            ax.scatter([num(r["dt"]) for r in pts], [num(r["stretch"]) for r in pts], marker=marker, c=color, s=18,
                       label=f"rk4 {state}")
        limits = sorted({(num(r["stretch"]), num(r["dt_limit"])) for r in stab})
        ax.plot([p[1] for p in limits], [p[0] for p in limits], "k-", lw=1, label="predicted limit 2.83 / ω_max")
        ax.set_xscale("log")
        ax.set_yscale("log")
        ax.set_xlabel("step Δt")
        ax.set_ylabel("stretch modulus k")
        ax.legend(fontsize=8)
        ax.set_title("Stability map of the seed's RK4 on curved paper (scene 1)")
        save(fig, "curved_stability.png")
        inside = [r for r in stab if num(r["dt_over_limit"]) <= 1.0 + 1e-9]
        beyond = [r for r in stab if num(r["dt_over_limit"]) > 1.0 + 1e-9]
        first = {}
        for r in stab:
            if r["diverged"] == "1":
                k = num(r["stretch"])
                first[k] = min(first.get(k, math.inf), num(r["dt_over_limit"]))
        tables["curved_stability"] = (
            f"{len(stab)} (Δt, k) cells: inside the predicted limit {sum(r['diverged'] == '1' for r in inside)} of "
            f"{len(inside)} diverged; beyond it {sum(r['diverged'] == '1' for r in beyond)} of {len(beyond)}. "
            "Smallest diverging Δt / limit per stretch modulus: "
            + ", ".join(f"k = {fmt(k)}: {fmt(v)}" for k, v in sorted(first.items())) + ".")


def table_wall_time(tables):
    """bench_wall_time.csv: how long each part of the `make bench` run that wrote the files took."""
    data = rows("bench_wall_time.csv")
    if not data:
        return
    lines = ["| part | wall time | CPU time |", "|---|---|---|"]
    for r in data:
        name = "**whole run**" if r["step"] == "total" else f"`{r['step']}`"
        lines.append(f"| {name} | {fmt(num(r['wall_seconds']))} s | {fmt(num(r['cpu_seconds']))} s |")
    total = next((num(r["wall_seconds"]) for r in data if r["step"] == "total"), math.nan)
    lines.append("")
    lines.append(f"The run took {fmt(total / 60, 2)} minutes of wall time, "
                 f"{'within' if total < 20 * 60 else 'over'} the 20-minute budget (binaries already built; "
                 "a first `make bench` also builds the package).")
    tables["wall_time"] = "\n".join(lines)


def crossing(speed, default_nodes=None, target=30.0):
    """Where the small-pull drag's speed falls through `target` solves per CPU second: the
    largest sheet measured at or above it, and the size at the target on the log-log line
    between it and the next one measured."""
    pts = sorted((num(r["vertices"]), num(r["solves_per_cpu_second"])) for r in speed)
    fast = [p for p in pts if p[1] >= target]
    if not fast:
        return f"No sheet measured ({int(pts[0][0])} vertices the smallest) is dragged at {nice(target)} solves per CPU second."
    if len(fast) == len(pts):
        return f"Every sheet measured, up to {int(pts[-1][0])} vertices, is dragged at {nice(target)} solves per CPU second or more."
    (v0, r0) = max(fast)
    (v1, r1) = next(p for p in pts if p[0] > v0)
    at = v0 * math.exp(math.log(target / r0) * math.log(v1 / v0) / math.log(r1 / r0))
    default = (f"; the node's default mesh of the square (bubble, spacing 0.1) has {default_nodes}"
               if default_nodes else "")
    return (f"One core drags a sheet at {nice(target)} small pulls per CPU second up to about {nice(at)} vertices "
            f"(measured: {nice(r0)} per second at {int(v0)}, {nice(r1)} at {int(v1)}){default}.")


def nice(x):
    """A figure for prose: whole numbers from 10 up (with thousands separators), else two digits."""
    if x is None or not math.isfinite(x):
        return "–"
    return f"{x:,.0f}" if abs(x) >= 10 else f"{x:.2g}"


def span(values):
    values = [v for v in values if math.isfinite(v)]
    if not values:
        return "–"
    lo, hi = nice(min(values)), nice(max(values))
    return lo if lo == hi else f"{lo}–{hi}"


def conclusions(tables):
    """The conclusions, each a figure or ratio read from the CSVs of this run."""
    out = []
    et = rows("error_time.csv")
    if et:
        def first(solver, target):
            hits = [num(r["seconds"]) for r in et if r["solver"] == solver and r["diverged"] == "0"
                    and num(r["max_strain"]) < target]
            return min(hits) if hits else math.nan
        newton = first("newton", 1e-9)
        others = {s: first(s, 1e-9) for s in ("shape_matching", "rigid_kinematics", "seed_spring")}
        reached = {s: t for s, t in others.items() if math.isfinite(t)}
        out.append(f"- Rigid faces: `newton` is the default solver. On the Miura-ori fold step it reaches strain "
                   f"1e-9 in {nice(newton * 1e3)} ms; " +
                   ", ".join(f"`{s}` in {nice(t * 1e3)} ms ({nice(t / newton)}×)" for s, t in reached.items()) +
                   "".join(f"; `{s}` never" for s in others if s not in reached) +
                   " (error against time above). `rigid_kinematics` stays the ground truth (zero strain by "
                   "construction), `shape_matching` the fallback that needs no factorisation per iteration.")
    sv = rows("solvers.csv")
    if sv:
        scenes = list(dict.fromkeys(r["scene"] for r in sv))
        newton_ok = [r["scene"] for r in sv if r["solver"] == "newton" and r["converged"] == "1"]
        seed_ok = [r["scene"] for r in sv if r["solver"] == "seed_spring" and r["converged"] == "1"]
        speedups = [num(r["speedup_vs_seed"]) for r in sv if r["solver"] == "newton"]
        out.append(f"- Reference scenes ({len(scenes)}: {', '.join(scenes)}): `newton` converged on "
                   f"{len(newton_ok)} of {len(scenes)}, the seed's scheme at its own d = 0.2 on {len(seed_ok)}; "
                   f"against the seed's scheme at its largest stable d, where that converges, `newton` is "
                   f"{span(speedups)}× faster (fold-step table above).")
    st = rows("stability_map.csv")
    if st:
        seed = [r for r in st if r["solver"] == "seed_spring"]
        off = sum((r["converged"] == "1" and num(r["bound"]) >= 2) or (r["diverged"] == "1" and num(r["bound"]) < 2)
                  for r in seed)
        out.append(f"- The seed's explicit scheme is kept as the baseline only: in {len(seed)} (Δt, λ) cells of its "
                   f"stability map it diverged exactly where d·λ·Δt² ≥ 2 ({off} cells off that bound), so its step "
                   "shrinks as 1/√λ with the largest face, while the implicit solvers converge on every face.")
    sc = rows("scaling.csv")
    if sc:
        explicit = [num(r["explicit_step_seconds"]) / num(r["explicit_floor_seconds"]) for r in sc]
        implicit = [num(r["newton_iteration_seconds"]) / num(r["ldlt_seconds"]) for r in sc]
        out.append(f"- At scale the explicit step runs {span(explicit)}× its memory floor (its cost is the number "
                   f"of steps, not bandwidth), and a Newton iteration costs {span(implicit)}× one sparse "
                   "factorisation of the same system: the factorisation is the implicit floor, so Newton reuses "
                   "it across iterations.")
    cs = rows("curved_solvers.csv")
    if cs:
        steps = [r for r in cs if r["case"] == "pull_step"]
        rk = [r for r in steps if r["method"] == "rk4"]
        ratios = [num(r["rk4_time_over_newton"]) for r in steps if r["method"] == "newton"]
        out.append(f"- Curved paper: Newton is the default. RK4 reached the tolerance in {sum(r['converged'] == '1' for r in rk)} "
                   f"of {len(rk)} cases within its budget and took {span(ratios)}× Newton's time (a lower bound where "
                   "it ran out of budget).")
    sp = rows("curved_speed.csv")
    if sp:
        r = max(sp, key=lambda row: num(row["vertices"]))
        rate = num(r["solves_per_cpu_second"])
        out.append(f"- The target of 30 static solves per second of a small pull on a {r['vertices']}-vertex sheet "
                   f"on one core is {'met' if rate >= 30 else 'not met'}: {nice(rate)} per CPU second "
                   f"({nice(30 / rate) if rate < 30 else nice(rate / 30)}× {'short' if rate < 30 else 'over'}). "
                   f"The median solve takes {nice(num(r['median_solve_cpu_ms']))} ms of CPU "
                   f"({nice(1000 / num(r['median_solve_cpu_ms']))} per second); the {r['slow_solves']} solves "
                   f"over five times the median (the start off the flat sheet, the snaps) take "
                   f"{nice(num(r['slow_cpu_seconds']))} s of the {nice(num(r['cpu_seconds']))} s.")
        square = [m for m in (rows("meshers.csv") or []) if m["pattern"] == "square" and m["mesher"] == "bubble"
                  and num(m["spacing"]) == 0.1]
        out.append(f"- {crossing(sp, square[0]['nodes'] if square else None)}")
    acc = rows("curved_drag_accuracy.csv")
    if acc:
        by_rate = sorted(acc, key=lambda r: num(r["solves_per_cpu_second"]))
        slow, fast = by_rate[0], by_rate[-1]
        out.append(f"- Speed against accuracy of the drag ({acc[0]['vertices']} vertices): tolerances from "
                   f"{min(num(r['tolerance']) for r in acc):g} to {max(num(r['tolerance']) for r in acc):g} span only "
                   f"{nice(num(slow['solves_per_cpu_second']))}–{nice(num(fast['solves_per_cpu_second']))} solves per CPU "
                   f"second (fastest at {fast['tolerance']}, median error {nice(num(fast['median_error']))} of the side), "
                   f"while the median error spans {nice(min(num(r['median_error']) for r in acc))}–"
                   f"{nice(max(num(r['median_error']) for r in acc))}: a looser tolerance buys little speed "
                   "(docs/CURVED.md, Speed against sheet size and tolerance); the default 1e-8 stays.")
    ms = rows("meshers.csv")
    if ms:
        def share(m):
            return [num(r["share_45_75"]) for r in ms if r["mesher"] == m]
        finest = {}
        for r in ms:
            key = r["pattern"]
            if key not in finest or num(r["spacing"]) < finest[key]:
                finest[key] = num(r["spacing"])
        speed = []
        for pattern, h in finest.items():
            t = {r["mesher"]: num(r["mesh_ms"]) for r in ms if r["pattern"] == pattern and num(r["spacing"]) == h}
            if "bubble" in t and "cgal" in t:
                speed.append(t["bubble"] / t["cgal"])
        better = sum(1 for p in {(r["pattern"], r["spacing"]) for r in ms}
                     if (lambda b, c: b and c and num(b[0]["share_45_75"]) > num(c[0]["share_45_75"]))(
                         [r for r in ms if (r["pattern"], r["spacing"]) == p and r["mesher"] == "bubble"],
                         [r for r in ms if (r["pattern"], r["spacing"]) == p and r["mesher"] == "cgal"]))
        cases = len({(r["pattern"], r["spacing"]) for r in ms})
        out.append(f"- Meshers: the bubble mesh has the larger share of triangles with every angle in 45–75° in "
                   f"{better} of {cases} cases (share {span(share('bubble'))} against {span(share('cgal'))}); "
                   f"CGAL's mesher is {span(speed)}× faster at the finest spacing. The bubble mesh is the default at "
                   "the node's spacing (0.1 of the sheet); CGAL for fine meshes and corners under 20° "
                   "(docs/CURVED.md, Meshing).")
    mr = rows("mesh_resolution.csv")
    if mr:
        # The finest row of each mesher is its reference (no next finer mesh): left out.
        measured = {m: sorted((r for r in mr if r["mesher"] == m and math.isfinite(num(r["rms_to_next"]))),
                              key=lambda r: -num(r["spacing"])) for m in ("bubble", "cgal")}
        if all(measured.values()):
            def fall(m):
                pts = measured[m]
                return (f"{fmt(num(pts[0]['rms_to_finest']), 2)} → {fmt(num(pts[-1]['rms_to_finest']), 2)} "
                        f"({m}, {nice(num(pts[0]['rms_to_finest']) / num(pts[-1]['rms_to_finest']))}-fold)")
            rises = [f"{m} {a['spacing']} → {b['spacing']}" for m, pts in measured.items() for a, b in zip(pts, pts[1:])
                     if num(b["rms_to_finest"]) > num(a["rms_to_finest"])]
            unbalanced = [f"{r['mesher']} {r['spacing']}" for r in mr if r["balanced"] != "1"]
            out.append(f"- Mesh resolution: on seed scene 1 pulled until its corner has turned {180 * num(mr[0]['pull']):g}° "
                       f"(bending q/k = {mr[0]['bend_q_over_k']}) the RMS distance to each mesher's finest "
                       f"solution falls from spacing {measured['bubble'][0]['spacing']} to "
                       f"{measured['bubble'][-1]['spacing']}: {fall('bubble')}, {fall('cgal')} of the side" +
                       (f"; it rises on {', '.join(rises)}" if rises else ", at every refinement") +
                       (f". Not balanced: {', '.join(unbalanced)}." if unbalanced else "; every solve balanced."))
        bubble = measured["bubble"]
        default = next((r for r in bubble if abs(num(r["spacing"]) - 0.1) < 1e-9), None)
        best = min(bubble, key=lambda r: num(r["rms_to_finest"])) if bubble else None
        if default and best:
            out.append(f"- Resolution: at the default spacing 0.1 the bubble mesh is "
                       f"{fmt(num(default['rms_to_finest']), 2)} of the side from its finest solution in "
                       f"{nice(num(default['cpu_seconds']))} s of CPU; the sweep's least distance, "
                       f"{fmt(num(best['rms_to_finest']), 2)} at spacing {best['spacing']}, takes "
                       f"{nice(num(best['cpu_seconds']) / num(default['cpu_seconds']))}× as long. Spacing 0.1 is "
                       "kept for interactive display; ask for a finer one "
                       "(`spacing`) where millimetres matter.")
    rp = rows("replay.csv")
    if rp:
        crane = next((r for r in rp if r["model"] == "crane"), rp[0])
        out.append(f"- Replay: the {crane['model']}'s {crane['operations']} operations replay in "
                   f"{nice(num(crane['replay_ms']))} ms, {nice(num(crane['speedup']))}× faster than recorded (target "
                   f"100×); of the {len(rp)} models replayed the least is {nice(min(num(r['speedup']) for r in rp))}× "
                   "faster.")
    if out:
        tables["conclusions"] = "\n".join(out)


# ---- Hardening: journal, memory, contention -------------------------------------------------

FRAME_MS = 1000 / 60  # one 60 Hz frame: an answer within it feels immediate


def chart_journal(tables):
    """journal.csv: one append of a whole state with fsync on and off, fsync and formatting alone."""
    data = rows("journal.csv")
    if not data:
        return
    v = [num(r["vertices"]) for r in data]
    fig, ax = plt.subplots(figsize=(7, 4.5))
    for key, label, style, color in (("sync", "append, fsync on (default)", "o-", "C3"),
                                     ("nosync", "append, fsync off", "s-", "C0")):
        ax.loglog(v, [num(r[f"{key}_median_ms"]) for r in data], style, c=color, label=f"{label}: median")
        ax.loglog(v, [num(r[f"{key}_p95_ms"]) for r in data], style[0] + ":", c=color, alpha=0.7,
                  label=f"{label}: p95")
    ax.loglog(v, [num(r["fsync_median_ms"]) for r in data], "^--", c="C2", label="fsync of the line alone: median")
    ax.loglog(v, [num(r["format_median_ms"]) for r in data], "v--", c="C7", label="JSON of the state alone: median")
    ax.axhline(FRAME_MS, c="k", lw=1, ls=":", label="one 60 Hz frame")
    finish(fig, ax, "vertices (flat grid sheet, every inner edge an F crease)", "milliseconds per append",
           "Journaling one operation (whole state per line), %s" % data[0]["filesystem"], "journal.png")

    lines = ["| vertices | line | fsync on: median | p95 | fsync off: median | p95 | fsync alone: median | p95 | "
             "JSON alone |", "|---|---|---|---|---|---|---|---|---|"]
    for r in data:
        lines.append(f"| {int(num(r['vertices'])):,} | {fmt(num(r['line_bytes']) / 1e6)} MB | "
                     f"{fmt(num(r['sync_median_ms']))} ms | {fmt(num(r['sync_p95_ms']))} ms | "
                     f"{fmt(num(r['nosync_median_ms']))} ms | {fmt(num(r['nosync_p95_ms']))} ms | "
                     f"{fmt(num(r['fsync_median_ms']))} ms | {fmt(num(r['fsync_p95_ms']))} ms | "
                     f"{fmt(num(r['format_median_ms']))} ms |")
    fsync = [num(r["fsync_median_ms"]) for r in data]
    # fsync's share of a synced append: the fsync alone against the unsynced append plus it.
    share = [num(r["fsync_median_ms"]) / (num(r["fsync_median_ms"]) + num(r["nosync_median_ms"])) for r in data]
    quick = [r for r in data if num(r["sync_median_ms"]) < FRAME_MS]
    slow_fsync = [r for r in data if num(r["fsync_median_ms"]) >= FRAME_MS]
    first, largest = data[0], data[-1]
    lines.append("")
    lines.append(
        f"fsync of one appended line, measured alone, takes {span(fsync)} ms (median) across the sizes. Against the "
        f"append without it ({fmt(num(first['nosync_median_ms']))} ms at {int(num(first['vertices'])):,} vertices, "
        f"{fmt(num(largest['nosync_median_ms']))} ms at {int(num(largest['vertices'])):,}) that is "
        f"{nice(100 * share[0])} % of a synced append at the smallest model and {nice(100 * share[-1])} % at the "
        f"largest, where formatting the whole state as JSON ({fmt(num(largest['format_median_ms']))} ms for a "
        f"{fmt(num(largest['line_bytes']) / 1e6)} MB line) is the cost. " +
        (f"Synced, an append's median stays within one 60 Hz frame up to {int(num(quick[-1]['vertices'])):,} "
         "vertices. " if quick else "No synced append's median stays within one 60 Hz frame. ") +
        ("fsync stays under a frame at every size measured: `journal_sync` true is affordable as the default "
         "at every size; what limits large models is the whole state written per operation, not fsync."
         if not slow_fsync else
         "fsync alone takes a frame or more from " + f"{int(num(slow_fsync[0]['vertices'])):,}" +
         " vertices: there `journal_sync` false trades the last operations before a machine crash for speed."))
    tables["journal"] = "\n".join(lines)


def chart_memory(tables):
    """memory.csv: resident memory of a session against model size and history, with and without a
    history limit; a FOLD file read through loadPaper."""
    data = rows("memory.csv")
    if not data:
        return
    sessions = [r for r in data if r["case"] == "session"]
    fold = [r for r in data if r["case"] == "fold_load"]
    limits = sorted({num(r["limit_mb"]) for r in sessions})
    fig, axes = plt.subplots(1, len(limits), figsize=(11, 4.5), sharey=True)
    axes = axes if len(limits) > 1 else [axes]
    for ax, limit in zip(axes, limits):
        for k, history in enumerate(sorted({int(num(r["history"])) for r in sessions})):
            rs = sorted((r for r in sessions if num(r["limit_mb"]) == limit and int(num(r["history"])) == history),
                        key=lambda r: num(r["vertices"]))
            v = [num(r["vertices"]) for r in rs]
            ax.loglog(v, [num(r["rss_mb"]) for r in rs], "o-", c=f"C{k}", label=f"{history} commits: resident")
            ax.loglog(v, [num(r["paper_approx_mb"]) + num(r["history_approx_mb"]) for r in rs], "--", c=f"C{k}",
                      alpha=0.7, label=f"{history} commits: approximateBytes")
        if limit > 0:
            ax.axhline(limit, c="k", lw=1, ls=":", label=f"history_memory_mb {fmt(limit)}")
        else:
            for r in fold:
                ax.loglog([num(r["vertices"])], [num(r["rss_mb"])], "kx", ms=9, label="FOLD file read: resident")
                ax.loglog([num(r["vertices"])], [num(r["rss_trimmed_mb"])], "k+", ms=11,
                          label="… after malloc_trim(0)")
        ax.set_title("no history limit" if limit == 0 else f"history limit {fmt(limit)} MB", fontsize=10)
        ax.set_xlabel("vertices (flat grid sheet)")
        ax.grid(True, which="both", alpha=0.3)
        ax.legend(fontsize=7)
    axes[0].set_ylabel("MB")
    fig.suptitle("Resident memory of a session against model size, one line per undo history length")
    save(fig, "memory.png")

    lines = ["| case | vertices | commits | limit | resident | after malloc_trim | peak | approximateBytes "
             "(state + history) | resident − start / approximateBytes | undo states kept (forgotten) |",
             "|---|---|---|---|---|---|---|---|---|---|"]
    for r in data:
        approx = num(r["paper_approx_mb"]) + num(r["history_approx_mb"])
        own = num(r["rss_mb"]) - num(r["baseline_mb"])
        name = "session" if r["case"] == "session" else f"FOLD file ({fmt(num(r['file_mb']))} MB) read"
        lines.append(f"| {name} | {int(num(r['vertices'])):,} | {r['history']} | "
                     f"{'none' if num(r['limit_mb']) == 0 else fmt(num(r['limit_mb'])) + ' MB'} | "
                     f"{fmt(num(r['rss_mb']))} MB | {fmt(num(r['rss_trimmed_mb']))} MB | {fmt(num(r['peak_mb']))} MB | "
                     f"{fmt(approx)} MB | {fmt(own / approx)}× | "
                     f"{r['undo_states_kept']} ({r['forgotten']}) |")
    big = [r for r in sessions if num(r["history"]) > 0 and num(r["vertices"]) >= 1e4]
    ratios = [(num(r["rss_trimmed_mb"]) - num(r["baseline_mb"])) /
              (num(r["paper_approx_mb"]) + num(r["history_approx_mb"])) for r in big]
    text = [f"Resident memory (after malloc_trim, less the process's start) is {span(ratios)}× what "
            "approximateBytes counts, for sessions of 10,000 vertices and more with a history: the count leaves "
            "out the allocator's overhead of every face's two small vectors."]
    limited = [r for r in sessions if num(r["limit_mb"]) > 0 and int(r["forgotten"]) > 0]
    if limited:
        r = max(limited, key=lambda q: num(q["rss_mb"]))
        counted = num(r["paper_approx_mb"]) + num(r["history_approx_mb"])
        text.append(
            f"With history_memory_mb {fmt(num(r['limit_mb']))}, the {int(num(r['vertices'])):,}-vertex session after "
            f"{r['history']} commits kept {r['undo_states_kept']} undo states ({fmt(num(r['history_approx_mb']))} MB "
            f"counted, forgot {r['forgotten']}); with the current state that is {fmt(counted)} MB counted and "
            f"{fmt(num(r['rss_mb']))} MB resident ({fmt(num(r['rss_trimmed_mb']))} MB after malloc_trim): "
            f"{fmt(num(r['rss_mb']) / num(r['limit_mb']))}× the limit. The limit holds the undo and redo states "
            "alone, not the current one, and counts approximate bytes: set it with that margin.")
    for r in fold:
        slack = num(r["rss_mb"]) - num(r["rss_trimmed_mb"])
        text.append(
            f"Reading a {int(num(r['vertices'])):,}-vertex FOLD file ({fmt(num(r['file_mb']))} MB) through loadPaper "
            f"peaks at {fmt(num(r['peak_mb']))} MB and leaves {fmt(num(r['rss_mb']))} MB resident for a "
            f"{fmt(num(r['paper_approx_mb']))} MB paper; malloc_trim(0) gives back {fmt(slack)} MB "
            f"({fmt(num(r['rss_trimmed_mb']))} MB left): freed memory of the parse that glibc keeps.")
    tables["memory"] = "\n".join(lines) + "\n\n" + "\n\n".join(text)


OLD_PROBE = {"p50": 441.0, "p99": 3000.0}  # crease under 4 clients before solves left the lock (outside probe)


def chart_contention(tables, name="contention", solver="slow solver"):
    """<name>.csv, <name>_refusals.csv: call latency at paper_model with 2 creasing and 2
    rotating clients, against each group alone."""
    data = rows(name + ".csv")
    if not data:
        return
    refusals = rows(name + "_refusals.csv") or []
    labels = [f"{r['phase']}\n{r['operation'].replace('_', ' ')}" for r in data]
    x = range(len(data))
    fig, ax = plt.subplots(figsize=(10, 4.8))
    width = 0.2
    for k, (key, color) in enumerate((("p50_ms", "C0"), ("p95_ms", "C1"), ("p99_ms", "C3"), ("max_ms", "C7"))):
        ax.bar([i + (k - 1.5) * width for i in x], [num(r[key]) for r in data], width, color=color,
               label=key.replace("_ms", ""))
    for i, r in zip(x, data):
        if int(r["refused"]):
            ax.annotate(f"{r['refused']}/{r['calls']} refused", (i, num(r["max_ms"])), textcoords="offset points",
                        xytext=(0, 4), ha="center", fontsize=7)
    ax.set_yscale("log")
    ax.set_xticks(list(x))
    ax.set_xticklabels(labels, fontsize=7)
    ax.set_ylabel("call latency at the client [ms]")
    ax.grid(True, axis="y", which="both", alpha=0.3)
    ax.legend(fontsize=8)
    ax.set_title(f"paper_model under contention: 2 creasing clients, 2 rotating clients ({solver})")
    save(fig, name + ".png")

    lines = ["| phase | operation | calls | refused | p50 | p95 | p99 | max |", "|---|---|---|---|---|---|---|---|"]
    for r in data:
        lines.append(f"| {r['phase']} | {r['operation'].replace('_', ' ')} | {r['calls']} | {r['refused']} | "
                     f"{fmt(num(r['p50_ms']))} ms | {fmt(num(r['p95_ms']))} ms | {fmt(num(r['p99_ms']))} ms | "
                     f"{fmt(num(r['max_ms']))} ms |")
    if refusals:
        lines += ["", "Refusals, by message:", ""]
        for r in refusals:
            lines.append(f"- {r['phase']}, {r['operation'].replace('_', ' ')}: {r['count']} × “{r['message']}”")

    def find(phase, operation):
        return next((r for r in data if r["phase"] == phase and r["operation"] == operation), None)

    alone, mixed = find("crease_alone", "crease"), find("mixed", "crease")
    text = []
    if alone and mixed:
        text.append(
            f"Creases while two clients turn the model (every turn a solve): p50 {fmt(num(mixed['p50_ms']))} ms, "
            f"p99 {fmt(num(mixed['p99_ms']))} ms, against p50 {fmt(num(alone['p50_ms']))} ms, p99 "
            f"{fmt(num(alone['p99_ms']))} ms with the creasing clients alone (max {fmt(num(mixed['max_ms']))} and "
            f"{fmt(num(alone['max_ms']))} ms). Before solver-bound operations left the lock an outside probe "
            f"measured p50 {nice(OLD_PROBE['p50'])} ms and p99 {fmt(OLD_PROBE['p99'] / 1e3)} s under 4 clients: a "
            f"crease no longer waits for another client's solve ({nice(OLD_PROBE['p99'] / num(mixed['p99_ms']))}× "
            "lower p99).")
    def refused_as(phase, words):
        return sum(int(r["count"]) for r in refusals
                   if r["phase"] == phase and r["operation"] == "rotate" and words in r["message"])

    for phase, pace in (("mixed", "back to back"), ("mixed_paced", "with a pause between pairs")):
        turn, c, u = find(phase, "rotate"), find(phase, "crease"), find(phase, "undo")
        if not (turn and c and u):
            continue
        rate = (int(c["succeeded"]) + int(u["succeeded"])) / num(c["phase_wall_s"])
        stale = refused_as(phase, "kept changing")
        text.append(
            f"Creasing clients {pace} ({nice(rate)} commits a second): {turn['succeeded']} of {turn['calls']} turns "
            f"committed, {stale} refused because the model kept changing and {int(turn['refused']) - stale} by the "
            f"solver (its budget or `solver_timeout`); a turn answered in {fmt(num(turn['p50_ms']) / 1e3)} s (p50) "
            f"and {fmt(num(turn['p99_ms']) / 1e3)} s (p99); creases p50 {fmt(num(c['p50_ms']))} ms, p99 "
            f"{fmt(num(c['p99_ms']))} ms, max {fmt(num(c['max_ms']))} ms.")
    solo = find("rotate_alone", "rotate")
    if solo:
        text.append(
            f"The two rotating clients alone: p50 {fmt(num(solo['p50_ms']))} ms, {solo['refused']} of {solo['calls']} "
            "refused (spring_solver solves one at a time). A solver-bound operation computed on a model that "
            "another client changed meanwhile is computed again; the last of its 3 tries (`solve_attempts`) "
            "computes with the model locked, so that it lands even while others commit faster than a solve takes "
            "(an earlier version without that lock had 20 of 20 turns refused back to back). The price is in the "
            "creases' tail: a crease that arrives during such a locked try waits for that one solve — the max "
            "above, and with a slow solver at a person's pace the p95 — while the median crease never waits.")
    tables[name] = "\n".join(lines) + "\n\n" + "\n\n".join(text)


DRIVER_COLORS = {"quasi_newton": "C0", "newton": "C2", "constant_lbfgs": "C1"}


def chart_fold(tables):
    """Fold by assignment at scale (fold_bench): preview frame and commit against vertex count
    beside the floor, error against CPU time at the largest size, and the rigid solvers' turn."""
    data = rows("fold_scaling.csv")
    if not data:
        return
    drivers = sorted({r["driver"] for r in data}, key=lambda d: list(DRIVER_COLORS).index(d)
                     if d in DRIVER_COLORS else 9)
    fig, (left, right, strain) = plt.subplots(1, 3, figsize=(17, 4.5))
    for d in drivers:
        pts = [(num(r["vertices"]), num(r["frame_p95_ms"]), num(r["commit_s"]), num(r.get("slide_p95_ms", "")),
                num(r.get("slide_max_strain", ""))) for r in data if r["driver"] == d]
        ok = [p for p in pts if math.isfinite(p[1])]
        left.loglog([p[0] for p in ok], [p[1] for p in ok], "o-", c=DRIVER_COLORS.get(d), label=f"{d}: frame p95")
        ok = [p for p in pts if math.isfinite(p[3])]
        left.loglog([p[0] for p in ok], [p[3] for p in ok], "s--", c=DRIVER_COLORS.get(d),
                    label=f"{d}: slide frame p95 (30 ms budget)")
        ok = [p for p in pts if math.isfinite(p[4])]
        strain.loglog([p[0] for p in ok], [p[4] for p in ok], "s--", c=DRIVER_COLORS.get(d), label=d)
        ok = [p for p in pts if math.isfinite(p[2])]
        right.loglog([p[0] for p in ok], [p[2] for p in ok], "o-", c=DRIVER_COLORS.get(d), label=d)
    sizes = sorted({num(r["vertices"]) for r in data})
    floors = [next(num(r["floor_ms"]) for r in data if num(r["vertices"]) == v) for v in sizes]
    left.loglog(sizes, floors, "k--", label="floor: one back-substitution + one gradient")
    left.axhline(33, c="gray", ls=":", label="33 ms (30 frames a second)")
    right.axhline(1.0, c="gray", ls=":", label="1 s")
    left.set_xlabel("vertices (Miura-ori)")
    left.set_ylabel("CPU ms per frame, 1 % further")
    left.grid(True, which="both", alpha=0.3)
    left.legend(fontsize=7)
    left.set_title("Preview frame against vertex count, one core")
    right.set_xlabel("vertices (Miura-ori)")
    right.set_ylabel("CPU s to commit 1 % further (strain 1e-9 where rigid)")
    right.grid(True, which="both", alpha=0.3)
    right.legend(fontsize=7)
    right.set_title("Commit against vertex count, one core")
    strain.axhline(1e-3, c="gray", ls=":", label="strain 1e-3")
    strain.set_xlabel("vertices (Miura-ori)")
    strain.set_ylabel("largest strain of any frame")
    strain.grid(True, which="both", alpha=0.3)
    strain.legend(fontsize=7)
    strain.set_title("A slide 30 → 100 % in 30 ms frames: strain shown")
    save(fig, "fold_scaling.png")

    def commit_range(r):
        low, high = num(r.get("commit_min_s", "")), num(r.get("commit_max_s", ""))
        return "" if math.isnan(low) or math.isnan(high) else f" ({fmt(low)}–{fmt(high)})"

    lines = ["| vertices | driver | frame p50 | frame p95 | frame strain | frames balanced | commit (median of 3: min–max) | commit strain | "
             "rigid | floor | slide (30 ms frames): p95 | slide strain |", "|---|---|---|---|---|---|---|---|---|---|---|---|"]
    for r in data:
        lines.append(f"| {int(num(r['vertices']))} | {r['driver']} | {fmt(num(r['frame_p50_ms']))} ms | "
                     f"{fmt(num(r['frame_p95_ms']))} ms | {fmt(num(r['frame_max_strain']))} | {r['frames_balanced']}/10 | "
                     f"{fmt(num(r['commit_s']))} s{commit_range(r)} | {fmt(num(r['commit_strain']))} | "
                     f"{'yes' if r['commit_rigid'] == '1' else 'no'} | {fmt(num(r['floor_ms']))} ms | "
                     f"{fmt(num(r.get('slide_p95_ms', '')))} ms | {fmt(num(r.get('slide_max_strain', '')))} |")
    text = []
    et = rows("fold_error_time.csv")
    if et:
        fig, ax = plt.subplots(figsize=(7, 4.5))
        for d in drivers:
            pts = [(num(r["cpu_s"]), num(r["error"])) for r in et if r["driver"] == d and num(r["error"]) > 0]
            if pts:
                ax.loglog([p[0] * 1e3 for p in pts], [p[1] for p in pts], "o-", c=DRIVER_COLORS.get(d), label=d)
        ax.axvline(33, c="gray", ls=":", label="33 ms")
        finish(fig, ax, "CPU ms (one solve, 1 % further, stopped after k iterations)",
               "max vertex error / sheet size", "Error against time at %d vertices" % int(num(et[0]["vertices"])),
               "fold_error_time.png")
        for d in drivers:
            within = [num(r["error"]) for r in et if r["driver"] == d and num(r["cpu_s"]) <= 0.033]
            if within:
                text.append(f"Within 33 ms at {int(num(et[0]['vertices']))} vertices, {d} comes to "
                            f"{fmt(min(within))} of the sheet from the balanced frame.")
    turn = rows("fold_turn.csv")
    if turn:
        text.append("A 10° turn of a corner face of a 40 × 40 Miura-ori (rotate, the turned face held): " + "; ".join(
            f"{r['solver']} turn {r['turn']}: {fmt(num(r['cpu_s']))} s CPU"
            f"{'' if r['converged'] == '1' else ' (not converged)'}" for r in turn) + ".")
    tables["fold"] = "\n".join(lines) + ("\n\n" + "\n\n".join(text) if text else "")


GESTURES = {
    "vertex_drag": "vertex drag, a wing's tip (its faces hinge on the axis): drag_vertex preview + markers",
    "vertex_drag_stack": "vertex drag, the stack's far corner (the solver carries every layer): drag_vertex "
                         "preview + markers",
    "flat_fold_frame": "flat fold: one animation frame + markers",
    "rotate_stack": "rotation carrying a stack: ring + rotate preview + markers",
    "pick_vertex": "interaction: press on a vertex (verticesUnder + pick markers)",
    "pick_face": "interaction: press on a face (facesUnder + pick markers)",
    "mark_crease": "interaction: click on a crease (creasesUnder + chosenCreaseMarkers)",
}
GESTURE_BUDGET_MS = 33.0


def chart_gestures(tables):
    """gesture_latency.csv (gesture_bench): each pointer event of the crane's gestures, from the event
    to the serialized markers, on the crane at its most layered state; p95 against 33 ms."""
    data = rows("gesture_latency.csv")
    if not data:
        return
    first = data[0]
    names = [r["gesture"] for r in data]
    x = range(len(data))
    fig, ax = plt.subplots(figsize=(9, 4.5))
    width = 0.38
    ax.bar([i - width / 2 for i in x], [num(r["median_ms"]) for r in data], width, color="C0", label="median")
    ax.bar([i + width / 2 for i in x], [num(r["p95_ms"]) for r in data], width, color="C1", label="p95")
    ax.axhline(GESTURE_BUDGET_MS, c="k", lw=1, ls=":", label="33 ms (30 frames a second)")
    ax.set_yscale("log")
    ax.set_xticks(list(x))
    ax.set_xticklabels(names, rotation=20, ha="right")
    ax.set_ylabel("milliseconds per pointer event (wall, one core)")
    ax.grid(True, which="both", axis="y", alpha=0.3)
    ax.legend(fontsize=8)
    ax.set_title("Crane gestures: preview latency (%s vertices, %s faces, %s layers)"
                 % (first["vertices"], first["faces"], first["layers"]))
    save(fig, "gesture_latency.png")

    lines = ["| gesture | what one event does | events | refused | median | p95 | max | p95 ≤ 33 ms |",
             "|---|---|---|---|---|---|---|---|"]
    for r in data:
        lines.append(f"| `{r['gesture']}` | {GESTURES.get(r['gesture'], '')} | {r['events']} | {r.get('refused', '–')} | "
                     f"{fmt(num(r['median_ms']))} ms | {fmt(num(r['p95_ms']))} ms | {fmt(num(r['max_ms']))} ms | "
                     f"{'yes' if num(r['p95_ms']) <= GESTURE_BUDGET_MS else '**no**'} |")
    previews = [r for r in data if not r["gesture"].startswith(("pick_", "mark_"))]
    over = [r for r in previews if num(r["p95_ms"]) > GESTURE_BUDGET_MS]
    slowest = max(previews, key=lambda r: num(r["p95_ms"])) if previews else None
    lines.append("")
    if slowest:
        lines.append(
            f"On the crane at its most layered state ({first['vertices']} vertices, {first['faces']} faces, "
            f"{first['layers']} layers over one point), the slowest gesture's p95 is {fmt(num(slowest['p95_ms']))} ms "
            f"(`{slowest['gesture']}`): " +
            ("every gesture's preview is within 33 ms at p95 on one core (target met)" +
             (f"; the slowest single event took {fmt(max(num(r['max_ms']) for r in previews))} ms."
              if any(num(r["max_ms"]) > GESTURE_BUDGET_MS for r in previews) else ".") if not over else
             ", ".join(f"`{r['gesture']}`" for r in over) + " over 33 ms at p95 (target not met)."))
    for r in previews:
        if num(r.get("refused")) > 0:
            lines.append("")
            lines.append(f"`{r['gesture']}`: {int(num(r['refused']))} of {r['events']} previews refused (the solver "
                         "did not reach its tolerance within spring_solver's limits; the preview on show stays the "
                         "last one), timed all the same: the user waits for a refusal as for a preview.")
    tables["gestures"] = "\n".join(lines)


USER_ACTIONS = [
    ("load", "load the FOLD file (`load`)"),
    ("fold_commit", "`fold_by_assignment` commit from the flat pattern"),
    ("slider_preview", "slider moved 1 % (0→40 %) or 5 % (0→100 %): the preview (feedback → interaction → "
                       "`fold_by_assignment` preview)"),
    ("slider_release_40", "slider let go at 40 %: the commit from the last preview"),
    ("slider_release_100", "slider let go at 100 %: the commit from the last preview"),
    ("slider_flick_preview", "slider flicked from 0 to 100 % in one move: its one preview"),
    ("slider_flick_release", "the flicked slider let go at once: the commit from that preview"),
    ("slider_flick_held_release", "the flicked slider held still for 0.5 s (its previews catching up with the "
                                  "handle), then let go: the commit"),
    ("turn_preview", "`rotate` preview of the corner face, 0.5°, 1°, … 10° (a mouse's drag; `turn_steps`)"),
    ("turn_commit", "`rotate` commit, 10°"),
    ("drag_vertex_preview", "`drag_vertex` preview, the corner vertex lifted 0.4 % of the sheet a step to 2 % (40 % state)"),
    ("drag_vertex_commit", "`drag_vertex` commit, 2 %"),
    ("drag_preview", "the same lift with the mouse in drag mode: each move's preview (feedback → interaction → "
                     "`drag_vertex`)"),
    ("drag_commit", "the mouse let go: the drag's commit"),
]


def percentile(values, p):
    v = sorted(x for x in values if math.isfinite(x))
    if not v:
        return math.nan
    return v[min(len(v) - 1, int(p * (len(v) - 1) + 0.5))]


def ms(x):
    """Milliseconds as the tables give them: ms below 1 s, else s."""
    if not math.isfinite(x):
        return "–"
    return f"{fmt(x)} ms" if x < 1000 else f"{fmt(x / 1000)} s"


def chart_user_path(tables):
    """user_path.csv and user_path_breakdown.csv (user_path_bench): origami.launch's nodes driven
    through their services and the interaction node's feedback, request to answer and to markers;
    beside fold_bench's in-process figures; the breakdown of where the time goes."""
    data = rows("user_path.csv")
    if not data:
        return
    sync = [r for r in data if r["configuration"] == "journal_sync"]
    groups = {}
    for r in sync:
        action = r["action"]
        if action == "fold_commit":
            action = f"fold_commit {round(100 * num(r['step']))} %"
        groups.setdefault((r["pattern"], int(num(r["vertices"]))), {}).setdefault(action, []).append(r)
    order = [a for a, _ in USER_ACTIONS]

    def action_key(a):
        return (order.index(a.split()[0]) if a.split()[0] in order else 99, a)

    lines = ["| pattern | vertices | action | n | answer: median | p95 | max | markers: median | p95 | max | "
             "refused | CPU median: paper_model | spring_solver | curved_mesh_solver |",
             "|---|---|---|---|---|---|---|---|---|---|---|---|---|---|"]
    for (pattern, vertices), actions in sorted(groups.items(), key=lambda kv: (kv[0][0] != "miura_70", kv[0])):
        for action in sorted(actions, key=action_key):
            rs = actions[action]
            ok = [r for r in rs if r["success"] == "1"]
            answer = [num(r["answer_ms"]) for r in rs]
            markers = [num(r["markers_ms"]) for r in ok]
            cpu = lambda col: percentile([num(r[col]) for r in ok], 0.5)  # noqa: E731
            lines.append(
                f"| {pattern} | {vertices:,} | `{action}` | {len(rs)} | {ms(percentile(answer, 0.5))} | "
                f"{ms(percentile(answer, 0.95))} | {ms(max(answer) if answer else math.nan)} | "
                f"{ms(percentile(markers, 0.5))} | {ms(percentile(markers, 0.95))} | "
                f"{ms(max(markers) if markers else math.nan)} | {len(rs) - len(ok)} | {ms(cpu('paper_model_cpu_ms'))} | "
                f"{ms(cpu('spring_solver_cpu_ms'))} | {ms(cpu('curved_mesh_solver_cpu_ms'))} |")
    refusals = {}
    for r in sync:
        if r["success"] != "1":
            refusals.setdefault((r["pattern"], r["vertices"], r["action"]), r["message"])
    if refusals:
        lines.append("")
        lines.append("Refused or unanswered: " + "; ".join(
            f"{p} {int(num(v)):,} `{a}`: “{m}”" for (p, v, a), m in sorted(refusals.items())) + ".")
    lines.append("")
    lines.append("Actions: " + "; ".join(f"`{a}`: {d}" for a, d in USER_ACTIONS) + ".")
    tables["user_path"] = "\n".join(lines)

    # Where the time goes, read first: the breakdown CSV also holds the release computed in process.
    parts = rows("user_path_breakdown.csv") or []
    found = {}
    for r in parts:
        if r["configuration"] == "journal_sync":
            found.setdefault((r["pattern"], int(num(r["vertices"]))), {})[r["quantity"]] = num(r["value"])

    # Beside the in-process figures (fold_bench, quasi_newton: paper_model's crease driver).
    fold = {int(num(r["vertices"])): r for r in rows("fold_scaling.csv") or [] if r["driver"] == "quasi_newton"}
    turn = rows("fold_turn.csv") or []
    guided = [num(r["cpu_s"]) * 1e3 for r in turn if r["solver"].startswith("newton guided")]
    miura = sorted(v for (p, v) in groups if p == "miura_70")
    side = ["| vertices | slider preview, user's path: median / p95 | fold_bench: frame of a slide, p95 CPU "
            "(its nearest size) | slider released at 40 %, user's path | the same release in process: wall / CPU | "
            "fold_bench: commit 1 % on, CPU | 10° turn commit, user's path | fold_bench: turn, guided, first / third "
            "(1,681 vertices) |", "|---|---|---|---|---|---|---|---|"]
    for v in miura:
        a = groups[("miura_70", v)]
        q = found.get(("miura_70", v), {})
        near = min(fold, key=lambda n: abs(n - v)) if fold else None
        previews = [num(r["markers_ms"]) for r in a.get("slider_preview", []) if r["success"] == "1"]
        release = [num(r["markers_ms"]) for r in a.get("slider_release_40", []) if r["success"] == "1"]
        turned = [num(r["markers_ms"]) for r in a.get("turn_commit", []) if r["success"] == "1"]
        side.append(
            f"| {v:,} | {ms(percentile(previews, 0.5))} / {ms(percentile(previews, 0.95))} | "
            + (f"{ms(num(fold[near]['slide_p95_ms']))} ({near:,}) | " if near else "– | ")
            + f"{ms(release[0]) if release else '–'} | "
            f"{ms(q.get('commit_40_in_process_ms', math.nan))} / {ms(q.get('commit_40_in_process_cpu_ms', math.nan))} | "
            + (f"{ms(num(fold[near]['commit_s']) * 1e3)} | " if near else "– | ")
            + f"{ms(turned[0]) if turned else '–'} | "
            f"{(ms(guided[0]) + ' / ' + ms(guided[-1])) if guided else '–'} |")
    said = []
    for v in miura:
        release = [num(r["markers_ms"]) for r in groups[("miura_70", v)].get("slider_release_40", [])
                   if r["success"] == "1"]
        alone = found.get(("miura_70", v), {}).get("commit_40_in_process_ms", math.nan)
        if release and math.isfinite(alone):
            said.append(f"{v:,} vertices: {ms(release[0])} through the nodes, {ms(alone)} in process "
                        f"({100 * (release[0] - alone) / alone:+.0f} %)")
    if said:
        side.append("")
        side.append("The slider's release at 40 % through the nodes against the same computation in this process: "
                    + "; ".join(said) + ".")
    tables["user_path_inprocess"] = "\n".join(side)

    nosync = [r for r in data if r["configuration"] == "no_journal_sync"]
    brk = ["| pattern | vertices | state message | markers message | tf face frames | build + serialise: state / "
           "markers | state parsed (each receiver, each solve) | trivial service: new connection / kept | one solve "
           "through spring_solver / in process (already converged) | commit CPU in paper_model / spring_solver / "
           "curved_mesh_solver (slider release 40 %) | journal fsync: release 40 % synced / not |",
           "|---|---|---|---|---|---|---|---|---|---|---|"]
    for (pattern, vertices), q in sorted(found.items(), key=lambda kv: (kv[0][0] != "miura_70", kv[0])):
        release = groups.get((pattern, vertices), {}).get("slider_release_40", [])
        rel = release[0] if release and release[0]["success"] == "1" else None
        off = [r for r in nosync if r["pattern"] == pattern and int(num(r["vertices"])) == vertices
               and r["action"] == "slider_release_40" and r["success"] == "1"]
        kb = lambda x: f"{fmt(x / 1e6)} MB" if x >= 1e6 else f"{fmt(x / 1e3)} kB"  # noqa: E731
        brk.append(
            f"| {pattern} | {vertices:,} | {kb(q.get('state_bytes', math.nan))} | {kb(q.get('markers_bytes', math.nan))} | "
            + (f"none ({int(q.get('faces', 0)):,} faces, over `face_frames_max`) | " if q.get("faces", 0) > 1000 else
               f"{int(q.get('tf_largest_transforms', 0))} ({kb(q.get('tf_largest_bytes', 0))}) | ") +
            f"{ms(q.get('state_build_ms', math.nan) + q.get('state_serialise_ms', math.nan))} / "
            f"{ms(q.get('markers_build_ms', math.nan) + q.get('markers_serialise_ms', math.nan))} | "
            f"{ms(q.get('state_parse_ms', math.nan) + q.get('state_deserialise_ms', math.nan))} | "
            f"{ms(q.get('trivial_call_new_connection_ms', math.nan))} / {ms(q.get('trivial_call_persistent_ms', math.nan))} | "
            f"{ms(q.get('solve_service_converged_ms', math.nan))} / {ms(q.get('solve_in_process_converged_ms', math.nan))} | "
            + (f"{ms(num(rel['paper_model_cpu_ms']))} / {ms(num(rel['spring_solver_cpu_ms']))} / "
               f"{ms(num(rel['curved_mesh_solver_cpu_ms']))} of {ms(num(rel['markers_ms']))} wall | " if rel else "– | ")
            + (f"{ms(num(rel['markers_ms']))} / {ms(num(off[0]['markers_ms']))} |" if rel and off else "– |"))
    tables["user_path_breakdown"] = "\n".join(brk)

    # Chart: the Miura-ori's user's path against vertex count, fold_bench's in-process figures beside.
    if not miura:
        return
    fig, ax = plt.subplots(figsize=(9, 5))
    styles = {"slider_preview": ("C0", "slider preview (median)"), "slider_release_40": ("C1", "slider release at 40 %"),
              "slider_release_100": ("C3", "slider release at 100 %"), "turn_preview": ("C2", "turn preview (median)"),
              "turn_commit": ("C4", "turn commit 10°"), "drag_preview": ("C5", "mouse drag preview (median)"),
              "drag_commit": ("C6", "mouse drag commit")}
    for action, (color, label) in styles.items():
        pts = []
        for v in miura:
            vals = [num(r["markers_ms"]) for r in groups[("miura_70", v)].get(action, []) if r["success"] == "1"]
            if vals:
                pts.append((v, percentile(vals, 0.5)))
        if pts:
            ax.loglog([p[0] for p in pts], [p[1] for p in pts], "o-", c=color, label=f"user's path: {label}")
    if fold:
        sizes = sorted(fold)
        ax.loglog(sizes, [num(fold[v]["commit_s"]) * 1e3 for v in sizes], "s--", c="C1",
                  label="fold_bench: commit 1 % on (CPU, in process)")
        ax.loglog(sizes, [num(fold[v]["slide_p95_ms"]) for v in sizes], "s--", c="C0",
                  label="fold_bench: slide frame p95 (CPU, in process)")
    alone = [(v, found.get(("miura_70", v), {}).get("commit_40_in_process_ms", math.nan)) for v in miura]
    alone = [p for p in alone if math.isfinite(p[1])]
    if alone:
        ax.loglog([p[0] for p in alone], [p[1] for p in alone], "^:", c="C1",
                  label="the release at 40 % computed in process (wall)")
    ax.axhline(33, c="gray", ls=":", label="33 ms")
    finish(fig, ax, "vertices (Miura-ori)", "ms from the request to the markers that show it",
           "The user's path against the in-process bench", "user_path.png")


def write_tables(tables):
    if not os.path.exists(DOC):
        return
    text = open(DOC).read()
    for name, body in tables.items():
        pattern = re.compile(r"(<!-- bench:%s -->\n).*?(<!-- /bench:%s -->)" % (name, name), re.S)
        text = pattern.sub(lambda m: m.group(1) + body + "\n" + m.group(2), text)
    open(DOC, "w").write(text)


def main():
    tables = {}
    if ONLY == "wall_time":
        table_wall_time(tables)
        write_tables(tables)
        return
    if ONLY == "fold":  # fold_bench alone, rerun
        chart_fold(tables)
        write_tables(tables)
        return
    if ONLY == "user_path":  # user_path_bench alone, rerun
        chart_user_path(tables)
        write_tables(tables)
        return
    if ONLY == "meshers":  # mesh_bench alone, rerun
        chart_meshers(tables)
        write_tables(tables)
        return
    chart_error_time(tables)
    chart_stability(tables)
    chart_scaling(tables)
    chart_seed_accuracy(tables)
    chart_curved(tables)
    chart_curved_speed(tables)
    chart_meshers(tables)
    table_replay(tables)
    chart_journal(tables)
    chart_memory(tables)
    chart_contention(tables)
    chart_contention(tables, "contention_newton", "newton, the default solver")
    chart_fold(tables)
    chart_gestures(tables)
    chart_user_path(tables)
    table_wall_time(tables)
    conclusions(tables)
    write_tables(tables)
    print("charts in %s, tables %s into %s" % (IMAGES, ", ".join(tables), DOC))


if __name__ == "__main__":
    main()
