#!/usr/bin/python3
# SPDX-License-Identifier: MIT
"""Draws the paper's Figs 9-12 (Sections 4.2 and 4.3) from several seeds and both pipelines.

Reads <dir>/<pipeline>-3d-seed<S>-4.2.csv and -4.3.csv, one pair per pipeline and seed (the
full-4.2.csv and full-4.3.csv of `scripts/reproduce.py --experiments 4.2,4.3 --seed S --pipeline P`),
and writes into the same folder:
    seeds-fig09-time-vs-density.png      detection time (wall, processor) against packing density E per N
    seeds-fig10-memory-vs-side.png       peak RSS and bytes held against cube side x per N
    seeds-fig11-time-vs-size-ratio.png   detection time (wall, processor) against size ratio H per N
    seeds-fig12-memory-vs-size-ratio.png peak RSS and bytes held against H per N
    seeds-4.2-4.3-summary.md             spreads across E and H, seed spread, bytes per box
One panel per pipeline. Each point is the median over the seeds of the median step time (or of
the memory); the bars run from the seed with the smallest to the seed with the largest value.
Missing rows (runs still going) leave their points out; the summary counts the seeds per point.

Usage: scripts/plot-seeds-density-ratio.py [--dir bench/results/cpp-2core/reproduction-4.2-4.3]
"""

import argparse
import csv
import glob
import importlib.util
import os
import re
import sys

import numpy as np

# The figure helpers of Section 4.1's plot (the file name has a hyphen, so no plain import).
_SPEC = importlib.util.spec_from_file_location(
    "plot_seeds", os.path.join(os.path.dirname(os.path.abspath(__file__)), "plot-seeds.py"))
plot_seeds = importlib.util.module_from_spec(_SPEC)
_SPEC.loader.exec_module(plot_seeds)
plt = plot_seeds.plt
MB, MARKERS, PIPELINES, REPO_ROOT = plot_seeds.MB, plot_seeds.MARKERS, plot_seeds.PIPELINES, plot_seeds.REPO_ROOT

FILE_NAME = re.compile(r"(?P<pipeline>\w+)-3d-seed(?P<seed>\d+)-(?P<experiment>4\.[23])\.csv$")
# What each experiment varies at a fixed N: the column that names a run, and how the figures show it.
VARIED = {"4.2": ("cube_side", "x"), "4.3": ("size_ratio", "H")}
TEXT_COLUMNS = ("experiment", "case", "reference_check")


def read_runs(folder):
    """{experiment: {pipeline: {N: {varied value: {seed: row}}}}}, numbers as floats."""
    runs = {}
    for path in sorted(glob.glob(os.path.join(folder, "*-3d-seed*-4.[23].csv"))):
        match = FILE_NAME.search(os.path.basename(path))
        if not match:
            continue
        experiment = match["experiment"]
        with open(path, newline="") as source:
            for row in csv.DictReader(source):
                for key, value in row.items():
                    if key not in TEXT_COLUMNS:
                        row[key] = float(value) if value not in ("", None) else float("nan")
                varied = row[VARIED[experiment][0]]
                (runs.setdefault(experiment, {}).setdefault(match["pipeline"], {}).setdefault(row["boxes"], {})
                 .setdefault(varied, {}))[int(match["seed"])] = row
    return runs


def series(points, key, per_box=None):
    """Varied values and an array [varied][seed] of key (ragged where seeds are missing, so a list)."""
    varied = sorted(points)
    values = [np.array([row[key] / (row[per_box] if per_box else 1.0) for row in points[v].values()])
              for v in varied]
    return np.array(varied), values


def draw_points(panel, x, values, marker, label):
    """Median over the seeds with a min-max bar, as plot_seeds.draw_spread but for ragged seed counts."""
    median = np.array([np.median(v) for v in values])
    low = median - np.array([v.min() for v in values])
    high = np.array([v.max() for v in values]) - median
    panel.errorbar(x, median, yerr=[low, high], marker=marker, markersize=4, capsize=3, elinewidth=0.9,
                   label=label)


def seed_label(points):
    counts = sorted({len(seeds) for seeds in points.values()})
    seeds = "/".join(map(str, counts))
    return f"{seeds} seed{'s' if counts != [1] else ''}"


def figure_time(runs, experiment, folder, subtitle, written):
    if experiment == "4.2":
        title, xlabel, name = "Fig. 9: packing density against detection time", "packing density E", \
            "seeds-fig09-time-vs-density.png"
    else:
        title, xlabel, name = "Fig. 11: size ratio against detection time", "size ratio H (log scale)", \
            "seeds-fig11-time-vs-size-ratio.png"
    # The processor time row: on a shared machine the wall time also counts the waits for a CPU.
    figure, axes = plot_seeds.panels(2, title + subtitle, xlabel,
                                     ["median step time, wall (s)", "median step time, processor (s)"],
                                     height=4.2)
    for index, pipeline in enumerate(PIPELINES):
        for row, column in enumerate(("step_median_s", "step_cpu_median_s")):
            panel = axes[row][index]
            panel.set_title(plot_seeds.PIPELINE_TITLES[pipeline], fontsize=10)
            for marker, (boxes, points) in zip(MARKERS, sorted(runs.get(pipeline, {}).items())):
                varied, times = series(points, column)
                if experiment == "4.2":
                    x = np.array([np.median([r["packing_density"] for r in points[v].values()]) for v in varied])
                else:
                    x = varied
                draw_points(panel, x, times, marker, f"N = {boxes / 1e3:.0f}k ({seed_label(points)})")
            if experiment == "4.3":
                panel.set_xscale("log")
                ratios = sorted({h for points in runs.get(pipeline, {}).values() for h in points})
                panel.set_xticks(ratios, [f"{h:.3g}" for h in ratios], fontsize=7)
                panel.minorticks_off()
            else:
                panel.set_xlim(left=0)
            panel.set_ylim(0, panel.get_ylim()[1] * 1.25)  # room for the legend above the lines
            if panel.get_legend_handles_labels()[0]:
                panel.legend(title="median of seeds; bars: min–max", fontsize=8, title_fontsize=8, ncol=3,
                             loc="upper left")
    plot_seeds.save(figure, folder, name, written)


def figure_memory(runs, experiment, folder, subtitle, written):
    if experiment == "4.2":
        title, xlabel, name = "Fig. 10: space length against total memory", "cube side x", \
            "seeds-fig10-memory-vs-side.png"
    else:
        title, xlabel, name = "Fig. 12: size ratio against total memory", "size ratio H (log scale)", \
            "seeds-fig12-memory-vs-size-ratio.png"
    figure, axes = plot_seeds.panels(2, title + subtitle, xlabel,
                                     ["peak resident memory of the process (MB)", "held by the smb World (MB)"],
                                     height=4.0)
    for index, pipeline in enumerate(PIPELINES):
        for marker, (boxes, points) in zip(MARKERS, sorted(runs.get(pipeline, {}).items())):
            for row, column in enumerate(("peak_rss_bytes", "bytes_held")):
                varied, memory = series(points, column)
                draw_points(axes[row][index], varied, [m / MB for m in memory], marker,
                            f"N = {boxes / 1e3:.0f}k")
        for row in range(2):
            panel = axes[row][index]
            panel.set_title(plot_seeds.PIPELINE_TITLES[pipeline], fontsize=10)
            if experiment == "4.3":
                panel.set_xscale("log")
                ratios = sorted({h for points in runs.get(pipeline, {}).values() for h in points})
                panel.set_xticks(ratios, [f"{h:.3g}" for h in ratios], fontsize=7)
                panel.minorticks_off()
            panel.set_ylim(0, panel.get_ylim()[1] * 1.15)
            if panel.get_legend_handles_labels()[0]:
                panel.legend(title="median of seeds; bars: min–max", fontsize=7, title_fontsize=7, ncol=3,
                             loc="lower right")
    plot_seeds.save(figure, folder, name, written)


def spread(values):
    return values.max() / values.min()


def summary_table(runs, experiment):
    symbol = VARIED[experiment][1]
    head = "E" if experiment == "4.2" else "H"
    lines = [f"| pipeline | N | {symbol} values (seeds per point) | {head} range | t min–max (s) | "
             f"t across {head}: max/min | CPU t across {head}: max/min | "
             f"t at {'densest / sparsest' if experiment == '4.2' else 'H = min / H = max'}: wall, CPU | "
             "µs/box min–max | seed spread: median, max | CPU seed spread: median, max | CPU / wall | "
             f"held B/box | held across {symbol}: max/min | peak RSS B/box | peak RSS across {symbol}: max/min | "
             "pairs per box |",
             "|" + "---|" * 17]
    for pipeline in PIPELINES:
        for boxes, points in sorted(runs.get(pipeline, {}).items()):
            varied, times = series(points, "step_median_s")
            medians = np.array([np.median(t) for t in times])
            cpu = np.array([np.median(t) for t in series(points, "step_cpu_median_s")[1]])
            seed_spread = np.array([spread(t) for t in times if len(t) > 1])
            cpu_seed_spread = np.array([spread(t) for t in series(points, "step_cpu_median_s")[1] if len(t) > 1])
            rows = [row for v in varied for row in points[v].values()]
            density = np.array([row["packing_density"] for row in rows])
            ratio = np.array([row["size_ratio"] for row in rows])
            held = np.array([np.median(m) for m in series(points, "bytes_held", "boxes_final")[1]])
            peak = np.array([np.median(m) for m in series(points, "peak_rss_bytes", "boxes_final")[1]])
            held_total = np.array([np.median(m) for m in series(points, "bytes_held")[1]])
            peak_total = np.array([np.median(m) for m in series(points, "peak_rss_bytes")[1]])
            per_box = medians / boxes * 1e6
            pairs = np.array([row["pairs_median"] / row["boxes_median"] for row in rows])
            # Sorted by x or H, the first point is the densest scene (4.2) or the most uniform sizes (4.3).
            ends = f"{medians[0] / medians[-1]:.2f}, {cpu[0] / cpu[-1]:.2f}"
            if experiment == "4.2":
                varied_range = f"{density.min():.3f}–{density.max():.3f}"
            else:
                varied_range = f"{ratio.min():g}–{ratio.max():g}"
            counts = "/".join(str(len(points[v])) for v in varied)
            cells = [pipeline, f"{boxes / 1e3:.0f}k", f"{len(varied)} ({counts})", varied_range,
                     f"{medians.min():.3f}–{medians.max():.3f}", f"{spread(medians):.2f}", f"{spread(cpu):.2f}",
                     ends, f"{per_box.min():.3f}–{per_box.max():.3f}",
                     f"{np.median(seed_spread):.2f}, {seed_spread.max():.2f}" if len(seed_spread) else "–",
                     (f"{np.median(cpu_seed_spread):.2f}, {cpu_seed_spread.max():.2f}" if len(cpu_seed_spread)
                      else "–"),
                     f"{np.median([r['step_cpu_median_s'] / r['step_median_s'] for r in rows]):.2f}",
                     f"{held.min():.0f}–{held.max():.0f}", f"{spread(held_total):.4f}",
                     f"{peak.min():.0f}–{peak.max():.0f}", f"{spread(peak_total):.4f}",
                     f"{pairs.min():.3f}–{pairs.max():.3f}"]
            lines.append("| " + " | ".join(cells) + " |")
    return lines


def pipeline_ratio_table(runs):
    """Paper pipeline's median step time over the default's, at each point both have."""
    lines = ["| N | paper / default: min–max over the points | median |", "|---|---|---|"]
    paper, default = runs.get("paper", {}), runs.get("persistent", {})
    for boxes in sorted(set(paper) & set(default)):
        shared = sorted(set(paper[boxes]) & set(default[boxes]))
        ratios = np.array([np.median([r["step_median_s"] for r in paper[boxes][v].values()])
                           / np.median([r["step_median_s"] for r in default[boxes][v].values()]) for v in shared])
        if len(ratios):
            lines.append(f"| {boxes / 1e3:.0f}k | {ratios.min():.1f}–{ratios.max():.1f} | {np.median(ratios):.1f} |")
    return lines


def summary_lines(runs, source):
    rows = [row for e in runs.values() for p in e.values() for n in p.values() for v in n.values()
            for row in v.values()]
    seeds = sorted({int(row["seed"]) for row in rows})
    steps = sorted({int(row["steps_timed"]) for row in rows})
    loads = [row["load_1min"] for row in rows]
    cpu_share = [row["step_cpu_median_s"] / row["step_median_s"] for row in rows]
    lines = ["# Sections 4.2 and 4.3 over several seeds, both pipelines: spreads\n",
             f"Written by scripts/plot-seeds-density-ratio.py from {source}: seeds {', '.join(map(str, seeds))}, "
             f"{'/'.join(map(str, steps))} timed steps after the build step per run, {len(rows)} runs, the "
             f"1-minute load average at the start of a run {min(loads):.1f}–{max(loads):.1f}, the CPU time of a "
             f"step {min(cpu_share):.2f}–{max(cpu_share):.2f} of its wall time "
             f"(median {np.median(cpu_share):.2f}).\n",
             "t is the median step time of a run; each point takes the median of t over the seeds. Across E (or x, "
             "H): max/min over the points of one N of those medians (CPU: the same for the median processor time "
             "of a step). Densest / sparsest (4.2: x = 100 over x = 200) and H = min / H = max (4.3: H = 1.111 over "
             "H = 10): the ratio of the end points (wall, then processor time), above 1 where the denser or more "
             "uniform scene is slower. "
             "Seed spread: max/min over the seeds of t at one point, the median over the points and the largest. "
             "B/box: bytes per box of the final N, median of the seeds, range over the points; across x or H: "
             "max/min over the points of the median bytes (1.0000 is the same memory at every point).\n",
             "## Section 4.2: cube side x, so packing density E (Table 2, Figs 9–10; H = 10, Λ = 1e-5)\n"]
    lines += summary_table(runs.get("4.2", {}), "4.2")
    lines += ["", "Paper pipeline against the default (ratio of the seed medians of t):\n"]
    lines += pipeline_ratio_table(runs.get("4.2", {}))
    lines += ["", "## Section 4.3: size ratio H (Table 3, Figs 11–12; x = 200, Λ = 1e-5)\n"]
    lines += summary_table(runs.get("4.3", {}), "4.3")
    lines += ["", "Paper pipeline against the default (ratio of the seed medians of t):\n"]
    lines += pipeline_ratio_table(runs.get("4.3", {}))
    return lines


def main():
    parser = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    parser.add_argument("--dir", default=os.path.join(REPO_ROOT, "bench", "results", "cpp-2core",
                                                      "reproduction-4.2-4.3"))
    args = parser.parse_args()
    runs = read_runs(args.dir)
    if not runs:
        sys.exit(f"plot-seeds-density-ratio.py: no <pipeline>-3d-seed<S>-4.2.csv or -4.3.csv in {args.dir}")
    seeds = sorted({seed for e in runs.values() for p in e.values() for n in p.values() for v in n.values()
                    for seed in v})
    subtitle = f" (3D, seeds {', '.join(map(str, seeds))}; loaded machine, see README)"
    written = []
    for experiment in sorted(runs):
        figure_time(runs[experiment], experiment, args.dir, subtitle, written)
        figure_memory(runs[experiment], experiment, args.dir, subtitle, written)
    plot_seeds.write_summary(args.dir, "seeds-4.2-4.3-summary.md",
                             summary_lines(runs, os.path.relpath(args.dir, REPO_ROOT)), written)


if __name__ == "__main__":
    main()
