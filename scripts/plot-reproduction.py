#!/usr/bin/python3
# SPDX-License-Identifier: MIT
"""Draws the reproduction's figures like the paper's Figs 6-12 and writes its tables of fits.

Reads <dir>/<mode>-4.1.csv, -4.2.csv and -4.3.csv (written by scripts/reproduce.py) and writes
into the same folder:
    <mode>-fig06-time-vs-n.png            detection time against N, one line per Λ
    <mode>-fig06b-time-per-box.png        the same divided by N (flat means linear)
    <mode>-fig07-correlation.png          correlation coefficient of time against N, per Λ
    <mode>-fig08-memory-vs-n.png          memory against N, per Λ
    <mode>-fig09-time-vs-density.png      time against packing density E, per N
    <mode>-fig10-memory-vs-side.png       memory against space length x, per N
    <mode>-fig11-time-vs-size-ratio.png   time against size ratio H, per N
    <mode>-fig12-memory-vs-size-ratio.png memory against H, per N
    <mode>-summary.md                     linear fits, correlation coefficients, spreads
Needs numpy and matplotlib (Debian: python3-numpy, python3-matplotlib).

Usage: scripts/plot-reproduction.py [--dir bench/results/cpp-2core/reproduction] [--mode full]
"""

import argparse
import csv
import os
import sys

import matplotlib

matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402  (the backend must be chosen first)
import numpy as np  # noqa: E402

REPO_ROOT = os.path.normpath(os.path.join(os.path.dirname(os.path.abspath(__file__)), ".."))
MB = 1e6
# The paper's total memory read off its Figs 8, 10 and 12: about 250 MB for 1M boxes.
PAPER_BYTES_PER_BOX = 250
MARKERS = "osD^v<>p*"


def read_rows(path):
    if not os.path.exists(path):
        return []
    with open(path, newline="") as source:
        rows = list(csv.DictReader(source))
    for row in rows:
        for key, value in row.items():
            if key in ("experiment", "case", "reference_check"):
                continue
            row[key] = float(value) if value not in ("", None) else float("nan")
    return rows


def by_case(rows, order_key):
    """Rows grouped by their case label, cases in order of order_key, rows sorted by N then x and H."""
    cases = {}
    for row in rows:
        cases.setdefault(row["case"], []).append(row)
    for case_rows in cases.values():
        case_rows.sort(key=lambda r: (r["boxes"], r["cube_side"], r["size_ratio"]))
    return sorted(cases.items(), key=lambda item: order_key(item[1][0]))


def column(rows, key):
    return np.array([row.get(key, float("nan")) for row in rows], dtype=float)


def case_title(case, rows=None):
    """Λ = ... or N = ...; below full size N is the one that ran, the paper's N in brackets."""
    if case.startswith("L="):
        return f"Λ = {float(case[2:]):g}"
    if case.startswith("N="):
        paper_boxes = int(case[2:])
        boxes = int(rows[0]["boxes"]) if rows else paper_boxes
        return f"N = {boxes:,}" if boxes == paper_boxes else f"N = {boxes:,} (paper: {paper_boxes:,})"
    return case


def side_label(rows):
    scaled = any(abs(row["cube_side"] - row["paper_cube_side"]) > 1e-6 for row in rows)
    return "space length x (the paper's x scaled by the cube root of N's scale)" if scaled else "space length x"


def linear_fit(x, y):
    """Slope, intercept and Pearson correlation coefficient of y against x."""
    if len(x) < 2:
        return float("nan"), float("nan"), float("nan")
    slope, intercept = np.polyfit(x, y, 1)
    correlation = np.corrcoef(x, y)[0, 1] if len(x) > 2 or np.ptp(y) > 0 else float("nan")
    return slope, intercept, correlation


def growth_exponent(x, y):
    """k in y ~ x^k, fitted on log-log axes: 1 for linear growth."""
    keep = (x > 0) & (y > 0)
    if keep.sum() < 2:
        return float("nan")
    return np.polyfit(np.log(x[keep]), np.log(y[keep]), 1)[0]


def new_figure(title, xlabel, ylabel):
    figure, axes = plt.subplots(figsize=(6.4, 4.6))
    axes.set_title(title, fontsize=11)
    axes.set_xlabel(xlabel)
    axes.set_ylabel(ylabel)
    axes.grid(True, alpha=0.3)
    return figure, axes


def save(figure, folder, name, written):
    path = os.path.join(folder, name)
    figure.tight_layout()
    figure.savefig(path, dpi=110)
    plt.close(figure)
    written.append(path)


def plot_with_step_range(axes, x, rows, marker, label):
    """The median step time, with a bar from the fastest to the slowest timed step."""
    median = column(rows, "step_median_s")
    below = median - column(rows, "step_min_s")
    above = column(rows, "step_max_s") - median
    axes.errorbar(x, median, yerr=[below, above], marker=marker, capsize=3, elinewidth=0.8, label=label)


def memory_panels(title, xlabel):
    """Two panels side by side: the process's peak RSS and the bytes the structure holds."""
    figure, (left, right) = plt.subplots(1, 2, figsize=(11, 4.4))
    figure.suptitle(title, fontsize=11)
    for axes, label in ((left, "peak resident memory of the process (MB)"),
                        (right, "held by the smb World (MB, its own accounting)")):
        axes.set_xlabel(xlabel)
        axes.set_ylabel(label)
        axes.grid(True, alpha=0.3)
    return figure, left, right


def plot_section_41(rows, folder, prefix, subtitle, written, summary):
    cases = by_case(rows, lambda r: r["update_factor"])
    if not cases:
        return
    fits = []

    figure, axes = new_figure(f"Fig. 6: N against detection time{subtitle}", "total number of boxes N (thousands)",
                              "median detection time per step (s)")
    for marker, (case, case_rows) in zip(MARKERS, cases):
        n = column(case_rows, "boxes_median")
        t = column(case_rows, "step_median_s")
        slope, intercept, correlation = linear_fit(n, t)
        held_slope, _, held_correlation = linear_fit(n, column(case_rows, "bytes_held"))
        peak_slope, _, peak_correlation = linear_fit(n, column(case_rows, "peak_rss_bytes"))
        cpu = column(case_rows, "step_cpu_median_s")
        _, _, cpu_correlation = linear_fit(n, cpu)
        fits.append(dict(case=case, update_factor=case_rows[0]["update_factor"], n=n, t=t, slope=slope,
                         cpu=cpu, cpu_correlation=cpu_correlation, cpu_exponent=growth_exponent(n, cpu),
                         intercept=intercept, correlation=correlation, exponent=growth_exponent(n, t),
                         build=column(case_rows, "build_s"), held_slope=held_slope,
                         held_correlation=held_correlation, peak_slope=peak_slope,
                         peak_correlation=peak_correlation, rows=case_rows))
        line, = axes.plot(n / 1e3, t, marker=marker, label=case_title(case, case_rows))
        axes.plot(n / 1e3, intercept + slope * n, linestyle=":", color=line.get_color(), linewidth=1)
    axes.legend(title="dotted: least-squares line", fontsize=8, title_fontsize=8)
    axes.set_xlim(left=0)
    axes.set_ylim(bottom=0)
    save(figure, folder, f"{prefix}-fig06-time-vs-n.png", written)

    figure, axes = new_figure(f"Detection time per box against N{subtitle}", "total number of boxes N (thousands)",
                              "median detection time per step / N (µs)")
    for marker, fit in zip(MARKERS, fits):
        axes.plot(fit["n"] / 1e3, fit["t"] / fit["n"] * 1e6, marker=marker, label=case_title(fit["case"]))
    axes.legend(title="flat = linear in N", fontsize=8, title_fontsize=8)
    axes.set_xlim(left=0)
    axes.set_ylim(bottom=0)
    save(figure, folder, f"{prefix}-fig06b-time-per-box.png", written)

    figure, axes = new_figure(f"Fig. 7: linear dependence of time on N{subtitle}", "case number",
                              "correlation coefficient of time against N")
    numbers = np.arange(1, len(fits) + 1)
    correlations = np.array([fit["correlation"] for fit in fits])
    for number, marker, fit in zip(numbers, MARKERS, fits):
        axes.plot([number], [fit["correlation"]], marker=marker, markersize=9, linestyle="none",
                  label=f"Case {number}: {case_title(fit['case'])}")
    axes.set_xticks(numbers)
    low = np.nanmin(correlations) if np.isfinite(correlations).any() else 0.9
    axes.set_ylim(min(0.90, low - 0.01), 1.0)
    axes.legend(fontsize=8)
    save(figure, folder, f"{prefix}-fig07-correlation.png", written)

    figure, left, right = memory_panels(f"Fig. 8: N against total memory{subtitle}", "total number of boxes N (thousands)")
    for marker, fit in zip(MARKERS, fits):
        n_final = column(fit["rows"], "boxes_final")
        left.plot(n_final / 1e3, column(fit["rows"], "peak_rss_bytes") / MB, marker=marker,
                  label=case_title(fit["case"]))
        right.plot(n_final / 1e3, column(fit["rows"], "bytes_held") / MB, marker=marker, label=case_title(fit["case"]))
    largest = max(fit["n"].max() for fit in fits)
    for axes in (left, right):
        axes.plot([0, largest / 1e3], [0, largest * PAPER_BYTES_PER_BOX / MB], color="grey", linestyle="--",
                  linewidth=1, label=f"paper, about {PAPER_BYTES_PER_BOX} B/box (its Fig. 8)")
        axes.legend(fontsize=8)
        axes.set_xlim(left=0)
        axes.set_ylim(bottom=0)
    save(figure, folder, f"{prefix}-fig08-memory-vs-n.png", written)

    summary.append("## Section 4.1: N and the update factor (Table 1, Figs 6-8)\n")
    summary.append("Time t (median step after the build step) fitted as t = a + b·N over the median N of the timed "
                   "steps; r is Pearson's correlation coefficient of t against N (the paper's Fig. 7); k is the "
                   "exponent of t ~ N^k fitted on log-log axes (1 = linear).\n")
    summary.append("| Λ | b (µs per box) | a (ms) | r | k | r, k of CPU time | t at largest N (s) "
                   "| µs/box smallest → largest N | build at largest N (s) |")
    summary.append("|---|---|---|---|---|---|---|---|---|")
    for fit in fits:
        per_box = fit["t"] / fit["n"] * 1e6
        summary.append(f"| {fit['update_factor']:g} | {fit['slope'] * 1e6:.3f} | {fit['intercept'] * 1e3:.1f} | "
                       f"{fit['correlation']:.4f} | {fit['exponent']:.3f} | {fit['cpu_correlation']:.4f}, "
                       f"{fit['cpu_exponent']:.3f} | {fit['t'][-1]:.3f} | {per_box[0]:.2f} → {per_box[-1]:.2f} | "
                       f"{fit['build'][-1]:.3f} |")
    summary.append("")
    summary.append("Where the time of a step goes (median phase times of the `DetectStats`, µs per box) at the "
                   "smallest N above 10 000 and at the largest N:\n")
    summary.append("| Λ | N | sort | cut + regroup | check | N | sort | cut + regroup | check |")
    summary.append("|---|---|---|---|---|---|---|---|---|")
    for fit in fits:
        cells = [f"{fit['update_factor']:g}"]
        large_rows = [row for row in fit["rows"] if row["boxes"] > 10_000] or fit["rows"]
        for row in (large_rows[0], fit["rows"][-1]):
            per_box = 1e6 / row["boxes_median"]
            phases = [row["sort_s"], row["cut_regroup_s"], row["check_s"]]
            cells += [f"{row['boxes']:.0f}"] + [f"{value * per_box:.2f}" for value in phases]
        summary.append("| " + " | ".join(cells) + " |")
    summary.append("")
    summary.append("Memory against N (final N of each run): slope of a least-squares line (bytes per box) and r.\n")
    summary.append("| Λ | held: bytes/box (slope) | held: r | peak RSS: bytes/box (slope) | peak RSS: r "
                   "| peak RSS at largest N (MB) | held at largest N (MB) |")
    summary.append("|---|---|---|---|---|---|---|")
    for fit in fits:
        summary.append(f"| {fit['update_factor']:g} | {fit['held_slope']:.0f} | {fit['held_correlation']:.5f} | "
                       f"{fit['peak_slope']:.0f} | {fit['peak_correlation']:.5f} | "
                       f"{fit['rows'][-1]['peak_rss_bytes'] / MB:.0f} | {fit['rows'][-1]['bytes_held'] / MB:.0f} |")
    summary.append("")
    summary.append("Every run of Section 4.1 (time in s, memory in bytes per box of the final N):\n")
    summary.append("| Λ | N | N final | E | H | build | step median | min | max | CPU median | pairs | held B/box "
                   "| peak RSS B/box |")
    summary.append("|---|---|---|---|---|---|---|---|---|---|---|---|---|")
    for fit in fits:
        for row in fit["rows"]:
            summary.append(f"| {row['update_factor']:g} | {row['boxes']:.0f} | {row['boxes_final']:.0f} | "
                           f"{row['packing_density']:.2f} | {row['size_ratio']:g} | {row['build_s']:.3f} | "
                           f"{row['step_median_s']:.4f} | {row['step_min_s']:.4f} | {row['step_max_s']:.4f} | "
                           f"{row.get('step_cpu_median_s', float('nan')):.4f} | {row['pairs_median']:.0f} | "
                           f"{row['bytes_per_box']:.0f} | {row['peak_rss_per_box']:.0f} |")
    summary.append("")


def spread_table(summary, cases, varied_key, varied_label):
    summary.append(f"| case | {varied_label} range | E range | t min (s) | t max (s) | max/min | (max-min)/median "
                   "| CPU time max/min | held B/box range | peak RSS MB range |")
    summary.append("|---|---|---|---|---|---|---|---|---|---|")
    for case, case_rows in cases:
        t = column(case_rows, "step_median_s")
        varied = column(case_rows, varied_key)
        density = column(case_rows, "packing_density")
        held = column(case_rows, "bytes_per_box")
        peak = column(case_rows, "peak_rss_bytes") / MB
        cpu = column(case_rows, "step_cpu_median_s")
        summary.append(f"| {case_title(case, case_rows)} | {varied.min():.4g}–{varied.max():.4g} | {density.min():.3f}–"
                       f"{density.max():.3f} | {t.min():.3f} | {t.max():.3f} | {t.max() / t.min():.2f} | "
                       f"{(t.max() - t.min()) / np.median(t):.2f} | {cpu.max() / cpu.min():.2f} | "
                       f"{held.min():.0f}–{held.max():.0f} | "
                       f"{peak.min():.0f}–{peak.max():.0f} |")
    summary.append("")


def run_table(summary, cases, varied_key, varied_label):
    summary.append(f"| case | {varied_label} | E | build (s) | step median (s) | min | max | CPU median | pairs "
                   "| oversized | held B/box | peak RSS (MB) |")
    summary.append("|---|---|---|---|---|---|---|---|---|---|---|---|")
    for case, case_rows in cases:
        for row in case_rows:
            summary.append(f"| {case_title(case, case_rows)} | {row[varied_key]:g} | {row['packing_density']:.3f} | "
                           f"{row['build_s']:.3f} | {row['step_median_s']:.4f} | {row['step_min_s']:.4f} | "
                           f"{row['step_max_s']:.4f} | {row.get('step_cpu_median_s', float('nan')):.4f} | "
                           f"{row['pairs_median']:.0f} | {row['oversized_boxes']:.0f} | "
                           f"{row['bytes_per_box']:.0f} | {row['peak_rss_bytes'] / MB:.0f} |")
    summary.append("")


def plot_section_42(rows, folder, prefix, subtitle, written, summary):
    cases = by_case(rows, lambda r: r["boxes"])
    if not cases:
        return
    figure, axes = new_figure(f"Fig. 9: packing density against detection time{subtitle}", "packing density E",
                              "median detection time per step (s)")
    for marker, (case, case_rows) in zip(MARKERS, cases):
        plot_with_step_range(axes, column(case_rows, "packing_density"), case_rows, marker,
                             case_title(case, case_rows))
    axes.legend(title="bars: fastest to slowest timed step", fontsize=8, title_fontsize=8)
    axes.set_xlim(left=0)
    axes.set_ylim(bottom=0)
    save(figure, folder, f"{prefix}-fig09-time-vs-density.png", written)

    figure, left, right = memory_panels(f"Fig. 10: space length against total memory{subtitle}", side_label(rows))
    for marker, (case, case_rows) in zip(MARKERS, cases):
        x = column(case_rows, "cube_side")
        left.plot(x, column(case_rows, "peak_rss_bytes") / MB, marker=marker, label=case_title(case, case_rows))
        right.plot(x, column(case_rows, "bytes_held") / MB, marker=marker, label=case_title(case, case_rows))
    for axes in (left, right):
        axes.legend(fontsize=8)
        axes.set_ylim(bottom=0)
    save(figure, folder, f"{prefix}-fig10-memory-vs-side.png", written)

    summary.append("## Section 4.2: space size and packing density (Table 2, Figs 9-10)\n")
    summary.append("H = 10, Λ = 1e-5. Spread of the median step time over the space lengths x of each case:\n")
    spread_table(summary, cases, "cube_side", "x")
    run_table(summary, cases, "cube_side", "x")


def plot_section_43(rows, folder, prefix, subtitle, written, summary):
    cases = by_case(rows, lambda r: r["boxes"])
    if not cases:
        return
    figure, axes = new_figure(f"Fig. 11: size ratio against detection time{subtitle}", "size ratio H",
                              "median detection time per step (s)")
    for marker, (case, case_rows) in zip(MARKERS, cases):
        plot_with_step_range(axes, column(case_rows, "size_ratio"), case_rows, marker, case_title(case, case_rows))
    axes.legend(title="bars: fastest to slowest timed step", fontsize=8, title_fontsize=8)
    axes.set_xlim(left=0)
    axes.set_ylim(bottom=0)
    save(figure, folder, f"{prefix}-fig11-time-vs-size-ratio.png", written)

    figure, left, right = memory_panels(f"Fig. 12: size ratio against total memory{subtitle}", "size ratio H")
    for marker, (case, case_rows) in zip(MARKERS, cases):
        h = column(case_rows, "size_ratio")
        left.plot(h, column(case_rows, "peak_rss_bytes") / MB, marker=marker, label=case_title(case, case_rows))
        right.plot(h, column(case_rows, "bytes_held") / MB, marker=marker, label=case_title(case, case_rows))
    for axes in (left, right):
        axes.legend(fontsize=8)
        axes.set_xlim(left=0)
        axes.set_ylim(bottom=0)
    save(figure, folder, f"{prefix}-fig12-memory-vs-size-ratio.png", written)

    summary.append("## Section 4.3: size ratio (Table 3, Figs 11-12)\n")
    summary.append("x = 200 (scaled with N below full size), Λ = 1e-5. Spread of the median step time over H:\n")
    spread_table(summary, cases, "size_ratio", "H")
    run_table(summary, cases, "size_ratio", "H")


def main():
    parser = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    parser.add_argument("--dir", default=os.path.join(REPO_ROOT, "bench", "results", "cpp-2core", "reproduction"))
    parser.add_argument("--mode", default="full", help="prefix of the CSV files (full, quick, smoke)")
    args = parser.parse_args()

    sections = {name: read_rows(os.path.join(args.dir, f"{args.mode}-{name}.csv")) for name in ("4.1", "4.2", "4.3")}
    if not any(sections.values()):
        sys.exit(f"plot-reproduction.py: no {args.mode}-4.*.csv in {args.dir}")
    steps = {int(row["steps_timed"]) for rows in sections.values() for row in rows}
    subtitle = f"\n(smb, {args.mode} mode, median of {'/'.join(map(str, sorted(steps)))} steps after the build step)"
    written = []
    summary = [f"# Reproduction of Section 4 ({args.mode} mode): fits and spreads\n",
               f"Written by scripts/plot-reproduction.py from {args.mode}-4.*.csv; "
               f"{'/'.join(map(str, sorted(steps)))} timed steps after the build step per run.\n"]
    plot_section_41(sections["4.1"], args.dir, args.mode, subtitle, written, summary)
    plot_section_42(sections["4.2"], args.dir, args.mode, subtitle, written, summary)
    plot_section_43(sections["4.3"], args.dir, args.mode, subtitle, written, summary)
    summary_path = os.path.join(args.dir, f"{args.mode}-summary.md")
    with open(summary_path, "w") as out:
        out.write("\n".join(summary) + "\n")
    written.append(summary_path)
    for path in written:
        print(os.path.relpath(path))


if __name__ == "__main__":
    main()
