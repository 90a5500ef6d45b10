#!/usr/bin/env python3
# SPDX-License-Identifier: MIT
"""The paper's pipeline measured with the counts that explain its time (docs/reproduction.md,
"The paper's segment rule" and "Why the time per box grows with N"). One `smb run --json` process
per run, the paper's 3D (or 2D) environment at E = 0.4, H = 2.5; runs of one configuration that
differ only in what is compared follow each other, so that a change of load hits both.

    # the paper's segment rule against the count from N
    /usr/bin/python3 scripts/paper-counts.py --compare rule --dims 3,2 --boxes 10000,100000,1000000 \\
        --update-factors 0.001,0.01 --cell-populations 24,8 --steps 6 \\
        --out bench/results/cpp-2core/paper-segment-rule.csv
    # the counts against N, the paper's lists beside the persistent cuts
    /usr/bin/python3 scripts/paper-counts.py --compare pipeline --dims 3 \\
        --boxes 10000,30000,100000,300000,1000000 --update-factors 0.001 --steps 10 \\
        --out bench/results/cpp-2core/paper-counts.csv

The time of a run is the median detect() wall time over the steps after the build step; each
count is its median over the same steps, per box (per item of its level for the level counts).
"""
import argparse
import csv
import json
import os
import subprocess


def run_one(args, dim, boxes, update_factor, population, pipeline, rule):
    command = [args.smb, "run", "--json", "--no-progress", "--no-check", "--dim", str(dim), "-n", str(boxes),
               "--update-factor", update_factor, "--steps", str(args.steps), "--pipeline", pipeline,
               "--cell-population", population]
    if pipeline == "paper":
        command += ["--segment-rule", rule]
    summary = json.loads(subprocess.run(command, capture_output=True, text=True, check=True).stdout)
    n = summary["boxes"]["median"]
    phases = summary["phase_seconds_median"]
    counts = summary["counts_median"]
    row = {
        "dim": dim, "boxes": boxes, "median_boxes": n, "update_factor": update_factor,
        "cell_population": population, "pipeline": pipeline,
        "segment_rule": rule if pipeline == "paper" else "", "build_s": summary["build_seconds"],
        "step_s": summary["detect_seconds"]["median"], "step_cpu_s": summary["detect_cpu_seconds"]["median"],
        "us_per_box": 1e6 * summary["detect_seconds"]["median"] / n,
        "list_sort_us_per_box": 1e6 * phases["list_sort"] / n,
        "cut_regroup_us_per_box": 1e6 * (phases["cut_regroup"] + phases["quantile"]) / n,
        "check_us_per_box": 1e6 * phases["check"] / n,
        "bytes_per_box": summary["bytes_per_box"], "peak_rss_bytes": summary["peak_rss_bytes"],
        "pairs_per_box": summary["pairs"]["median"] / n, "cells": counts["cells"],
        "boxes_per_cell": n / counts["cells"], "oversized_last": summary["oversized_boxes_last"],
        "largest_cell_boxes": counts.get("largest_cell_boxes", ""),
        "sort_moves_per_box": counts["sort_moves"] / n,
    }
    for axis, level in counts.get("levels", {}).items():
        items = n * 2 ** (list(counts["levels"]).index(axis) + 1)
        row[f"{axis}_moves_per_item"] = level["sort_moves"] / items
        row[f"{axis}_comparisons_per_item"] = level["sort_comparisons"] / items
        row[f"{axis}_singular_fraction"] = level["singular_items"] / items
        row[f"{axis}_fallback_fraction"] = level["sort_fallback_items"] / items
    return row


def main():
    parser = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    parser.add_argument("--smb", default=os.path.join(os.path.dirname(__file__), "..", "build", "tools", "smb", "smb"))
    parser.add_argument("--compare", choices=("rule", "pipeline"), default="rule")
    parser.add_argument("--dims", default="3")
    parser.add_argument("--boxes", default="10000,100000")
    parser.add_argument("--update-factors", default="0.001")
    parser.add_argument("--cell-populations", default="24", help="--cell-population of smb run, a list")
    parser.add_argument("--steps", type=int, default=6, help="steps including the build step")
    parser.add_argument("--out", default="")
    args = parser.parse_args()

    variants = [("paper", "count"), ("paper", "paper")] if args.compare == "rule" else [("paper", "count"),
                                                                                         ("persistent", "")]
    rows = []
    with open("/proc/loadavg") as handle:
        print("load at start:", handle.read().split()[:3], flush=True)
    for dim in [int(d) for d in args.dims.split(",")]:
        for boxes in [int(b) for b in args.boxes.split(",")]:
            for update_factor in args.update_factors.split(","):
                for population in args.cell_populations.split(","):
                    for pipeline, rule in variants:
                        row = run_one(args, dim, boxes, update_factor, population, pipeline, rule)
                        with open("/proc/loadavg") as handle:
                            row["load"] = float(handle.read().split()[0])
                        rows.append(row)
                        print(f"{dim}D N {boxes:>8} L {update_factor:>6} pop {population:>3} {pipeline:>10} "
                              f"{rule:>5}: {row['step_s'] * 1e3:9.2f} ms ({row['us_per_box']:.3f} us/box, CPU "
                              f"{row['step_cpu_s'] * 1e3:.2f} ms), {row['bytes_per_box']:.1f} B/box, "
                              f"{row['boxes_per_cell']:.1f} boxes/cell, largest {row['largest_cell_boxes']}, "
                              f"oversized {row['oversized_last']}, load {row['load']}", flush=True)
    if args.out:
        os.makedirs(os.path.dirname(os.path.abspath(args.out)), exist_ok=True)
        fields = []
        for row in rows:
            fields += [key for key in row if key not in fields]
        with open(args.out, "w", newline="") as handle:
            writer = csv.DictWriter(handle, fieldnames=fields)
            writer.writeheader()
            writer.writerows(rows)


if __name__ == "__main__":
    main()
