#!/usr/bin/env python3
# SPDX-License-Identifier: MIT
"""Draws the distributed detector's decomposition (docs/distributed.md): the boxes of a 2D
scene CSV (its first frame) and the region of every rank, as written by
smb_distributed_steps's REGIONS_CSV.

Usage: plot-distributed.py SCENE_CSV REGIONS_CSV OUTPUT_PNG"""
import csv
import sys

import matplotlib

matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402
from matplotlib.patches import Rectangle  # noqa: E402


def main():
    scene_path, regions_path, output_path = sys.argv[1:4]
    boxes = []
    with open(scene_path, newline="") as scene:
        for row in csv.DictReader(scene):
            if row["frame"] != "0":
                break
            boxes.append(tuple(float(row[k]) for k in ("xmin", "ymin", "xmax", "ymax")))
    low = min(min(b[0], b[1]) for b in boxes)
    high = max(max(b[2], b[3]) for b in boxes)
    regions = []
    with open(regions_path) as lines:
        for line in lines:
            rank, xmin, ymin, xmax, ymax = line.strip().split(",")
            clip = lambda v: min(max(float(v), low), high)  # noqa: E731 (infinite outer faces)
            regions.append((int(rank), clip(xmin), clip(ymin), clip(xmax), clip(ymax)))
    figure, axes = plt.subplots(figsize=(7, 7))
    colours = plt.cm.tab10.colors
    for rank, xmin, ymin, xmax, ymax in regions:
        axes.add_patch(Rectangle((xmin, ymin), xmax - xmin, ymax - ymin, facecolor=colours[rank % 10], alpha=0.15))
        axes.text((xmin + xmax) / 2, (ymin + ymax) / 2, f"rank {rank}", ha="center", va="center", fontsize=14)
    for xmin, ymin, xmax, ymax in boxes:
        axes.add_patch(Rectangle((xmin, ymin), xmax - xmin, ymax - ymin, fill=False, linewidth=0.3, edgecolor="0.3"))
    for rank, xmin, ymin, xmax, ymax in regions:
        axes.add_patch(Rectangle((xmin, ymin), xmax - xmin, ymax - ymin, fill=False, linewidth=2, edgecolor="black"))
    axes.set_xlim(low, high)
    axes.set_ylim(low, high)
    axes.set_aspect("equal")
    axes.set_title(f"{len(boxes)} boxes, {len(regions)} regions of equal population (x cut first, then y)")
    figure.tight_layout()
    figure.savefig(output_path, dpi=110)
    print(f"wrote {output_path}")


if __name__ == "__main__":
    main()
