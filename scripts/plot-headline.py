#!/usr/bin/env python3
# SPDX-License-Identifier: MIT
"""Draws the headline run (scripts/bench-headline.py) as one chart: for every scene, the grid's
steady step over smb's (World and Detector; above 1: smb is faster), on a log scale, with the
line at 1 where smb and the grid are level.

Usage: /usr/bin/python3 scripts/plot-headline.py bench/results/cpp-2core/headline.csv
       [--output bench/results/cpp-2core/headline-ratios.png]
Needs matplotlib (Debian's python3-matplotlib).
"""

import argparse
import csv
import math
import os

import matplotlib

matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402

# The methods drawn, as the run names them, and their labels.
METHODS = [
    ("smb", "smb World"),
    ("smb_detector", "smb Detector"),
    ("smb_detector_skin", "smb Detector, skin 0.1"),
    ("verlet_grid", "Verlet-skin grid"),
]


def scene_name(row):
    name = row["family"] if row["family"] != "paper" else "paper"
    boxes = int(row["boxes"])
    size = f"{boxes // 1000000}M" if boxes >= 1000000 else f"{boxes // 1000}k"
    return f"{name} {row['dim']}D {size}, Λ {float(row['lambda']):g}"


def main():
    parser = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    parser.add_argument("csv", help="headline.csv written by scripts/bench-headline.py")
    parser.add_argument("--output", help="the PNG to write (default: headline-ratios.png beside the CSV)")
    args = parser.parse_args()
    output = args.output or os.path.join(os.path.dirname(args.csv), "headline-ratios.png")

    scenes = []  # in the run's order
    ratios = {}
    with open(args.csv, newline="") as handle:
        for row in csv.DictReader(handle):
            scene = scene_name(row)
            if scene not in scenes:
                scenes.append(scene)
            ratios[(scene, row["method"])] = float(row["grid_over_steady"])

    drawn = [(method, label) for method, label in METHODS if any((s, method) in ratios for s in scenes)]
    height = 0.8 / len(drawn)
    figure, axes = plt.subplots(figsize=(9, 0.42 * len(scenes) + 1.5))
    for index, (method, label) in enumerate(drawn):
        ys = [row - 0.4 + height * (index + 0.5) for row, scene in enumerate(scenes) if (scene, method) in ratios]
        xs = [ratios[(scene, method)] for scene in scenes if (scene, method) in ratios]
        axes.barh(ys, xs, height=height, label=label, left=0)
    axes.axvline(1.0, color="black", linewidth=1)
    axes.set_xscale("log")
    # Wide enough for the largest ratio (the skin against the grid rebuilt every step).
    top = 4.0
    while top < max(ratios.values()) * 1.05:
        top *= 2
    ticks = [0.25 * 2**k for k in range(int(round(math.log2(top / 0.25))) + 1)]
    axes.set_xlim(0.25, top)
    axes.set_xticks(ticks)
    axes.set_xticklabels([f"{tick:g}×" for tick in ticks])
    axes.set_yticks(range(len(scenes)))
    axes.set_yticklabels(scenes)
    axes.invert_yaxis()
    axes.set_xlabel("uniform grid's steady step ÷ the method's (right of 1: faster than the grid)")
    axes.set_title("One thread, steady step, every method's pairs equal at every step")
    axes.legend(loc="lower right")
    figure.tight_layout()
    figure.savefig(output, dpi=110)
    print(f"wrote {output}")


if __name__ == "__main__":
    main()
