#!/usr/bin/python3
# SPDX-License-Identifier: MIT
"""Plots and tables from a comparison CSV written by scripts/bench-compare.py.

Writes next to the CSV (bench/results/<machine>/):
    <mode>-step-time-L<Λ>.png   median step time against N, one line per method, 3D and 2D
    <mode>-memory-per-box.png    bytes per box against N (paper scenes, Λ = 1e-3)
    <mode>-tables.md             step time, first step and memory tables with ratios to smb
Usage: scripts/plot-compare.py bench/results/cpp-2core/quick.csv
"""

import csv
import os
import sys
from collections import defaultdict

import matplotlib

matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402

METHOD_ORDER = ["smb", "smb_2threads", "smb_double", "smb_paper", "smb_detector", "smb_detector_2threads",
                "smb_detector_skin", "smb_detector_skin_2threads", "brute_force", "box_pruning", "uniform_grid",
                "uniform_grid_every_cell", "cgal_box_intersection", "bullet_axis_sweep", "bullet_dbvt",
                "box2d_dynamic_tree"]
SHORT = {"smb": "smb", "smb_2threads": "smb 2 threads", "smb_paper": "smb paper lists", "smb_double": "smb double",
         "smb_detector": "Detector", "smb_detector_2threads": "Detector 2 threads",
         "smb_detector_skin": "Detector skin", "smb_detector_skin_2threads": "Detector skin 2 threads",
         "uniform_grid_every_cell": "grid (every cell)", "brute_force": "brute", "box_pruning": "box pruning", "uniform_grid": "grid",
         "cgal_box_intersection": "CGAL", "bullet_axis_sweep": "Bullet SAP", "bullet_dbvt": "Bullet DBVT",
         "box2d_dynamic_tree": "Box2D tree"}
STYLE = {"smb": dict(color="black", linewidth=2.5, marker="o"),
         "smb_2threads": dict(color="black", linewidth=1.5, linestyle="--", marker="o"),
         "smb_paper": dict(color="grey", linewidth=1.5, linestyle=":", marker="o")}


def load(path):
    with open(path) as handle:
        return list(csv.DictReader(handle))


def scene_key(row):
    return (row["family"], int(row["dim"]), float(row["lambda"]), int(row["boxes"]))


def plot_lines(rows, value, ylabel, title, path, family, update_factor, log_y=True):
    fig, axes = plt.subplots(1, 2, figsize=(11, 4.2))
    for ax, dim in zip(axes, (3, 2)):
        series = defaultdict(list)
        for r in rows:
            if r["status"] == "ok" and r["family"] == family and int(r["dim"]) == dim and \
                    float(r["lambda"]) == update_factor and r[value]:
                series[r["method"]].append((int(r["boxes"]), float(r[value])))
        for method in METHOD_ORDER:
            if method in series:
                points = sorted(series[method])
                ax.plot([p[0] for p in points], [p[1] for p in points], label=SHORT[method],
                        **STYLE.get(method, dict(marker=".")))
        ax.set_xscale("log")
        if log_y:
            ax.set_yscale("log")
        else:
            ax.set_ylim(bottom=0)
        ax.set_xlabel("boxes N")
        ax.set_ylabel(ylabel)
        ax.set_title(f"{dim}D")
        ax.grid(True, which="both", alpha=0.3)
        if series:
            ax.legend(fontsize=8)
    fig.suptitle(title)
    fig.tight_layout()
    fig.savefig(path, dpi=110)
    plt.close(fig)


def format_cell(row, value, smb_row, scale, unit):
    if row is None:
        return "–"
    if row["status"] != "ok":
        return "skipped"
    if not row.get(value):
        return "–"
    number = float(row[value]) * scale
    text = f"{number:.3g}{unit}"
    if smb_row is not None and row["method"] != "smb" and smb_row.get(value) and float(smb_row[value]) > 0:
        text += f" ({float(row[value]) / float(smb_row[value]):.2g}×)"
    return text


def tables(rows, methods):
    by_scene = defaultdict(dict)
    for r in rows:
        by_scene[scene_key(r)][r["method"]] = r
    header = "| scene | Λ | N | pairs | " + " | ".join(SHORT[m] for m in methods) + " |"
    rule = "|" + "---|" * (4 + len(methods))
    out = []
    kinds = [("Median time per step (ratio to smb; above 1 = smb faster)", "median_step_s", 1e3, " ms")]
    # Runs longer than ten steps after the build: those ten and the later (steady) ones apart.
    if any(r.get("steady_median_s") for r in rows):
        kinds += [("Steps 1-10 after the build, median (ratio to smb)", "early_median_s", 1e3, " ms"),
                  ("Steady state: median of the steps after the first ten (ratio to smb)", "steady_median_s", 1e3,
                   " ms")]
    kinds += [("First step: build and detect (ratio to smb)", "first_step_s", 1e3, " ms"),
              ("Memory: peak heap bytes per box allocated by the method (ratio to smb)", "bytes_per_box", 1, " B")]
    for title, value, scale, unit in kinds:
        out += [f"### {title}", "", header, rule]
        for key in sorted(by_scene, key=lambda k: (k[0], -k[1], k[2], k[3])):
            family, dim, update_factor, boxes = key
            scene = by_scene[key]
            smb = scene.get("smb")
            pairs = next((r["pairs_last"] for r in scene.values() if r["status"] == "ok"), "")
            cells = [format_cell(scene.get(m), value, smb, scale, unit) for m in methods]
            out.append(f"| {family} {dim}D | {update_factor:g} | {boxes:,} | {pairs} | " + " | ".join(cells) + " |")
        out.append("")
    disagree = [r for r in rows if r["status"] == "ok" and r.get("agrees", "").startswith("NO")]
    out.append("Pair sets: " + ("every method reported the same pairs at every step of every scene "
                                "(per-step digests of the sorted pair lists)." if not disagree else
                                "DISAGREEMENTS: " + "; ".join(f"{r['method']} on {scene_key(r)}" for r in disagree)))
    skipped = [r for r in rows if r["status"] != "ok"]
    if skipped:
        out += ["", "Skipped runs:", ""]
        out += [f"- {SHORT.get(r['method'], r['method'])} on {r['family']} {r['dim']}D Λ={float(r['lambda']):g} "
                f"N={int(r['boxes']):,}: {r['note']}" for r in skipped]
    return "\n".join(out) + "\n"


def main():
    if len(sys.argv) != 2:
        print(__doc__)
        return 2
    path = sys.argv[1]
    rows = load(path)
    out_dir = os.path.dirname(path)
    mode = os.path.splitext(os.path.basename(path))[0]
    update_factors = sorted({float(r["lambda"]) for r in rows if r["family"] == "paper"})
    for update_factor in update_factors:
        plot_lines(rows, "median_step_s", "median seconds per step",
                   f"Paper environment, Λ = {update_factor:g}: time per step",
                   os.path.join(out_dir, f"{mode}-step-time-L{update_factor:g}.png"), "paper", update_factor)
    memory_factor = 1e-3 if 1e-3 in update_factors else (update_factors[0] if update_factors else None)
    if memory_factor is not None:
        plot_lines(rows, "bytes_per_box", "peak heap bytes per box",
                   f"Paper environment, Λ = {memory_factor:g}: memory per box",
                   os.path.join(out_dir, f"{mode}-memory-per-box.png"), "paper", memory_factor, log_y=False)
    present = {r["method"] for r in rows}
    methods = [m for m in METHOD_ORDER if m in present]
    with open(os.path.join(out_dir, f"{mode}-tables.md"), "w") as handle:
        handle.write(tables(rows, methods))
    print(f"wrote plots and {mode}-tables.md in {out_dir}")
    return 0


if __name__ == "__main__":
    sys.exit(main())
