#!/usr/bin/python3
"""Figures of a sweep report (msbench report writes this script into the report directory and runs
it; run it again by hand with `python3 make_figures.py REPORT_DIR`).

Reads REPORT_DIR/report_runs.csv (run id, world, series, status, run directory) and each complete
run's coverage.csv and topdown.png, and writes:
  coverage_<world>.png  explored area A over simulated time, one mean line and min-max band per
                        series (method or variant), like the MonoSpheres paper's Fig. 8/9;
                        a run that ended early (collision) keeps its final A to the end
  gallery.png           every complete run's top-down map, labelled with its id
Needs Debian's python3-matplotlib (apt-get install python3-matplotlib).
"""
import csv
import os
import re
import sys

import matplotlib

matplotlib.use("Agg")
import matplotlib.image as mpimg  # noqa: E402
import matplotlib.pyplot as plt  # noqa: E402


def read_coverage(path):
    """(times, areas) of a coverage.csv."""
    times, areas = [], []
    with open(path, newline="") as f:
        for row in csv.DictReader(f):
            times.append(float(row["t_s"]))
            areas.append(float(row["area_m2"]))
    return times, areas


def value_at(times, areas, t):
    """A at time t: the last sample at or before t (held after the run's end)."""
    best = 0.0
    for ti, ai in zip(times, areas):
        if ti > t:
            break
        best = ai
    return best


def coverage_figures(out_dir, runs):
    worlds = sorted({r["world"] for r in runs})
    for world in worlds:
        series = {}
        for r in runs:
            if r["world"] != world:
                continue
            cov = os.path.join(r["dir"], "coverage.csv")
            if os.path.exists(cov):
                series.setdefault(r["series"], []).append(read_coverage(cov))
        if not series:
            continue
        end = max(t[-1] for runs_of in series.values() for t, _ in runs_of if t)
        grid = [end * k / 200.0 for k in range(201)]
        fig, ax = plt.subplots(figsize=(7, 4.2))
        for name in sorted(series):
            curves = [[value_at(t, a, g) for g in grid] for t, a in series[name]]
            mean = [sum(c[k] for c in curves) / len(curves) for k in range(len(grid))]
            lo = [min(c[k] for c in curves) for k in range(len(grid))]
            hi = [max(c[k] for c in curves) for k in range(len(grid))]
            (line,) = ax.plot(grid, mean, label=f"{name} ({len(curves)} runs)")
            ax.fill_between(grid, lo, hi, color=line.get_color(), alpha=0.2, linewidth=0)
        ax.set_xlabel("simulated time (s)")
        ax.set_ylabel("explored area A (m²)")
        ax.set_title(f"{os.path.basename(world)}: coverage over time (mean, min–max)")
        ax.grid(alpha=0.3)
        ax.legend(fontsize=8)
        fig.tight_layout()
        safe = re.sub(r"[^A-Za-z0-9_.-]+", "_", os.path.basename(world))
        fig.savefig(os.path.join(out_dir, f"coverage_{safe}.png"), dpi=110)
        plt.close(fig)


def gallery(out_dir, runs):
    pictures = [(r["id"], os.path.join(r["dir"], "topdown.png")) for r in runs]
    pictures = [(i, p) for i, p in pictures if os.path.exists(p)]
    if not pictures:
        return
    cols = min(4, len(pictures))
    rows = (len(pictures) + cols - 1) // cols
    fig, axes = plt.subplots(rows, cols, figsize=(4.5 * cols, 4.2 * rows), squeeze=False)
    for k, ax in enumerate(axes.flat):
        ax.axis("off")
        if k < len(pictures):
            run_id, path = pictures[k]
            ax.imshow(mpimg.imread(path))
            ax.set_title(run_id, fontsize=9)
    fig.tight_layout()
    fig.savefig(os.path.join(out_dir, "gallery.png"), dpi=100)
    plt.close(fig)


def main():
    if len(sys.argv) != 2:
        sys.exit("usage: make_figures.py REPORT_DIR")
    out_dir = sys.argv[1]
    with open(os.path.join(out_dir, "report_runs.csv"), newline="") as f:
        runs = [r for r in csv.DictReader(f) if r["status"] == "complete"]
    coverage_figures(out_dir, runs)
    gallery(out_dir, runs)
    print(f"figures written to {out_dir}")


if __name__ == "__main__":
    main()
