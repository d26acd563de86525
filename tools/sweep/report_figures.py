#!/usr/bin/python3
"""Figures of a sweep report (msbench report writes this script into the report directory and runs
it; run it again by hand with `python3 make_figures.py REPORT_DIR`).

Reads REPORT_DIR/report_runs.csv (run id, world, series, status, run directory), REPORT_DIR/table.csv
(the rows with their intervals) and each complete run's coverage.csv and topdown.png, and writes:
  table1.png            each row's mean A with its 95 % bootstrap interval (the report's), beside
                        the paper's Table I mean and max where the row exists
  coverage_<world>.png  explored area A over simulated time, one mean line per series (method or
                        variant) with the 95 % percentile bootstrap band of the mean over its runs
                        (fixed resampling seed: the same figure every time), like the MonoSpheres
                        paper's Fig. 8/9; a run that ended early (collision) keeps its final A
  gallery.png           every complete run's top-down map, labelled with its id
  ablation_levels_<world>.png  (sweeps with a method axis and one level axis) each method's mean A
                        over the full method's at each level, with its 95 % paired bootstrap interval
Needs Debian's python3-matplotlib (apt-get install python3-matplotlib; it brings numpy).
"""
import csv
import os
import re
import sys

import matplotlib
import numpy as np

matplotlib.use("Agg")
import matplotlib.image as mpimg  # noqa: E402
import matplotlib.pyplot as plt  # noqa: E402



def plain(text):
    """A name from a file for a figure's title: control characters (line breaks, escape sequences)
    removed and `$` escaped, so a name can neither break the title nor start matplotlib's mathtext."""
    return re.sub(r"[\x00-\x1f\x7f]", "", text).replace("$", r"\$")

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


RESAMPLE_SEED = 20261126  # fixed: the bands are the same every time the figures are drawn
DRAWS = 2000


def bootstrap_band(curves, level=0.95):
    """Mean curve and the percentile bootstrap band of the mean over the runs (rows of curves)."""
    data = np.asarray(curves, dtype=float)
    mean = data.mean(axis=0)
    if len(data) < 2:
        return mean, mean, mean
    rng = np.random.default_rng(RESAMPLE_SEED)
    picks = rng.integers(0, len(data), size=(DRAWS, len(data)))
    means = data[picks].mean(axis=1)
    tail = (1.0 - level) / 2.0
    return mean, np.quantile(means, tail, axis=0), np.quantile(means, 1.0 - tail, axis=0)


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
            mean, lo, hi = bootstrap_band(curves)
            (line,) = ax.plot(grid, mean, label=f"{name} (n = {len(curves)})")
            ax.fill_between(grid, lo, hi, color=line.get_color(), alpha=0.2, linewidth=0)
        ax.set_xlabel("simulated time (s)")
        ax.set_ylabel("explored area A (m²)")
        ax.set_title(f"{plain(os.path.basename(world))}: coverage over time (mean, 95 % bootstrap band)")
        ax.grid(alpha=0.3)
        ax.legend(fontsize=8)
        fig.tight_layout()
        safe = re.sub(r"[^A-Za-z0-9_.-]+", "_", os.path.basename(world))
        fig.savefig(os.path.join(out_dir, f"coverage_{safe}.png"), dpi=110)
        plt.close(fig)


def number(text):
    """A float of a CSV field, None when empty."""
    return float(text) if text not in ("", None) else None


def table_figure(out_dir):
    """Each row's mean A with its interval, beside the paper's mean and max (table.csv)."""
    path = os.path.join(out_dir, "table.csv")
    if not os.path.exists(path):
        return
    with open(path, newline="") as f:
        rows = [r for r in csv.DictReader(f) if number(r["mean_area_m2"]) is not None]
    if not rows:
        return
    x = np.arange(len(rows))
    mean = np.array([number(r["mean_area_m2"]) for r in rows])
    lo = np.array([number(r["area_ci_lo"]) for r in rows])
    hi = np.array([number(r["area_ci_hi"]) for r in rows])
    fig, ax = plt.subplots(figsize=(max(6.0, 0.75 * len(rows) + 2), 4.5))
    ax.bar(x - 0.2, mean, 0.4, yerr=[mean - lo, hi - mean], capsize=3, label="msbench mean A, 95 % CI")
    paper = [(k, number(r["paper_mean_area_m2"]), number(r["paper_max_area_m2"])) for k, r in enumerate(rows)]
    paper = [p for p in paper if p[1] is not None]
    if paper:
        ax.bar([k + 0.2 for k, _, _ in paper], [m for _, m, _ in paper], 0.4, color="0.6", label="paper mean A")
        ax.scatter([k + 0.2 for k, _, _ in paper], [m for _, _, m in paper], marker="_", s=200, color="k",
                   label="paper max A", zorder=3)
    ax.set_xticks(x)
    ax.set_xticklabels([f"{r['world']}\n{r['method']}" for r in rows], rotation=60, ha="right", fontsize=7)
    ax.set_ylabel("explored area A (m²)")
    # The title follows the sweep: only a Table I sweep has the paper's rows beside its own.
    sweep = os.path.basename(os.path.dirname(os.path.abspath(out_dir)))
    ax.set_title("Table I: mean A per row (msbench with 95 % bootstrap interval; the paper)" if paper else
                 f"{sweep}: mean A per row, as claimed (95 % bootstrap interval)")
    ax.grid(alpha=0.3, axis="y")
    ax.legend(fontsize=8)
    fig.tight_layout()
    fig.savefig(os.path.join(out_dir, "table1.png"), dpi=110)
    plt.close(fig)


def ablation_level_figures(out_dir):
    """Each method's area ratio to the full method against the level, with 95 % intervals
    (ablation_levels.csv, written for sweeps with a method axis and one level axis)."""
    path = os.path.join(out_dir, "ablation_levels.csv")
    if not os.path.exists(path):
        return
    with open(path, newline="") as f:
        cells = list(csv.DictReader(f))
    worlds = list(dict.fromkeys(c["world"] for c in cells))
    for world in worlds:
        mine = [c for c in cells if c["world"] == world]
        levels = {}
        for c in mine:
            levels[int(c["level_index"])] = c["level"]
        methods = list(dict.fromkeys(c["method"] for c in mine))
        fig, ax = plt.subplots(figsize=(7.0, 4.5))
        for k, method in enumerate(methods):
            pts = sorted((int(c["level_index"]), float(c["ratio"]), float(c["lo"]), float(c["hi"]))
                         for c in mine if c["method"] == method)
            x = np.array([p[0] for p in pts]) + (k - (len(methods) - 1) / 2) * 0.06
            y = np.array([p[1] for p in pts])
            lo = np.array([p[2] for p in pts])
            hi = np.array([p[3] for p in pts])
            ax.errorbar(x, y, yerr=[y - lo, hi - y], marker="o", capsize=3, label=method)
        ax.axhline(1.0, color="k", lw=0.8)
        ax.set_xticks(sorted(levels))
        ax.set_xticklabels([levels[i] for i in sorted(levels)])
        ax.set_ylabel("mean A / full method's mean A")
        ax.set_title(f"{plain(world)}: each ablation against the full method, 95 % paired bootstrap CI")
        ax.grid(alpha=0.3)
        ax.legend(fontsize=8)
        fig.tight_layout()
        safe = re.sub(r"[^A-Za-z0-9_.-]", "_", world)
        fig.savefig(os.path.join(out_dir, f"ablation_levels_{safe}.png"), dpi=110)
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
            ax.set_title(plain(run_id), fontsize=9)
    fig.tight_layout()
    fig.savefig(os.path.join(out_dir, "gallery.png"), dpi=100)
    plt.close(fig)


def main():
    if len(sys.argv) != 2:
        sys.exit("usage: make_figures.py REPORT_DIR")
    out_dir = sys.argv[1]
    with open(os.path.join(out_dir, "report_runs.csv"), newline="") as f:
        runs = [r for r in csv.DictReader(f) if r["status"] == "complete"]
    table_figure(out_dir)
    coverage_figures(out_dir, runs)
    gallery(out_dir, runs)
    ablation_level_figures(out_dir)
    print(f"figures written to {out_dir}")


if __name__ == "__main__":
    main()
