#!/usr/bin/python3
"""Error against time per frame: the anytime frames of issue 37 beside the converged solves.

    /usr/bin/python3 bench/curved_frames_chart.py [docs/bench] [docs/images/bench]

Reads curved_speed_bench's per-frame files curved_frames_<vertices>_<mode>.csv (modes wall, cpu,
sync: anytime frames; newton: every pointer step solved to 1e-8) and draws, per sheet size, each
checked frame's distance to the tight balance over the side against its wall time (the modes of
CHARTED, run in the same hour). Writes
curved_frames_error_time.png and the summary curved_frames_error_time.csv (one row per size and
mode: wall time and error percentiles, steady frames apart from those near a snap).
"""
import csv
import glob
import math
import os
import re
import sys

import matplotlib

matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402

BENCH = sys.argv[1] if len(sys.argv) > 1 else "docs/bench"
IMAGES = sys.argv[2] if len(sys.argv) > 2 else "docs/images/bench"
MODES = {  # mode: (label, colour, marker)
    "wall": ("anytime frames (26 ms of wall)", "C0", "o"),
    "cpu": ("anytime frames (26 ms of the frame thread's CPU)", "C2", "s"),
    "sync": ("frames with a fresh factor each (not anytime)", "C1", "^"),
    "newton": ("Newton to 1e-8 each step (converged)", "C3", "D"),
}
CHARTED = ("wall", "newton")  # drawn (measured in the same hour); every mode is in the summary
FLOOR = 1e-12  # errors of exactly 0 (the balance itself) drawn here


def num(x):
    try:
        return float(x)
    except (TypeError, ValueError):
        return math.nan


def percentile(values, p):
    values = sorted(v for v in values if not math.isnan(v))
    if not values:
        return math.nan
    return values[min(len(values) - 1, max(0, math.ceil(p * len(values)) - 1))]


def main():
    runs = {}
    for path in glob.glob(os.path.join(BENCH, "curved_frames_*_*.csv")):
        m = re.fullmatch(r"curved_frames_(\d+)_([a-z]+)\.csv", os.path.basename(path))
        if not m or m.group(2) not in MODES:
            continue
        with open(path) as f:
            runs[(int(m.group(1)), m.group(2))] = list(csv.DictReader(f))
    sizes = sorted({v for v, _ in runs})
    if not sizes:
        sys.exit("curved_frames_chart.py: no curved_frames_<vertices>_<mode>.csv in " + BENCH)

    summary = []
    fig, axes = plt.subplots(1, len(sizes), figsize=(6 * len(sizes), 4.8), squeeze=False)
    for ax, vertices in zip(axes[0], sizes):
        for mode, (label, colour, marker) in MODES.items():
            rows = runs.get((vertices, mode))
            if not rows:
                continue
            checked = [r for r in rows if not math.isnan(num(r["error"]))]
            steady = [r for r in checked if r["near_snap"] == "0"]
            near = [r for r in checked if r["near_snap"] != "0"]
            for part, filled in ((steady, True), (near, False)) if mode in CHARTED else ():
                if not part:
                    continue
                ax.scatter([num(r["wall_ms"]) for r in part], [max(num(r["error"]), FLOOR) for r in part],
                           c=colour if filled else "none", edgecolors=colour, marker=marker, s=22,
                           label=label + ("" if filled else ", within 3 frames of a snap"))
            wall = [num(r["wall_ms"]) for r in rows]
            summary.append({
                "vertices": vertices, "mode": mode, "frames": len(rows), "checked": len(checked),
                "steady_checked": len(steady),
                "wall_ms_p50": percentile(wall, 0.5), "wall_ms_p95": percentile(wall, 0.95),
                "wall_ms_max": percentile(wall, 1.0),
                "steady_error_median": percentile([num(r["error"]) for r in steady], 0.5),
                "steady_error_p95": percentile([num(r["error"]) for r in steady], 0.95),
                "steady_error_max": percentile([num(r["error"]) for r in steady], 1.0),
                "all_error_max": percentile([num(r["error"]) for r in checked], 1.0),
            })
        ax.axhline(1e-4, color="k", ls=":", lw=1)
        ax.axvline(33, color="k", ls="--", lw=1)
        ax.text(34, 1.3e-4, "targets: 1e-4 of the side, 33 ms", fontsize=7)
        ax.set_xscale("log")
        ax.set_yscale("log")
        ax.set_xlabel("wall time of the frame or solve [ms]")
        ax.set_ylabel("distance to the tight balance / side")
        ax.set_title(f"{vertices:,} vertices")
        ax.grid(True, which="both", alpha=0.3)
    handles, labels = axes[0][0].get_legend_handles_labels()
    fig.legend(handles, labels, loc="lower center", ncol=2, fontsize=8)
    fig.suptitle("Curved paper dragged at 30 Hz: error against time per frame (curved_speed_bench frames)")
    fig.tight_layout(rect=(0, 0.1, 1, 0.95))
    os.makedirs(IMAGES, exist_ok=True)
    fig.savefig(os.path.join(IMAGES, "curved_frames_error_time.png"), dpi=110)
    with open(os.path.join(BENCH, "curved_frames_error_time.csv"), "w", newline="") as f:
        writer = csv.DictWriter(f, fieldnames=list(summary[0]))
        writer.writeheader()
        for row in summary:
            writer.writerow({k: (f"{v:.4g}" if isinstance(v, float) else v) for k, v in row.items()})
    for row in summary:
        print(", ".join(f"{k} {v:.3g}" if isinstance(v, float) else f"{k} {v}" for k, v in row.items()))


if __name__ == "__main__":
    main()
