# SPDX-License-Identifier: MIT
"""smb beside what Python users have for "every overlapping pair of N boxes", on the same boxes,
and the binding's overhead over the C++ call it makes.

Peers (each used as its documentation recommends for speed, with Debian's packages):
  shapely  STRtree of the boxes (shapely.geometry.box), every box queried with query_items;
           2D only (GEOS envelopes are 2D). Debian's shapely is 1.8, without shapely 2's
           vectorised query, so the queries are a Python loop.
  rtree    libspatialindex R*-tree bulk-loaded from a stream, every box queried with
           intersection(); rtree 1.0 has no vectorised query either.
  ckdtree  scipy.spatial.cKDTree.query_pairs(r, p=inf, output_type='ndarray') over the centres:
           its exact case, since every box of the scene is the same cube (two cubes of side s
           overlap iff their centres are within s in the Chebyshev metric).
smb is smb.find_overlapping_pairs (pairs sorted) and, for the overhead, smb.Detector.detect
called again on the same boxes. A peer's pair count must equal smb's, else the run stops.

Scene: N equal cubes (squares in 2D) at uniformly random centres in the unit cube, sized so
that a box overlaps about 4 others.

Needs, beside the module (PYTHONPATH=<build>/python, docs/python.md):
  apt-get install python3-shapely python3-rtree python3-scipy python3-matplotlib
and, for the overhead, the C++ timer built in the same build folder:
  cmake --build <build> --target smb_python_call_timer

  /usr/bin/python3 python/bench/compare_peers.py --build build [--sizes 10000 100000 1000000]
      [--dims 2 3] [--repeats 5] [--peer-repeats 1] [--budget 60] [--out bench/results/cpp-2core/python-peers]
writes OUT.csv, OUT.md (tables) and OUT.png (the plot). A peer that took more than --budget
seconds at one size is not run at the larger ones.
"""

import argparse
import json
import os
import statistics
import subprocess
import sys
import tempfile
import time
import warnings

import numpy as np


def scene(count, dim, seed=1):
    rng = np.random.default_rng(seed)
    side = 0.5 * (4.0 / count) ** (1.0 / dim)  # (2 side)^dim * count = 4 neighbours on average
    centres = rng.random((count, dim))
    boxes = np.stack([centres - side / 2, centres + side / 2], axis=1)
    return boxes, centres, side


def timed(call, repeats, clock=time.perf_counter):
    seconds, result = [], None
    for _ in range(repeats):
        start = clock()
        result = call()
        seconds.append(clock() - start)
    return statistics.median(seconds), min(seconds), result


def run_smb(smb, boxes, centres, side, repeats):
    median, best, pairs = timed(lambda: smb.find_overlapping_pairs(boxes), repeats)
    return median, best, len(pairs)


def run_smb_detector(smb, boxes, repeats):
    detector = smb.Detector(boxes.shape[2])
    detector.detect(boxes)
    median, best, pairs = timed(lambda: detector.detect(boxes), repeats)
    return median, best, len(pairs)


def run_shapely(boxes, repeats):
    from shapely.geometry import box as shapely_box
    from shapely.strtree import STRtree

    def all_pairs():
        geometries = [shapely_box(b[0, 0], b[0, 1], b[1, 0], b[1, 1]) for b in boxes]
        tree = STRtree(geometries)
        hits = sum(len(tree.query_items(g)) for g in geometries)
        return (hits - len(geometries)) // 2  # each pair twice, and every box finds itself

    median, best, count = timed(all_pairs, repeats)
    return median, best, count


def run_rtree(boxes, repeats):
    from rtree import index

    dim = boxes.shape[2]
    flat = boxes.reshape(len(boxes), 2 * dim).tolist()  # xmin, ymin[, zmin], xmax, ... (interleaved)

    def all_pairs():
        properties = index.Property(dimension=dim)
        tree = index.Index(((i, b, None) for i, b in enumerate(flat)), properties=properties)
        hits = sum(len(list(tree.intersection(b))) for b in flat)
        return (hits - len(flat)) // 2

    median, best, count = timed(all_pairs, repeats)
    return median, best, count


def run_ckdtree(centres, side, repeats):
    from scipy.spatial import cKDTree

    def all_pairs():
        return len(cKDTree(centres).query_pairs(side, p=np.inf, output_type="ndarray"))

    median, best, count = timed(all_pairs, repeats)
    return median, best, count


def cpp_call(timer, boxes, repeats, clock="wall"):
    with tempfile.NamedTemporaryFile(suffix=".f64") as file:
        np.ascontiguousarray(boxes, dtype=np.float64).tofile(file.name)
        out = subprocess.run([timer, file.name, str(boxes.shape[2]), str(repeats), clock], check=True,
                             capture_output=True, text=True).stdout
    return json.loads(out)


def main():
    parser = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    parser.add_argument("--build", default="build", help="CMake build folder with python/smb and the timer")
    parser.add_argument("--sizes", type=int, nargs="+", default=[10_000, 100_000, 1_000_000])
    parser.add_argument("--dims", type=int, nargs="+", default=[2, 3])
    parser.add_argument("--repeats", type=int, default=5, help="runs of smb and of the C++ calls")
    parser.add_argument("--peer-repeats", type=int, default=1, help="runs of each peer")
    parser.add_argument("--budget", type=float, default=60.0)
    parser.add_argument("--out", default="bench/results/cpp-2core/python-peers")
    args = parser.parse_args()

    sys.path.insert(0, os.path.join(args.build, "python"))
    import smb

    # shapely 1.8 announces its 2.0 STRtree on every construction.
    warnings.filterwarnings("ignore", message="STRtree will be changed")

    timer = os.path.join(args.build, "python", "smb_python_call_timer")
    rows = []
    for dim in args.dims:
        over_budget = set()
        for count in args.sizes:
            boxes, centres, side = scene(count, dim)
            median, best, expected = run_smb(smb, boxes, centres, side, args.repeats)
            rows.append(dict(dim=dim, boxes=count, method="smb", median=median, min=best, pairs=expected))
            peers = [("ckdtree", lambda: run_ckdtree(centres, side, args.peer_repeats)),
                     ("rtree", lambda: run_rtree(boxes, args.peer_repeats))]
            if dim == 2:
                peers.append(("shapely", lambda: run_shapely(boxes, args.peer_repeats)))
            for name, run in peers:
                if name in over_budget:
                    continue
                median, best, pairs = run()
                if pairs != expected:
                    sys.exit(f"{name} found {pairs} pairs where smb found {expected} ({dim}D, {count} boxes)")
                rows.append(dict(dim=dim, boxes=count, method=name, median=median, min=best, pairs=pairs))
                if median > args.budget:
                    over_budget.add(name)
            if os.path.exists(timer):
                cpp = cpp_call(timer, boxes, args.repeats)
                if cpp["pairs"] != expected:
                    sys.exit(f"the C++ timer found {cpp['pairs']} pairs where smb found {expected}")
                detect_median, detect_min, _ = run_smb_detector(smb, boxes, args.repeats)
                rows.append(dict(dim=dim, boxes=count, method="smb.Detector.detect", median=detect_median,
                                 min=detect_min, pairs=expected))
                rows.append(dict(dim=dim, boxes=count, method="C++ find_overlapping_pairs+sort",
                                 median=cpp["find_median"], min=cpp["find_min"], pairs=expected))
                rows.append(dict(dim=dim, boxes=count, method="C++ Detector::detect", median=cpp["detect_median"],
                                 min=cpp["detect_min"], pairs=expected))
            for row in rows:
                if row["dim"] == dim and row["boxes"] == count:
                    print(f"{dim}D {count:>8} {row['method']:<32} median {row['median']:9.4f} s  "
                          f"min {row['min']:9.4f} s  pairs {row['pairs']}", flush=True)
    write_results(rows, args.out)


def write_results(rows, out):
    os.makedirs(os.path.dirname(out) or ".", exist_ok=True)
    with open(out + ".csv", "w") as file:
        file.write("dim,boxes,method,median_seconds,min_seconds,pairs\n")
        for row in rows:
            file.write(f"{row['dim']},{row['boxes']},{row['method']},{row['median']:.6f},{row['min']:.6f},"
                       f"{row['pairs']}\n")
    smb_time = {(r["dim"], r["boxes"]): r["median"] for r in rows if r["method"] == "smb"}
    with open(out + ".md", "w") as file:
        file.write("| dim | boxes | method | median s | min s | median / smb | pairs |\n")
        file.write("|---|---|---|---|---|---|---|\n")
        for row in rows:
            ratio = row["median"] / smb_time[(row["dim"], row["boxes"])]
            file.write(f"| {row['dim']}D | {row['boxes']} | {row['method']} | {row['median']:.4f} | "
                       f"{row['min']:.4f} | {ratio:.2f} | {row['pairs']} |\n")
    import matplotlib

    matplotlib.use("Agg")
    import matplotlib.pyplot as plt

    dims = sorted({r["dim"] for r in rows})
    figure, axes = plt.subplots(1, len(dims), figsize=(6 * len(dims), 4.5), squeeze=False)
    for axis, dim in zip(axes[0], dims):
        for method in ["smb", "ckdtree", "rtree", "shapely"]:
            points = [(r["boxes"], r["median"]) for r in rows if r["dim"] == dim and r["method"] == method]
            if points:
                axis.loglog(*zip(*points), marker="o", label=method)
        axis.set_title(f"all overlapping pairs, {dim}D equal cubes")
        axis.set_xlabel("boxes")
        axis.set_ylabel("seconds (median)")
        axis.grid(True, which="both", alpha=0.3)
        axis.legend()
    figure.tight_layout()
    figure.savefig(out + ".png", dpi=100)


if __name__ == "__main__":
    main()
