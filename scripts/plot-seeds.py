#!/usr/bin/python3
# SPDX-License-Identifier: MIT
"""Draws the paper's Figs 6-8 (Section 4.1) from several seeds and both pipelines, and their fits.

Reads <dir>/<pipeline>-<dim>d-seed<S>-4.1-L<Λ>.csv, one file per pipeline, seed and update factor
(written by `scripts/reproduce.py --experiments 4.1 --update-factors Λ --seed S --pipeline P`), and
writes into the same folder:
    seeds-fig06-time-vs-n.png       detection time against N per Λ, one panel per pipeline
    seeds-fig06b-time-per-box.png   the same divided by N (flat means linear)
    seeds-fig07-correlation.png     correlation coefficient of time against N, per seed and pooled
    seeds-fig08-memory-vs-n.png     peak RSS and bytes held against N, one row per pipeline
    seeds-summary.md                fits, time per box, seed spread and bytes per box
Each point is the median over the seeds of the median step time; the bars run from the seed with
the smallest to the seed with the largest value.

Usage: scripts/plot-seeds.py [--dir bench/results/xeon-16core/reproduction-4.1] [--dim 3]
"""

import argparse
import csv
import glob
import importlib.util
import os
import re
import sys

import matplotlib

matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402  (the backend must be chosen first)
import numpy as np  # noqa: E402

# The single-seed plot's constants and figure saving (the file name has a hyphen, so no plain
# import).
_SPEC = importlib.util.spec_from_file_location(
    "plot_reproduction", os.path.join(os.path.dirname(os.path.abspath(__file__)), "plot-reproduction.py"))
plot_reproduction = importlib.util.module_from_spec(_SPEC)
_SPEC.loader.exec_module(plot_reproduction)
REPO_ROOT, MB = plot_reproduction.REPO_ROOT, plot_reproduction.MB
PAPER_BYTES_PER_BOX = plot_reproduction.PAPER_BYTES_PER_BOX
save = plot_reproduction.save
MARKERS = "osD^v"
PIPELINES = ("paper", "persistent")
SHORT = {"paper": "paper pipeline", "persistent": "default pipeline"}
PIPELINE_TITLES = {"paper": "paper pipeline (Pipeline::paper_lists)",
                   "persistent": "default pipeline (persistent cuts)"}
FILE_NAME = re.compile(r"(?P<pipeline>\w+)-(?P<dim>\d)d-seed(?P<seed>\d+)-4\.1-L(?P<factor>[0-9.e+-]+)\.csv$")


def read_runs(folder, dim):
    """{pipeline: {Λ: {seed: rows sorted by N}}}, numbers as floats."""
    runs = {}
    for path in sorted(glob.glob(os.path.join(folder, "*-4.1-L*.csv"))):
        match = FILE_NAME.search(os.path.basename(path))
        if not match or int(match["dim"]) != dim:
            continue
        with open(path, newline="") as source:
            rows = list(csv.DictReader(source))
        for row in rows:
            for key, value in row.items():
                if key not in ("experiment", "case", "reference_check"):
                    row[key] = float(value) if value not in ("", None) else float("nan")
        rows.sort(key=lambda r: r["boxes"])
        factor = float(match["factor"])
        runs.setdefault(match["pipeline"], {}).setdefault(factor, {})[int(match["seed"])] = rows
    return runs


def column(rows, key):
    return np.array([row[key] for row in rows], dtype=float)


def stacked(seeds, key, per_box=None):
    """Array [seed, N] of key (divided by the per_box column if given); N is each file's row order."""
    values = []
    for rows in seeds.values():
        value = column(rows, key)
        values.append(value / column(rows, per_box) if per_box else value)
    return np.array(values)


def nominal_boxes(seeds):
    return column(next(iter(seeds.values())), "boxes")


def linear_fit(x, y):
    slope, intercept = np.polyfit(x, y, 1)
    return slope, intercept, np.corrcoef(x, y)[0, 1]


def growth_exponent(x, y):
    return np.polyfit(np.log(x), np.log(y), 1)[0]


def draw_spread(axes, x, values, marker, label):
    """Median over the seeds, with a bar from the smallest to the largest seed."""
    median = np.median(values, axis=0)
    axes.errorbar(x, median, yerr=[median - values.min(axis=0), values.max(axis=0) - median], marker=marker,
                  markersize=4, capsize=3, elinewidth=0.9, label=label)


def panels(rows, title, xlabel, ylabels, width=12.0, height=4.6):
    figure, axes = plt.subplots(rows, 2, figsize=(width, height * rows), squeeze=False)
    figure.suptitle(title, fontsize=11)
    for row_axes, ylabel in zip(axes, ylabels):
        for panel in row_axes:
            panel.set_xlabel(xlabel)
            panel.set_ylabel(ylabel)
            panel.grid(True, alpha=0.3)
    return figure, axes


def write_summary(folder, name, lines, written):
    """Writes the summary's lines to folder/name, then prints every file written, relative."""
    path = os.path.join(folder, name)
    with open(path, "w") as out:
        out.write("\n".join(lines) + "\n")
    written.append(path)
    for done in written:
        print(os.path.relpath(done))


def figure_time(runs, folder, subtitle, written, per_box):
    name = "Detection time per box against N" if per_box else "Fig. 6: N against detection time"
    ylabel = "median step time / N (µs)" if per_box else "median step time (s)"
    figure, axes = panels(1, name + subtitle, "total number of boxes N (thousands)", [ylabel])
    for panel, pipeline in zip(axes[0], PIPELINES):
        panel.set_title(PIPELINE_TITLES[pipeline], fontsize=10)
        for marker, (factor, seeds) in zip(MARKERS, sorted(runs.get(pipeline, {}).items())):
            values = stacked(seeds, "step_median_s", "boxes_median" if per_box else None) * (1e6 if per_box else 1)
            draw_spread(panel, nominal_boxes(seeds) / 1e3, values, marker, f"Λ = {factor:g}")
        panel.legend(title="median of seeds; bars: min–max", fontsize=8, title_fontsize=8, ncol=3,
                     loc="upper left")
        panel.set_xlim(left=0)
        panel.set_ylim(0, panel.get_ylim()[1] * 1.3)  # room for the legend above the lines
    save(figure, folder, "seeds-fig06b-time-per-box.png" if per_box else "seeds-fig06-time-vs-n.png", written)


def correlations(seeds):
    """Pearson r of the median step time against the median N: per seed, and over all seeds' points pooled."""
    per_seed = {seed: linear_fit(column(rows, "boxes_median"), column(rows, "step_median_s"))[2]
                for seed, rows in sorted(seeds.items())}
    n = np.concatenate([column(rows, "boxes_median") for rows in seeds.values()])
    t = np.concatenate([column(rows, "step_median_s") for rows in seeds.values()])
    return per_seed, linear_fit(n, t)[2]


def figure_correlation(runs, folder, subtitle, written):
    figure, panel = plt.subplots(figsize=(7.5, 4.8))
    figure.suptitle("Fig. 7: linear dependence of time on N" + subtitle.replace("; ", ";\n"), fontsize=11)
    panel.set_xlabel("case: update factor Λ")
    panel.set_ylabel("correlation coefficient r of time against N")
    panel.grid(True, alpha=0.3)
    factors = sorted({factor for pipeline in runs.values() for factor in pipeline})
    lowest = 1.0
    for offset, color, pipeline in ((-0.12, "tab:blue", "paper"), (0.12, "tab:orange", "persistent")):
        for index, factor in enumerate(factors):
            seeds = runs.get(pipeline, {}).get(factor)
            if not seeds:
                continue
            per_seed, pooled = correlations(seeds)
            x = index + 1 + offset
            panel.plot([x] * len(per_seed), list(per_seed.values()), "o", color=color, markersize=4, alpha=0.6,
                       label=f"{SHORT[pipeline]}: one seed" if index == 0 else None)
            panel.plot([x], [pooled], "D", color=color, markersize=9, markerfacecolor="none", markeredgewidth=1.6,
                       label=f"{SHORT[pipeline]}: all seeds pooled" if index == 0 else None)
            lowest = min(lowest, pooled, *per_seed.values())
    panel.set_xticks(range(1, len(factors) + 1), [f"{factor:g}" for factor in factors])
    panel.set_ylim(min(0.90, lowest - 0.01), 1.0)
    panel.legend(fontsize=8, loc="lower left")
    save(figure, folder, "seeds-fig07-correlation.png", written)


def figure_memory(runs, folder, subtitle, written):
    """Every seed's run at its final N (which drifts at Λ = 0.1), with a least-squares line per Λ."""
    figure, axes = panels(2, "Fig. 8: N against total memory" + subtitle, "final number of boxes N (thousands)",
                          ["peak resident memory of the process (MB)", "held by the smb World (MB)"], height=4.0)
    for index, pipeline in enumerate(PIPELINES):
        for marker, (factor, seeds) in zip(MARKERS, sorted(runs.get(pipeline, {}).items())):
            n = np.concatenate([column(rows, "boxes_final") for rows in seeds.values()])
            for row, key in enumerate(("peak_rss_bytes", "bytes_held")):
                memory = np.concatenate([column(rows, key) for rows in seeds.values()]) / MB
                slope, intercept, _ = linear_fit(n, memory)
                points, = axes[row][index].plot(n / 1e3, memory, marker=marker, markersize=4, linestyle="none",
                                                alpha=0.7, label=f"Λ = {factor:g}: {slope * MB:.0f} B/box")
                ends = np.array([0, n.max()])
                axes[row][index].plot(ends / 1e3, intercept + slope * ends, linestyle=":", linewidth=1,
                                      color=points.get_color())
        for row in range(2):
            panel = axes[row][index]
            panel.set_title(PIPELINE_TITLES[pipeline], fontsize=10)
            panel.plot([0, 1000], [0, 1e6 * PAPER_BYTES_PER_BOX / MB], color="grey", linestyle="--",
                       linewidth=1, label=f"paper, about {PAPER_BYTES_PER_BOX} B/box")
            panel.legend(title="every seed; dotted: least squares", fontsize=7, title_fontsize=7)
            panel.set_xlim(left=0)
            panel.set_ylim(bottom=0)
    save(figure, folder, "seeds-fig08-memory-vs-n.png", written)


def at_boxes(seeds, boxes, key, per_box):
    """The values over the seeds of key / per_box at the nominal N `boxes`."""
    index = list(nominal_boxes(seeds)).index(boxes)
    return stacked(seeds, key, per_box)[:, index]


def summary_lines(runs, source):
    seed_names = sorted({seed for pipeline in runs.values() for seeds in pipeline.values() for seed in seeds})
    all_rows = [row for p in runs.values() for s in p.values() for rows in s.values() for row in rows]
    steps = sorted({int(row["steps_timed"]) for row in all_rows})
    loads = [row["load_1min"] for row in all_rows]
    lines = ["# Section 4.1 over several seeds, both pipelines: fits and spreads\n",
             f"Written by scripts/plot-seeds.py from {source}: seeds {', '.join(map(str, seed_names))}, "
             f"{'/'.join(map(str, steps))} timed steps after the build step per run, the 1-minute load average "
             f"at the start of a run {min(loads):.1f}–{max(loads):.1f}.\n",
             "t is the median step time of a run. b and a: least-squares line t = a + b·N over every seed's points "
             "(N = the median box count of the timed steps); r: Pearson's correlation coefficient of t against N, "
             "pooled and per seed (the paper's Fig. 7); k: exponent of t ~ N^k on log-log axes, pooled. µs/box: "
             "median over the seeds, min–max in brackets. Seed spread: max/min over the seeds of t at one N, the "
             "median over the N and the largest. B/box: bytes held by the World and peak RSS of the process, per "
             "box of the final N at 1M (median of seeds); memory slope: least-squares bytes per box of the World "
             "over N, pooled.\n",
             "| pipeline | Λ | b (µs/box) | a (ms) | r pooled | r per seed | k | µs/box at 100k | µs/box at 1M "
             "| seed spread: median, max | held B/box at 1M | peak RSS B/box at 1M | held: slope (B/box), r |",
             "|---|---|---|---|---|---|---|---|---|---|---|---|---|"]
    for pipeline in PIPELINES:
        for factor, seeds in sorted(runs.get(pipeline, {}).items()):
            n = np.concatenate([column(rows, "boxes_median") for rows in seeds.values()])
            t = np.concatenate([column(rows, "step_median_s") for rows in seeds.values()])
            slope, intercept, _ = linear_fit(n, t)
            per_seed, pooled = correlations(seeds)
            times = stacked(seeds, "step_median_s")
            ratio = times.max(axis=0) / times.min(axis=0)
            cells = [pipeline, f"{factor:g}", f"{slope * 1e6:.3f}", f"{intercept * 1e3:.1f}", f"{pooled:.4f}",
                     f"{min(per_seed.values()):.4f}–{max(per_seed.values()):.4f}", f"{growth_exponent(n, t):.3f}"]
            for boxes in (100_000, 1_000_000):
                values = at_boxes(seeds, boxes, "step_median_s", "boxes_median") * 1e6
                cells.append(f"{np.median(values):.3f} ({values.min():.3f}–{values.max():.3f})")
            cells.append(f"{np.median(ratio):.2f}, {ratio.max():.2f}")
            for key in ("bytes_held", "peak_rss_bytes"):
                cells.append(f"{np.median(at_boxes(seeds, 1_000_000, key, 'boxes_final')):.0f}")
            held_n = np.concatenate([column(rows, "boxes_final") for rows in seeds.values()])
            held = np.concatenate([column(rows, "bytes_held") for rows in seeds.values()])
            held_slope, _, held_r = linear_fit(held_n, held)
            cells.append(f"{held_slope:.0f}, {held_r:.4f}")
            lines.append("| " + " | ".join(cells) + " |")
    lines += ["", "Paper pipeline against the default, median step time over the seeds (ratio paper / default):\n",
              "| Λ | 100k: paper (s) | default (s) | ratio | 1M: paper (s) | default (s) | ratio |",
              "|---|---|---|---|---|---|---|"]
    for factor in sorted(set(runs.get("paper", {})) & set(runs.get("persistent", {}))):
        cells = [f"{factor:g}"]
        for boxes in (100_000, 1_000_000):
            paper, default = (np.median(at_boxes(runs[p][factor], boxes, "step_median_s", None)) for p in PIPELINES)
            cells += [f"{paper:.4f}", f"{default:.4f}", f"{paper / default:.1f}"]
        lines.append("| " + " | ".join(cells) + " |")
    lines += ["", "Where a step goes at 1M (median over the seeds of the phase times of `DetectStats`, µs per box):\n",
              "| pipeline | Λ | sort | cut + regroup | check | CPU / wall |", "|---|---|---|---|---|---|"]
    for pipeline in PIPELINES:
        for factor, seeds in sorted(runs.get(pipeline, {}).items()):
            cells = [pipeline, f"{factor:g}"]
            for key in ("sort_s", "cut_regroup_s", "check_s"):
                cells.append(f"{np.median(at_boxes(seeds, 1_000_000, key, 'boxes_median')) * 1e6:.3f}")
            cpu = (at_boxes(seeds, 1_000_000, "step_cpu_median_s", None)
                   / at_boxes(seeds, 1_000_000, "step_median_s", None))
            cells.append(f"{np.median(cpu):.3f}")
            lines.append("| " + " | ".join(cells) + " |")
    return lines


def main():
    parser = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    parser.add_argument("--dir", default=os.path.join(REPO_ROOT, "bench", "results", "xeon-16core", "reproduction-4.1"))
    parser.add_argument("--dim", type=int, default=3, choices=(2, 3))
    args = parser.parse_args()
    runs = read_runs(args.dir, args.dim)
    if not runs:
        sys.exit(f"plot-seeds.py: no <pipeline>-{args.dim}d-seed<S>-4.1-L<Λ>.csv in {args.dir}")
    seeds = sorted({seed for pipeline in runs.values() for factor in pipeline.values() for seed in factor})
    subtitle = f" ({args.dim}D, seeds {', '.join(map(str, seeds))}; loaded machine, see README)"
    written = []
    figure_time(runs, args.dir, subtitle, written, per_box=False)
    figure_time(runs, args.dir, subtitle, written, per_box=True)
    figure_correlation(runs, args.dir, subtitle, written)
    figure_memory(runs, args.dir, subtitle, written)
    write_summary(args.dir, "seeds-summary.md", summary_lines(runs, os.path.relpath(args.dir, REPO_ROOT)), written)


if __name__ == "__main__":
    main()
