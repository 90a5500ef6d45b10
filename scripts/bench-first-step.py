#!/usr/bin/env python3
# SPDX-License-Identifier: MIT
"""Times the first (build) step of several methods side by side on the paper's scenes.

Runs `smb_compare --steps 1 --no-check` for every method, dimension and size, round after round
(the methods alternate, so that the shared machine's slow minutes fall on all of them), appends
the JSON lines to a .jsonl file and prints the median first step of each method.

Usage: /usr/bin/python3 scripts/bench-first-step.py --build-dir build-peers \\
           --output bench/results/cpp-2core/build-step.jsonl
"""

import argparse
import collections
import json
import pathlib
import statistics
import subprocess
import sys


def main() -> int:
    parser = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    parser.add_argument("--build-dir", default="build-peers")
    parser.add_argument("--methods", default="smb,smb_detector,uniform_grid")
    parser.add_argument("--dims", default="2,3")
    parser.add_argument("--boxes", default="100000,1000000")
    parser.add_argument("--lambda", dest="update_factor", default="1e-3")
    parser.add_argument("--rounds", type=int, default=3)
    parser.add_argument("--output", required=True, help="the .jsonl file the lines are written to")
    args = parser.parse_args()

    compare = pathlib.Path(args.build_dir) / "bench" / "smb_compare"
    if not compare.exists():
        print(f"no {compare}: build the smb_compare target first", file=sys.stderr)
        return 1
    output = pathlib.Path(args.output)
    output.parent.mkdir(parents=True, exist_ok=True)
    first_steps = collections.defaultdict(list)
    with output.open("w") as lines:
        for _ in range(args.rounds):
            for dim in args.dims.split(","):
                for boxes in args.boxes.split(","):
                    for method in args.methods.split(","):
                        run = subprocess.run(
                            [str(compare), "--method", method, "--scene", "paper", "--dim", dim, "--boxes", boxes,
                             "--lambda", args.update_factor, "--steps", "1", "--no-check"],
                            check=True, capture_output=True, text=True)
                        lines.write(run.stdout)
                        record = json.loads(run.stdout)
                        first_steps[(int(dim), int(boxes), method)].append(record["first_step_s"] * 1e3)
    print("dim,boxes,method,median_first_step_ms,runs_ms")
    for (dim, boxes, method), times in sorted(first_steps.items()):
        runs = " ".join(f"{t:.1f}" for t in times)
        print(f"{dim},{boxes},{method},{statistics.median(times):.1f},{runs}")
    return 0


if __name__ == "__main__":
    sys.exit(main())
