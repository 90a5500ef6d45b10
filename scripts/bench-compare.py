#!/usr/bin/python3
# SPDX-License-Identifier: MIT
"""Runs the side-by-side comparison: every method on every scene, one process each.

Each run is `smb_compare --method M --scene ...` (bench/smb_compare.cpp), which prints one JSON
line. This script decides what to run, skips what would take too long (printing why), checks
that all methods report the same pair sets, and writes
    bench/results/<machine>/<mode>.csv      one row per method and scene, ratios to smb
    bench/results/<machine>/<mode>.jsonl    the raw lines, per-step pair digests included
Usage: scripts/bench-compare.py --build-dir build --mode quick [--machine cpp-2core]
"""

import argparse
import csv
import json
import os
import subprocess
import sys
import time

# (family, dims, box counts, update factors, steps after step 0)
SUITES = {
    "quick": [
        ("paper", (3, 2), (10_000, 30_000), (1e-5, 1e-3, 1e-1), 5),
        ("sparse", (3,), (40_000,), (1e-5,), 5),
        ("clustered", (3, 2), (10_000, 30_000), (1e-3,), 5),
        ("mixed", (3, 2), (10_000, 30_000), (1e-3,), 5),
    ],
    "full": [
        ("paper", (3, 2), (10_000, 100_000, 1_000_000), (1e-5, 1e-3, 1e-1), 5),
        ("sparse", (3,), (400_000, 800_000), (1e-5,), 5),
        ("clustered", (3, 2), (100_000, 1_000_000), (1e-3,), 5),
        ("mixed", (3, 2), (100_000, 1_000_000), (1e-3,), 5),
    ],
}

# Growth exponents (first step, later steps) used to predict a run at a larger N from the
# same method's run at a smaller one. Brute force is quadratic; box pruning sweeps about
# N^(1/3) (3D) or N^(1/2) (2D) x-neighbours per box at fixed density; Bullet's sweep inserts
# each proxy in O(N) and moves inserted/removed ones in O(N); the rest are near linear.
GROWTH = {
    "brute_force": (2.0, 2.0),
    "box_pruning": (1.6, 1.6),
    "bullet_axis_sweep": (2.0, 1.6),
}
DEFAULT_GROWTH = (1.15, 1.15)

LIMITS = {  # (predicted seconds above which a run is skipped, hard timeout per process)
    "quick": (20.0, 60.0),
    "full": (150.0, 400.0),
}


def list_methods(binary):
    out = subprocess.run([binary, "--list"], check=True, capture_output=True, text=True).stdout
    methods = []
    for line in out.split():
        name, dims = line.split(",")
        methods.append((name, "2d" in dims, "3d" in dims))
    return methods


def run_one(binary, method, family, dim, boxes, update_factor, steps, seed, timeout):
    command = [binary, "--method", method, "--scene", family, "--dim", str(dim), "--boxes", str(boxes),
               "--lambda", repr(update_factor), "--steps", str(steps), "--seed", str(seed)]
    started = time.monotonic()
    try:
        done = subprocess.run(command, capture_output=True, text=True, timeout=timeout)
    except subprocess.TimeoutExpired:
        return None, f"timed out after {timeout:.0f} s"
    if done.returncode != 0:
        return None, f"exit {done.returncode}: {done.stderr.strip()[-200:]}"
    result = json.loads(done.stdout.strip().splitlines()[-1])
    result["wall_s"] = time.monotonic() - started
    return result, ""


def predicted_seconds(method, previous, boxes, steps):
    grow_first, grow_step = GROWTH.get(method, DEFAULT_GROWTH)
    scale = boxes / previous["boxes"]
    return previous["first_step_s"] * scale ** grow_first + steps * previous["median_step_s"] * scale ** grow_step


def check_agreement(results):
    """Marks each result with what its per-step digests agree with. The reference is brute
    force where it ran; otherwise the digest that most methods report at each step."""
    ok = [r for r in results if r.get("digests")]
    if not ok:
        return []
    steps = len(ok[0]["digests"])
    brute = next((r for r in ok if r["method"] == "brute_force"), None)
    reference, reference_name = [], "brute_force" if brute else "majority"
    for s in range(steps):
        if brute:
            reference.append(brute["digests"][s])
            continue
        counts = {}
        for r in ok:
            counts[r["digests"][s]] = counts.get(r["digests"][s], 0) + 1
        reference.append(max(counts, key=counts.get))
    problems = []
    for r in ok:
        bad = [s for s in range(steps) if r["digests"][s] != reference[s]]
        r["agrees"] = reference_name if not bad else f"NO (steps {bad})"
        if bad:
            problems.append(f"{r['method']} disagrees with {reference_name} at steps {bad}")
    return problems


FIELDS = ["machine", "mode", "family", "dim", "lambda", "boxes", "max_boxes", "steps", "method", "status", "note",
          "first_step_s", "median_step_s", "early_median_s", "steady_median_s", "min_step_s", "peak_rss_mib", "bytes_per_box", "held_bytes_per_box",
          "pairs_step0", "pairs_last", "digest_last", "agrees", "first_ratio_to_smb", "step_ratio_to_smb",
          "early_ratio_to_smb", "steady_ratio_to_smb", "memory_ratio_to_smb"]


def write_results(out_dir, name, rows, raw_lines):
    """Rewritten after every scene, so an interrupted run keeps what it measured."""
    csv_path = os.path.join(out_dir, f"{name}.csv")
    with open(csv_path, "w", newline="") as handle:
        writer = csv.DictWriter(handle, fieldnames=FIELDS)
        writer.writeheader()
        for row in rows:
            writer.writerow({k: (f"{v:.6g}" if isinstance(v, float) else v) for k, v in row.items()})
    with open(os.path.join(out_dir, f"{name}.jsonl"), "w") as handle:
        handle.write("\n".join(raw_lines) + "\n")
    return csv_path


def main():
    parser = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    parser.add_argument("--build-dir", default="build")
    parser.add_argument("--mode", choices=sorted(SUITES), default="quick")
    parser.add_argument("--machine", default="cpp-2core")
    parser.add_argument("--methods", default="", help="comma-separated subset (default: all in the build)")
    parser.add_argument("--families", default="", help="comma-separated subset of scene families")
    parser.add_argument("--seed", type=int, default=1)
    parser.add_argument("--steps", type=int, default=0,
                        help="steps after the build in every scene (default: the suite's); above 10 the steady "
                             "state (steps after the first ten) gets columns of its own")
    parser.add_argument("--output", default="", help="base name of the result files (default: the mode)")
    parser.add_argument("--predict-from", default="",
                        help="a .jsonl of earlier runs to predict first sizes from (e.g. a previous part)")
    parser.add_argument("--limit", type=float, default=0,
                        help="skip a run predicted to take longer, in seconds (default: the mode's)")
    parser.add_argument("--results-dir", default=os.path.join(os.path.dirname(__file__), "..", "bench", "results"))
    args = parser.parse_args()

    binary = os.path.join(args.build_dir, "bench", "smb_compare")
    methods = list_methods(binary)
    if args.methods:
        wanted = set(args.methods.split(","))
        methods = [m for m in methods if m[0] in wanted or m[0] == "smb"]
    families = set(args.families.split(",")) if args.families else None
    skip_above, timeout = LIMITS[args.mode]
    if args.limit > 0:
        skip_above = args.limit
    out_dir = os.path.join(args.results_dir, args.machine)
    os.makedirs(out_dir, exist_ok=True)

    rows, raw_lines, all_problems = [], [], []
    # The largest run of each (method, dim) so far in any scene: predicts the first size of a
    # scene family, where the family itself has no smaller run yet.
    largest_run = {}
    if args.predict_from:
        with open(args.predict_from) as handle:
            for line in handle:
                if line.strip():
                    earlier = json.loads(line)
                    key = (earlier["method"], earlier["dim"])
                    if key not in largest_run or largest_run[key]["boxes"] <= earlier["boxes"]:
                        largest_run[key] = earlier
    for family, dims, counts, update_factors, steps in SUITES[args.mode]:
        steps = args.steps or steps
        if families and family not in families:
            continue
        for dim in dims:
            for update_factor in update_factors:
                previous = {}   # method -> result at the largest N run so far
                gave_up = {}    # method -> reason it will not run at larger N
                for boxes in counts:
                    label = f"{family}{dim}d N={boxes} L={update_factor:g}"
                    baseline, why = run_one(binary, "none", family, dim, boxes, update_factor, steps, args.seed, timeout)
                    if baseline is None:
                        print(f"[{label}] scene failed: {why}", file=sys.stderr)
                        continue
                    results, skipped = [], []
                    for name, runs_2d, runs_3d in methods:
                        if not (runs_2d if dim == 2 else runs_3d):
                            continue
                        if name in gave_up:
                            skipped.append((name, gave_up[name]))
                            continue
                        basis = previous.get(name) or largest_run.get((name, dim))
                        if basis is not None and basis["boxes"] < boxes:
                            guess = predicted_seconds(name, basis, boxes, steps)
                            if guess > skip_above:
                                where = "" if name in previous else f" of {basis['family']}"
                                reason = (f"predicted {guess:.0f} s from {basis['boxes']} boxes{where} "
                                          f"(limit {skip_above:.0f} s)")
                                gave_up[name] = reason
                                skipped.append((name, reason))
                                continue
                        result, why = run_one(binary, name, family, dim, boxes, update_factor, steps, args.seed, timeout)
                        if result is None:
                            gave_up[name] = why
                            skipped.append((name, why))
                            continue
                        previous[name] = result
                        if (name, dim) not in largest_run or largest_run[(name, dim)]["boxes"] <= boxes:
                            largest_run[(name, dim)] = result
                        results.append(result)
                    problems = check_agreement(results)
                    all_problems += [f"[{label}] {p}" for p in problems]
                    smb = next((r for r in results if r["method"] == "smb"), None)
                    # The method's own memory: the peak of the heap it allocated inside its
                    # build() and step() calls (smb_compare's heap meter). Where the meter is
                    # off (sanitizer builds), resident growth less the scene's own and the pair list.
                    harness_growth = baseline["resident_peak_bytes"] - baseline["resident_before_bytes"]
                    for r in results:
                        if r["heap_meter"]:
                            own_bytes, held_bytes = r["heap_peak_bytes"], r["heap_live_bytes"]
                        else:
                            own_bytes = (r["resident_peak_bytes"] - r["resident_before_bytes"] - harness_growth
                                         - r["pair_list_bytes"])
                            held_bytes = own_bytes
                        r["bytes_per_box"] = max(0, own_bytes) / max(1, r["max_boxes"])
                        r["held_bytes_per_box"] = max(0, held_bytes) / max(1, r["max_boxes"])
                    for r in results:
                        ratio = lambda key: (r[key] / smb[key]) if smb and smb[key] > 0 else ""
                        rows.append({
                            "machine": args.machine, "mode": args.mode, "family": family, "dim": dim,
                            "lambda": update_factor, "boxes": boxes, "max_boxes": r["max_boxes"], "steps": steps,
                            "method": r["method"], "status": "ok", "note": "",
                            "first_step_s": r["first_step_s"], "median_step_s": r["median_step_s"],
                            "early_median_s": r.get("early_median_s", ""),
                            "steady_median_s": r.get("steady_median_s") or "",
                            "min_step_s": r["min_step_s"], "peak_rss_mib": r["peak_rss_bytes"] / 2**20,
                            "bytes_per_box": r["bytes_per_box"],
                            "held_bytes_per_box": r["held_bytes_per_box"], "pairs_step0": r["pairs"][0],
                            "pairs_last": r["pairs"][-1], "digest_last": r["digests"][-1],
                            "agrees": r.get("agrees", ""),
                            "first_ratio_to_smb": ratio("first_step_s"), "step_ratio_to_smb": ratio("median_step_s"),
                            "early_ratio_to_smb": ratio("early_median_s"),
                            "steady_ratio_to_smb": ratio("steady_median_s") if r.get("steady_median_s") else "",
                            "memory_ratio_to_smb": ratio("bytes_per_box"),
                        })
                        raw_lines.append(json.dumps(dict(r, baseline_peak_rss_bytes=baseline["peak_rss_bytes"])))
                    for name, reason in skipped:
                        rows.append({"machine": args.machine, "mode": args.mode, "family": family, "dim": dim,
                                     "lambda": update_factor, "boxes": boxes, "steps": steps, "method": name,
                                     "status": "skipped", "note": reason})
                    print(f"[{label}] " + ", ".join(
                        f"{r['method']} {r['median_step_s'] * 1e3:.2f} ms" for r in results) +
                        "".join(f"; SKIPPED {n}: {why}" for n, why in skipped), flush=True)
                    for p in problems:
                        print(f"[{label}] MISMATCH: {p}", flush=True)
                    csv_path = write_results(out_dir, args.output or args.mode, rows, raw_lines)

    csv_path = write_results(out_dir, args.output or args.mode, rows, raw_lines)
    print(f"wrote {csv_path}")
    if all_problems:
        print("PAIR SETS DISAGREE:\n  " + "\n  ".join(all_problems), file=sys.stderr)
        return 1
    print("all methods agree on every step of every scene")
    return 0


if __name__ == "__main__":
    sys.exit(main())
