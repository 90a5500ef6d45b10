#!/usr/bin/python3
# SPDX-License-Identifier: MIT
"""The headline comparison: smb against the best uniform grid, the grid's Verlet-skin and
two-thread forms and the established broad phases, on the paper's workload and on the other scene
families, one process per method and scene (smb_compare), in one command.

Scenes and methods (40 steps after the build, one thread unless named):
    3D paper, 1M boxes, Λ = 1e-3: grid (1 and 2 threads), World (float, double), Detector, World and
                                  Detector on 2 threads
    3D paper, 1M boxes, Λ = 0.1:  grid, World (float, double), Detector
    3D paper, 1M boxes, Λ = 1e-5: grid, Verlet-skin grid, Detector with skin 0.1, Bullet's DBVT
    2D paper, 100k boxes, Λ = 1e-3: grid, World, Detector
    2D paper, 100k boxes, Λ = 1e-5: grid, Verlet-skin grid, Box2D's dynamic tree, World, Detector
                                    with skin 0.1
    3D, 300k boxes, Λ = 1e-3: mixed, clustered, sparse, loguniform2, loguniform3, islands, plane,
                              rods: grid, World, Detector
    2D, 100k boxes, Λ = 1e-3: mixed, clustered, loguniform2, islands, rods: grid, World, Detector
Every step's pair set must agree between the methods of a scene (per-step digests).

Writes bench/results/<machine>/<name>.csv, .jsonl (smb_compare's lines) and .md: for each
method the build step, the median of the ten steps after it, the median of the later (steady)
steps, and each as a ratio grid ÷ method (above 1: faster than the grid).
Usage: scripts/bench-headline.py --build-dir build-bench [--name headline] [--steps 40]
       [--boxes-3d 1000000] [--boxes-2d 100000] [--boxes-family 300000] [--rounds 1]
       [--only METHOD,...] [--extra METHOD,...] [--families paper,mixed,...] [--dims 2,3]
       [--update-factors 1e-3,...]
"""

import argparse
import csv
import datetime
import json
import os
import statistics
import subprocess
import sys
import time

# (family, dim, Λ, size, methods); the first method of each scene is the one the ratios divide.
# size: "paper" scenes take --boxes-3d or --boxes-2d, "family" ones --boxes-family in 3D and
# --boxes-2d in 2D.
ONE_THREAD = ["uniform_grid", "smb", "smb_detector"]
SCENES = [
    ("paper", 3, 1e-3, "paper", ["uniform_grid", "uniform_grid_2threads", "smb", "smb_double", "smb_detector",
                                 "smb_2threads", "smb_detector_2threads", "uniform_grid_sorted",
                                 "smb_detector_sorted"]),
    ("paper", 3, 1e-1, "paper", ["uniform_grid", "smb", "smb_double", "smb_detector"]),
    ("paper", 3, 1e-5, "paper", ["uniform_grid", "verlet_grid", "smb_detector_skin", "bullet_dbvt"]),
    ("paper", 2, 1e-3, "paper", ONE_THREAD),
    ("paper", 2, 1e-5, "paper", ["uniform_grid", "verlet_grid", "box2d_dynamic_tree", "smb", "smb_detector_skin"]),
] + [(family, 3, 1e-3, "family", ONE_THREAD)
     for family in ["mixed", "clustered", "sparse", "loguniform2", "loguniform3", "islands", "plane", "rods"]] + [
    (family, 2, 1e-3, "family", ONE_THREAD) for family in ["mixed", "clustered", "loguniform2", "islands", "rods"]]
REFERENCE = "uniform_grid"
LABEL = {"uniform_grid": "uniform grid", "uniform_grid_2threads": "uniform grid, 2 threads",
         "verlet_grid": "Verlet-skin grid", "smb": "smb World float", "smb_double": "smb World double",
         "smb_detector": "smb Detector", "smb_2threads": "smb World, 2 threads",
         "smb_detector_2threads": "smb Detector, 2 threads", "smb_detector_skin": "smb Detector, skin 0.1",
         "bullet_dbvt": "Bullet btDbvtBroadphase", "box2d_dynamic_tree": "Box2D b2DynamicTree",
         "uniform_grid_every_cell": "textbook grid (every cell)",
         "uniform_grid_sorted": "uniform grid, array sorted in its order",
         "smb_detector_sorted": "smb Detector, array sorted in its order"}
TIMES = ["first_step_s", "early_median_s", "steady_median_s", "median_step_s", "first_step_cpu_s", "early_median_cpu_s",
         "steady_median_cpu_s", "wall_s"]
FIELDS = ["family", "dim", "lambda", "boxes", "steps", "method", "first_step_ms", "early_median_ms", "steady_median_ms",
          "median_step_ms", "first_step_cpu_ms", "early_median_cpu_ms", "steady_median_cpu_ms", "grid_over_first", "grid_over_early", "grid_over_steady", "pairs_last", "agrees",
          "bytes_per_box", "wall_s"]


def run_one(binary, method, family, dim, boxes, update_factor, steps, early_steps):
    command = [binary, "--method", method, "--scene", family, "--dim", str(dim), "--boxes", str(boxes),
               "--lambda", repr(update_factor), "--steps", str(steps), "--early-steps", str(early_steps),
               "--no-check"]
    started = time.monotonic()
    done = subprocess.run(command, capture_output=True, text=True)
    if done.returncode != 0:
        return None, f"exit {done.returncode}: {done.stderr.strip()[-300:]}"
    result = json.loads(done.stdout.strip().splitlines()[-1])
    result["wall_s"] = time.monotonic() - started
    return result, ""


def merge_rounds(results):
    """One result whose times are the medians over the rounds; digests and pairs of the first
    round (every round's digests must agree: the scene is the same)."""
    merged = dict(results[0])
    for key in TIMES:
        merged[key] = statistics.median(r[key] for r in results)
    merged["digests_differ"] = any(r["digests"] != results[0]["digests"] for r in results)
    return merged


def load_average():
    with open("/proc/loadavg") as handle:
        return " ".join(handle.read().split()[:3])


def describe_checkout(root):
    try:
        return subprocess.run(["git", "-C", root, "describe", "--always", "--dirty"], capture_output=True,
                              text=True, check=True).stdout.strip()
    except (OSError, subprocess.CalledProcessError):
        return "unknown"


def ratio(reference, value):
    return reference / value if reference and value else ""


def markdown(rows, header_lines, early_steps=10):
    early = f"steps 1–{early_steps}"
    out = header_lines + [""]
    scenes = []
    for row in rows:
        key = (row["family"], row["dim"], row["lambda"], row["boxes"])
        if key not in scenes:
            scenes.append(key)
    for family, dim, update_factor, boxes in scenes:
        title = "paper workload" if family == "paper" else f"`{family}`"
        out += [f"### {dim}D {title}, N = {boxes:,}, Λ = {update_factor:g}", "",
                f"| method | build ms | {early} ms | steady ms | grid ÷ method: build | {early} | steady "
                "| steady CPU ms | pairs | agrees |",
                "|---|---:|---:|---:|---:|---:|---:|---:|---:|---|"]
        for row in rows:
            if (row["family"], row["dim"], row["lambda"], row["boxes"]) != (family, dim, update_factor, boxes):
                continue
            if row.get("status") == "failed":
                out.append(f"| {LABEL.get(row['method'], row['method'])} | failed: {row['agrees']} ||||||||")
                continue
            cells = [f"{row[k]:.1f}" if row[k] != "" else "–" for k in
                     ("first_step_ms", "early_median_ms", "steady_median_ms")]
            cells += [f"{row[k]:.2f}×" if row[k] != "" else "–" for k in
                      ("grid_over_first", "grid_over_early", "grid_over_steady")]
            cpu = f"{row['steady_median_cpu_ms']:.1f}" if row["steady_median_ms"] != "" else "–"
            out.append(f"| {LABEL.get(row['method'], row['method'])} | " + " | ".join(cells) +
                       f" | {cpu} | {row['pairs_last']:,} | {row['agrees']} |")
        out.append("")
    return "\n".join(out) + "\n"


def main():
    parser = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    parser.add_argument("--build-dir", default="build-bench")
    parser.add_argument("--machine", default="cpp-2core")
    parser.add_argument("--name", default="headline", help="base name of the result files")
    parser.add_argument("--steps", type=int, default=40, help="steps after the build")
    parser.add_argument("--early-steps", type=int, default=10, help="steps after the build counted as early")
    parser.add_argument("--boxes-3d", type=int, default=1_000_000)
    parser.add_argument("--boxes-2d", type=int, default=100_000)
    parser.add_argument("--boxes-family", type=int, default=300_000, help="boxes of the 3D scenes other than paper")
    parser.add_argument("--families", default="", help="comma-separated scene families to run (default: all)")
    parser.add_argument("--dims", default="", help="comma-separated dimensions to run, 2 and/or 3 (default: both)")
    parser.add_argument("--update-factors", default="",
                        help="comma-separated update factors Λ to run, as in the scene list (default: all)")
    parser.add_argument("--rounds", type=int, default=1,
                        help="runs of every method, alternating; the tables show the median (default 1)")
    parser.add_argument("--only", default="", help="comma-separated methods to run (the grid always runs)")
    parser.add_argument("--extra", default="", help="comma-separated methods added to every scene")
    parser.add_argument("--results-dir", default=os.path.join(os.path.dirname(__file__), "..", "bench", "results"))
    args = parser.parse_args()

    root = os.path.abspath(os.path.join(os.path.dirname(__file__), ".."))
    binary = os.path.join(args.build_dir, "bench", "smb_compare")
    listed = subprocess.run([binary, "--list"], check=True, capture_output=True, text=True).stdout.split()
    available = {line.split(",")[0]: line.split(",")[1] for line in listed}
    only = set(args.only.split(",")) | {REFERENCE} if args.only else None
    extra = [m for m in args.extra.split(",") if m]
    out_dir = os.path.join(args.results_dir, args.machine)
    os.makedirs(out_dir, exist_ok=True)

    started, load_before = time.monotonic(), load_average()
    rows, raw_lines, problems = [], [], []
    families = set(args.families.split(",")) if args.families else None
    dims = {int(d) for d in args.dims.split(",")} if args.dims else None
    update_factors = [float(f) for f in args.update_factors.split(",")] if args.update_factors else None
    for family, dim, update_factor, size, methods in SCENES:
        if families is not None and family not in families:
            continue
        if dims is not None and dim not in dims:
            continue
        if update_factors is not None and not any(abs(update_factor - f) <= 1e-9 * f for f in update_factors):
            continue
        if dim == 2:
            boxes = args.boxes_2d
        else:
            boxes = args.boxes_3d if size == "paper" else args.boxes_family
        where = f"{family} {dim}D Λ={update_factor:g}"
        chosen = []
        for method in methods + [m for m in extra if m not in methods]:
            if only is not None and method not in only and method not in extra:
                continue
            if f"{dim}d" not in available.get(method, ""):
                print(f"[{where}] {method} is not in this build, left out", flush=True)
                continue
            chosen.append(method)
        runs, failed = {m: [] for m in chosen}, set()
        # Rounds alternate the methods, so that a busy spell of the machine falls on several.
        for _ in range(args.rounds):
            for method in chosen:
                if method in failed:
                    continue
                result, why = run_one(binary, method, family, dim, boxes, update_factor, args.steps, args.early_steps)
                if result is None:
                    failed.add(method)
                    problems.append(f"{where} {method}: {why}")
                    rows.append({"family": family, "dim": dim, "lambda": update_factor, "boxes": boxes, "steps": args.steps,
                                 "method": method, "status": "failed", "agrees": why})
                    continue
                print(f"[{where} N={boxes}] {method}: build "
                      f"{result['first_step_s'] * 1e3:.1f} ms, steps 1-{result['early_steps']} "
                      f"{result['early_median_s'] * 1e3:.1f} ms, steady {result['steady_median_s'] * 1e3:.1f} ms "
                      f"({result['wall_s']:.0f} s)", flush=True)
                runs[method].append(result)
                raw_lines.append(json.dumps(result))
        results = [merge_rounds(runs[m]) for m in chosen if m not in failed]
        reference = next((r for r in results if r["method"] == REFERENCE), results[0] if results else None)
        for r in results:
            bad = [s for s, (a, b) in enumerate(zip(r["digests"], reference["digests"])) if a != b]
            if r["digests_differ"]:
                problems.append(f"{where}: {r['method']} reported different pairs in two rounds")
            if bad:
                problems.append(f"{where}: {r['method']} differs from {reference['method']} "
                                f"at steps {bad}")
            ms = {k: r[k] * 1e3 for k in ("first_step_s", "early_median_s", "steady_median_s", "median_step_s")}
            base = {k: reference[k] * 1e3 for k in ms}
            steady = ms["steady_median_s"] if r["steady_median_s"] > 0 else ""
            rows.append({
                "family": family, "dim": dim, "lambda": update_factor, "boxes": boxes, "steps": args.steps, "method": r["method"],
                "first_step_ms": ms["first_step_s"], "early_median_ms": ms["early_median_s"],
                "steady_median_ms": steady, "median_step_ms": ms["median_step_s"],
                "grid_over_first": ratio(base["first_step_s"], ms["first_step_s"]),
                "grid_over_early": ratio(base["early_median_s"], ms["early_median_s"]),
                "grid_over_steady": ratio(base["steady_median_s"], steady) if steady != "" else "",
                "first_step_cpu_ms": r["first_step_cpu_s"] * 1e3, "early_median_cpu_ms": r["early_median_cpu_s"] * 1e3,
                "steady_median_cpu_ms": r["steady_median_cpu_s"] * 1e3,
                "pairs_last": r["pairs"][-1], "agrees": "yes" if not bad else f"NO (steps {bad})",
                "bytes_per_box": r["heap_peak_bytes"] / max(1, r["max_boxes"]), "wall_s": r["wall_s"],
            })

    elapsed = time.monotonic() - started
    header = [f"## Headline comparison ({args.name})", "",
              f"smb_compare at {describe_checkout(root)}, {datetime.datetime.utcnow():%Y-%m-%d %H:%M} UTC, "
              f"{os.cpu_count()} cores; load average {load_before} before, {load_average()} after; "
              f"{elapsed / 60:.1f} minutes in all; {args.rounds} round(s), medians over them.",
              f"Paper workload (E = 0.4, H = 2.5) and the other families of `smb_compare --help`, {args.steps} "
              f"steps after the build; times are wall-clock ms "
              f"of the method's calls; steps 1–{args.early_steps} are the first after the build, steady = "
              f"the median of the later ones. Ratios: grid time ÷ method time (above 1: faster than the grid). "
              f"CPU ms: CPU time of the process, all its threads.",
              "Pair sets: " + ("every method reported the same pairs at every step of its scene."
                               if not problems else "PROBLEMS: " + "; ".join(problems))]
    csv_path = os.path.join(out_dir, f"{args.name}.csv")
    with open(csv_path, "w", newline="") as handle:
        writer = csv.DictWriter(handle, fieldnames=FIELDS, extrasaction="ignore")
        writer.writeheader()
        for row in rows:
            writer.writerow({k: (f"{v:.6g}" if isinstance(v, float) else v) for k, v in row.items()})
    with open(os.path.join(out_dir, f"{args.name}.jsonl"), "w") as handle:
        handle.write("\n".join(raw_lines) + "\n")
    with open(os.path.join(out_dir, f"{args.name}.md"), "w") as handle:
        handle.write(markdown(rows, header, args.early_steps))
    print(f"wrote {csv_path} (.jsonl, .md) in {elapsed / 60:.1f} minutes")
    if problems:
        print("PROBLEMS:\n  " + "\n  ".join(problems), file=sys.stderr)
        return 1
    return 0


if __name__ == "__main__":
    sys.exit(main())
