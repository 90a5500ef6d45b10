#!/usr/bin/python3
# SPDX-License-Identifier: MIT
"""Reproduces the experiments of the paper's Section 4 (Li, Feng & Owen 2006) with `smb run`.

Every configuration runs in its own process (`smb run --json --no-check`), so the peak resident
memory it reports belongs to that configuration alone. Time is the median detection time over
the steps after the first (build) step, which is reported apart. Writes, after every run:
    <out>/<mode>-4.1.csv   Table 1, Figs 6-8: N and the update factor Λ (E and H per N as Table 1)
    <out>/<mode>-4.2.csv   Table 2, Figs 9-10: space size x (so packing density E), N 400k-800k
    <out>/<mode>-4.3.csv   Table 3, Figs 11-12: size ratio H, N 500k-900k
    <out>/<mode>-meta.json how it ran: commands, steps, machine, load, durations
Plot them with scripts/plot-reproduction.py.

Modes: full (the paper's sizes), quick (N / 10, fewer points; about a minute on 2 cores) and
smoke (N / 500, seconds; for CI). Sizes scaled below the paper's keep the paper's packing
densities: the cube side x is scaled by the cube root of the N scale.

--dim 2 runs experiment 4.1 with squares (E = N((a+b)/2)^2 / x^2); the other two experiments
set the cube side of the paper's 3D tables and exist in 3D only. --update-factors keeps a subset
of 4.1's update factors, so that one experiment can be shared among several processes.

Usage: scripts/reproduce.py --mode quick [--smb build/tools/smb/smb] [--out DIR] [--dim 2|3]
"""

import argparse
import csv
import json
import os
import platform
import random
import subprocess
import sys
import time

REPO_ROOT = os.path.normpath(os.path.join(os.path.dirname(os.path.abspath(__file__)), ".."))

# Table 1 of the paper: N (thousands) -> (packing density E, size ratio H).
TABLE1 = {
    10: (0.43, 2.5), 100: (0.43, 3.3), 200: (0.31, 2.5), 300: (0.38, 3.3), 400: (0.33, 2.0),
    500: (0.41, 2.0), 600: (0.40, 2.5), 700: (0.38, 3.3), 800: (0.34, 2.0), 900: (0.38, 2.0),
    1000: (0.36, 1.4),
}
UPDATE_FACTORS = (1e-5, 1e-4, 1e-3, 1e-2, 1e-1)
# Table 2: H = 10 and Λ = 1e-5 fixed, the cube side x varied.
TABLE2_SIDES = (100, 120, 140, 160, 180, 200)
TABLE2_BOXES = (400_000, 600_000, 800_000)
# Table 3: x = 200 and Λ = 1e-5 fixed, the size ratio H varied (b = 1, a = 1 / H).
TABLE3_RATIOS = (1.111, 1.25, 1.429, 1.667, 2.0, 2.5, 3.333, 5.0, 10.0)
TABLE3_BOXES = (500_000, 700_000, 900_000)
TABLE3_SIDE = 200

MODES = {
    # scale: factor on every N; steps: timed steps after the build step.
    "full": dict(scale=1.0, steps=5, table1=tuple(TABLE1), update_factors=UPDATE_FACTORS,
                 sides=TABLE2_SIDES, ratios=TABLE3_RATIOS, timeout=900),
    "quick": dict(scale=0.1, steps=5, table1=(10, 200, 400, 600, 800, 1000),
                  update_factors=UPDATE_FACTORS, sides=(100, 140, 200),
                  ratios=(1.111, 1.667, 2.5, 5.0, 10.0), timeout=300),
    "smoke": dict(scale=0.002, steps=2, table1=(10, 500, 1000), update_factors=(1e-5, 1e-1),
                  sides=(100, 200), ratios=(1.111, 10.0), timeout=60),
}

FIELDS = [
    "experiment", "case", "dim", "boxes", "boxes_final", "boxes_median", "packing_density", "cube_side",
    "paper_cube_side", "size_ratio", "update_factor", "seed", "steps_timed", "build_s",
    "step_median_s", "step_min_s", "step_max_s", "step_cpu_median_s", "list_update_s", "sort_s",
    "cut_regroup_s", "check_s", "world_update_s", "pairs_median", "bytes_held", "bytes_per_box",
    "peak_rss_bytes", "peak_rss_per_box", "oversized_boxes", "reference_check", "wall_s", "load_1min",
]


def scaled_boxes(boxes, scale):
    return max(2, round(boxes * scale))


def scaled_side(side, scale):
    return side * scale ** (1.0 / 3.0)


def plan(mode, update_factors=None):
    """Every configuration of the mode: (experiment, case label, smb run arguments, extra CSV fields)."""
    settings = MODES[mode]
    scale = settings["scale"]
    runs = []
    for update_factor in update_factors or settings["update_factors"]:
        for thousands in settings["table1"]:
            density, ratio = TABLE1[thousands]
            boxes = scaled_boxes(thousands * 1000, scale)
            runs.append(("4.1", f"L={update_factor:g}",
                         ["-n", str(boxes), "--density", repr(density), "--size-ratio", repr(ratio),
                          "--update-factor", repr(update_factor)], {"paper_cube_side": ""}))
    for boxes in TABLE2_BOXES:
        for side in settings["sides"]:
            runs.append(("4.2", f"N={boxes}",
                         ["-n", str(scaled_boxes(boxes, scale)), "--side", repr(scaled_side(side, scale)),
                          "--size-ratio", "10", "--update-factor", "1e-05"], {"paper_cube_side": side}))
    for boxes in TABLE3_BOXES:
        for ratio in settings["ratios"]:
            runs.append(("4.3", f"N={boxes}",
                         ["-n", str(scaled_boxes(boxes, scale)),
                          "--side", repr(scaled_side(TABLE3_SIDE, scale)), "--size-ratio", repr(ratio),
                          "--update-factor", "1e-05"], {"paper_cube_side": TABLE3_SIDE}))
    return runs


def load_average():
    try:
        return os.getloadavg()[0]
    except OSError:
        return float("nan")


def run_one(smb, arguments, steps, seed, check, timeout):
    command = [smb, "run", "--json", "--no-progress", "--steps", str(steps + 1), "--seed", str(seed)]
    command += arguments
    if not check:
        command.append("--no-check")
    started = time.monotonic()
    load = load_average()
    done = subprocess.run(command, capture_output=True, text=True, timeout=timeout)
    wall = time.monotonic() - started
    if done.returncode not in (0, 2):  # 2: a checked step differs from the reference
        raise RuntimeError(f"{' '.join(command)} exited {done.returncode}: {done.stderr.strip()[-400:]}")
    return command, json.loads(done.stdout), wall, load


def csv_row(experiment, case, extra, summary, wall, load):
    detect = summary["detect_seconds"]
    phases = summary["phase_seconds_median"]
    boxes = summary["boxes"]
    peak = summary.get("peak_rss_bytes")
    check = summary["check"]
    return {
        "experiment": experiment, "case": case, "dim": summary["dimension"],
        "boxes": boxes["initial"], "boxes_final": boxes["final"], "boxes_median": boxes["median"],
        "packing_density": summary["packing_density"], "cube_side": summary["cube_side"],
        "paper_cube_side": extra["paper_cube_side"], "size_ratio": summary["size_ratio"],
        "update_factor": summary["update_factor"], "seed": summary["seed"],
        "steps_timed": summary["steps"] - 1, "build_s": summary["build_seconds"],
        "step_median_s": detect["median"], "step_min_s": detect["min"], "step_max_s": detect["max"],
        "step_cpu_median_s": (summary.get("detect_cpu_seconds") or {}).get("median", ""),
        # sort_s: the paper's list sorts, or the persistent cuts' quantile selection (the other is 0).
        "list_update_s": phases["update"], "sort_s": phases["list_sort"] + phases["quantile"],
        "cut_regroup_s": phases["cut_regroup"], "check_s": phases["check"],
        "world_update_s": summary["world_update_seconds_median"],
        "pairs_median": summary["pairs"]["median"], "bytes_held": summary["bytes_held"],
        "bytes_per_box": summary["bytes_per_box"],
        "peak_rss_bytes": "" if peak is None else peak,
        "peak_rss_per_box": "" if peak is None else peak / boxes["final"],
        "oversized_boxes": summary["oversized_boxes_last"],
        "reference_check": ("ok" if check["ok"] else "MISMATCH") if check["enabled"] else "skipped",
        "wall_s": round(wall, 3), "load_1min": round(load, 2),
    }


def write_csv(path, rows):
    def printable(value):
        return f"{value:.6g}" if isinstance(value, float) else value

    temporary = path + ".tmp"
    with open(temporary, "w", newline="") as out:
        writer = csv.DictWriter(out, fieldnames=FIELDS)
        writer.writeheader()
        writer.writerows({key: printable(value) for key, value in row.items()} for row in rows)
    os.replace(temporary, path)


def machine_description():
    model = ""
    try:
        with open("/proc/cpuinfo") as cpuinfo:
            model = next((line.split(":", 1)[1].strip() for line in cpuinfo if line.startswith("model name")), "")
    except OSError:
        pass
    return {"cpu": model or platform.processor(), "logical_cpus": os.cpu_count(), "system": platform.platform()}


def git_commit():
    try:
        return subprocess.run(["git", "-C", REPO_ROOT, "rev-parse", "--short", "HEAD"], capture_output=True,
                              text=True, check=True).stdout.strip()
    except (OSError, subprocess.CalledProcessError):
        return ""


def main():
    parser = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    parser.add_argument("--mode", choices=sorted(MODES), default="quick")
    parser.add_argument("--smb", default=os.path.join(REPO_ROOT, "build", "tools", "smb", "smb"),
                        help="the smb executable (default: build/tools/smb/smb)")
    parser.add_argument("--out", default=os.path.join(REPO_ROOT, "bench", "results", "cpp-2core", "reproduction"),
                        help="folder of the result files")
    parser.add_argument("--steps", type=int, default=0, help="timed steps after the build step (default: the mode's)")
    parser.add_argument("--experiments", default="4.1,4.2,4.3", help="comma-separated subset")
    parser.add_argument("--seed", type=int, default=1)
    parser.add_argument("--dim", type=int, choices=(2, 3), default=3,
                        help="dimension of the boxes (2: experiment 4.1 only)")
    parser.add_argument("--update-factors", default="",
                        help="comma-separated subset of experiment 4.1's update factors (default: the mode's)")
    parser.add_argument("--check", action="store_true",
                        help="check each run's last step against the grid reference (its grid then counts in "
                             "the peak memory)")
    parser.add_argument("--pipeline", choices=("paper", "persistent"), default="paper",
                        help="smb run --pipeline: the paper's lists (default: this is a reproduction of the "
                             "paper's algorithm) or the default persistent-cut pipeline")
    parser.add_argument("--listed-order", action="store_true",
                        help="run in table order; by default the order is shuffled (seeded) so that a change "
                             "of machine load during the run does not turn into a trend along N, x or H")
    args = parser.parse_args()

    if not os.access(args.smb, os.X_OK):
        sys.exit(f"reproduce.py: no smb executable at {args.smb} (build target smb_cli, or pass --smb)")
    settings = MODES[args.mode]
    steps = args.steps or settings["steps"]
    wanted = set(args.experiments.split(","))
    if args.dim == 2 and wanted - {"4.1"}:
        sys.exit("reproduce.py: --dim 2 runs experiment 4.1 only (4.2 and 4.3 set the paper's 3D cube sides)")
    try:
        update_factors = [float(text) for text in args.update_factors.split(",")] if args.update_factors else None
    except ValueError:
        sys.exit(f"reproduce.py: --update-factors {args.update_factors!r} is not a list of numbers")
    runs = [run for run in plan(args.mode, update_factors) if run[0] in wanted]
    if not runs:
        sys.exit(f"reproduce.py: no experiment among {args.experiments}")
    order = list(range(len(runs)))
    if not args.listed_order:
        random.Random(args.seed).shuffle(order)

    os.makedirs(args.out, exist_ok=True)
    rows = {experiment: [None] * len(runs) for experiment in wanted}
    meta = {
        "mode": args.mode, "scale": settings["scale"], "steps_timed": steps, "seed": args.seed, "dim": args.dim,
        "pipeline": args.pipeline,
        "reference_check": args.check, "order": "listed" if args.listed_order else "shuffled",
        "commit": git_commit(), "machine": machine_description(), "load_1min_start": load_average(),
        "started": time.strftime("%Y-%m-%d %H:%M:%S %z"), "runs": len(runs),
        "example_command": "",
    }
    started = time.monotonic()
    mismatches = 0
    for done_count, index in enumerate(order, start=1):
        experiment, case, arguments, extra = runs[index]
        command, summary, wall, load = run_one(args.smb, arguments + ["--pipeline", args.pipeline,
                                                                 "--dim", str(args.dim)], steps,
                                               args.seed, args.check,
                                               settings["timeout"])
        row = csv_row(experiment, case, extra, summary, wall, load)
        mismatches += row["reference_check"] == "MISMATCH"
        rows[experiment][index] = row
        meta["example_command"] = meta["example_command"] or " ".join(os.path.relpath(part, REPO_ROOT)
                                                                      if part == args.smb else part
                                                                      for part in command)
        for name, table in rows.items():
            write_csv(os.path.join(args.out, f"{args.mode}-{name}.csv"), [r for r in table if r is not None])
        elapsed = time.monotonic() - started
        print(f"[{done_count}/{len(runs)} {elapsed:6.0f} s] {experiment} {case} N {row['boxes']} "
              f"E {row['packing_density']:.3g} H {row['size_ratio']:g}: step {row['step_median_s']:.4f} s, "
              f"build {row['build_s']:.3f} s, {row['bytes_per_box']:.0f} B/box, load {load:.1f}", file=sys.stderr)

    meta["seconds"] = round(time.monotonic() - started, 1)
    meta["load_1min_end"] = load_average()
    meta["finished"] = time.strftime("%Y-%m-%d %H:%M:%S %z")
    with open(os.path.join(args.out, f"{args.mode}-meta.json"), "w") as out:
        json.dump(meta, out, indent=2)
        out.write("\n")
    print(f"reproduce.py: {len(runs)} runs in {meta['seconds']:.0f} s; results in {args.out}", file=sys.stderr)
    if mismatches:
        sys.exit(f"reproduce.py: {mismatches} run(s) differ from the grid reference")


if __name__ == "__main__":
    main()
