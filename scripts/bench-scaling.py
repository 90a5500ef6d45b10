#!/usr/bin/env python3
# SPDX-License-Identifier: MIT
"""Time per box against N: `smb run` (the paper's 3D environment, double coordinates) at each N,
one process per run, with 1 and 2 threads. Writes a CSV and prints a Markdown table.

    /usr/bin/python3 scripts/bench-scaling.py --smb build/tools/smb/smb \
        --boxes 10000,100000,1000000,10000000 --threads 1,2 --steps 6 \
        --out bench/results/cpp-2core/scaling.csv

The time of a run is the median detect() wall time over the steps after the build step; the
world update (batch insert/update/remove) is timed apart by `smb run` and not included.
"""
import argparse
import csv
import json
import os
import subprocess
import sys


def main():
    parser = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    parser.add_argument("--smb", default=os.path.join(os.path.dirname(__file__), "..", "build", "tools", "smb", "smb"))
    parser.add_argument("--boxes", default="10000,100000,1000000,10000000")
    parser.add_argument("--threads", default="1,2")
    parser.add_argument("--update-factor", default="0.001")
    parser.add_argument("--dim", default="3")
    parser.add_argument("--steps", type=int, default=6, help="steps including the build step")
    parser.add_argument("--pipeline", default="persistent", choices=("persistent", "paper"))
    parser.add_argument("--out", default="")
    args = parser.parse_args()

    rows = []
    for boxes in [int(b) for b in args.boxes.split(",")]:
        for threads in [int(t) for t in args.threads.split(",")]:
            command = [args.smb, "run", "--json", "--no-progress", "--no-check", "--dim", args.dim, "-n", str(boxes),
                       "--update-factor", args.update_factor, "--steps", str(args.steps), "--threads", str(threads),
                       "--pipeline", args.pipeline]
            done = subprocess.run(command, capture_output=True, text=True, check=True)
            summary = json.loads(done.stdout)
            detect = summary["detect_seconds"]
            row = {
                "boxes": boxes, "threads": threads, "dim": args.dim, "update_factor": args.update_factor,
                "pipeline": args.pipeline, "build_s": summary["build_seconds"], "median_step_s": detect["median"],
                "min_step_s": detect["min"], "max_step_s": detect["max"],
                "ns_per_box": 1e9 * detect["median"] / boxes, "bytes_per_box": summary["bytes_per_box"],
                "peak_rss_bytes": summary["peak_rss_bytes"], "pairs_last": summary["pairs"]["last"],
                "cut_regroup_s": summary["phase_seconds_median"]["cut_regroup"],
                "check_s": summary["phase_seconds_median"]["check"],
            }
            rows.append(row)
            print(f"N {boxes:>9} threads {threads}: build {row['build_s'] * 1e3:9.1f} ms, step median "
                  f"{row['median_step_s'] * 1e3:9.2f} ms ({row['ns_per_box']:6.1f} ns/box), "
                  f"{row['bytes_per_box']:6.1f} B/box held", flush=True)
    if args.out:
        os.makedirs(os.path.dirname(os.path.abspath(args.out)), exist_ok=True)
        with open(args.out, "w", newline="") as handle:
            writer = csv.DictWriter(handle, fieldnames=list(rows[0].keys()))
            writer.writeheader()
            writer.writerows(rows)
    print("\n| N | threads | build | median step | ns per box | bytes per box held |")
    print("|---|---|---|---|---|---|")
    for row in rows:
        print(f"| {row['boxes']:,} | {row['threads']} | {row['build_s'] * 1e3:.1f} ms | "
              f"{row['median_step_s'] * 1e3:.2f} ms | {row['ns_per_box']:.1f} | {row['bytes_per_box']:.0f} |")


if __name__ == "__main__":
    sys.exit(main())
