#!/usr/bin/env python3
# SPDX-License-Identifier: MIT
"""Randomised odd scenes through `smb pairs`, checked against a brute force.

Each trial writes a scene CSV (2D or 3D, up to 2000 boxes, 1 to 4 frames with deletions,
insertions and moves, ids above 2^40) of one kind:
    far      boxes of size ~1 around offsets up to 7e19
    huge     the same around 1e300 (double coordinates beyond the float range)
    tiny     boxes under 1e-7 wide
    mixed    sizes 0, 1e-9, 0.3, 40 and 1e6 together
    lattice  unit boxes on an integer lattice: every neighbour touches
    ulp      zero-size and thin boxes, half of them touching or missing a neighbour by one ulp
runs `smb pairs` on it and compares the pair CSV with the brute force, frame by frame. Python
floats are doubles and the CSV is written with repr(), so the brute force sees exactly the
coordinates smb parses. Standard library only: any python3 runs it.

    python3 scripts/stress-pairs.py --smb build/tools/smb/smb --trials 100 --seed 1

Exit status 1 on any mismatch; the failing scene is kept (its path is printed). Set
SMB_NO_AVX2=1 to check the sweep's four-lane path on an AVX2 machine.
"""

import argparse
import math
import os
import random
import subprocess
import sys
import tempfile

KINDS = ("far", "huge", "tiny", "mixed", "lattice", "ulp")


def random_box(rng, dim, kind, base):
    if kind == "lattice":
        centre = [base + rng.randint(0, 12) for _ in range(dim)]
        half = [0.5] * dim
    else:
        spread = 1e-6 if kind == "tiny" else 50.0
        centre = [base + rng.uniform(-1, 1) * spread for _ in range(dim)]
        if kind == "ulp":
            half = [rng.choice([0.0, 1e-12, 0.5]) for _ in range(dim)]
        elif kind == "mixed":
            half = [rng.choice([0.0, 1e-9, 0.3, 40.0, 1e6]) for _ in range(dim)]
        elif kind == "tiny":
            half = [rng.uniform(0, 1e-7) for _ in range(dim)]
        else:
            half = [rng.uniform(0, 3) for _ in range(dim)]
    lo = [centre[k] - half[k] for k in range(dim)]
    hi = [centre[k] + half[k] for k in range(dim)]
    if kind == "ulp" and rng.random() < 0.5:
        # On one axis the box starts where it ended, or one ulp after: it touches or misses
        # boxes that end there.
        k = rng.randrange(dim)
        lo[k] = hi[k] if rng.random() < 0.5 else math.nextafter(hi[k], math.inf)
        hi[k] = max(hi[k], lo[k])
    return lo, hi


def random_scene(rng, dim):
    """Rows (frame, id, lo, hi)."""
    n = rng.choice([0, 1, 2, 50, 300, 2000])
    kind = rng.choice(KINDS)
    base = 1e300 if kind == "huge" else rng.choice([0.0, 5.0, 1e6, -3e9, 1e15, 7e19, 1e-20])
    boxes = {}
    rows = []
    serial = 0
    for frame in range(rng.randint(1, 4)):
        if frame == 0:
            arrivals = n
        else:
            for box_id in list(boxes):
                roll = rng.random()
                if roll < 0.1:
                    del boxes[box_id]
                elif roll < 0.6:
                    boxes[box_id] = random_box(rng, dim, kind, base)
            arrivals = rng.randint(0, n // 10 + 1)
        for _ in range(arrivals):
            boxes[serial * 3 + rng.randint(0, 2) * (1 << 40) + frame * (1 << 50)] = random_box(rng, dim, kind, base)
            serial += 1
        rows.extend((frame, box_id, lo, hi) for box_id, (lo, hi) in boxes.items())
    return rows


def brute_force(rows, dim):
    frames = {}
    for frame, box_id, lo, hi in rows:
        frames.setdefault(frame, []).append((box_id, lo, hi))
    pairs = []
    for frame in sorted(frames):
        boxes = sorted(frames[frame])
        for i, (a, a_lo, a_hi) in enumerate(boxes):
            for b, b_lo, b_hi in boxes[i + 1:]:
                if all(a_lo[k] <= b_hi[k] and b_lo[k] <= a_hi[k] for k in range(dim)):
                    pairs.append((frame, a, b))
    return pairs


def write_scene(path, rows, dim):
    header = "frame,id,xmin,ymin,xmax,ymax" if dim == 2 else "frame,id,xmin,ymin,zmin,xmax,ymax,zmax"
    with open(path, "w") as handle:
        handle.write(header + "\n")
        for frame, box_id, lo, hi in rows:
            handle.write(",".join([str(frame), str(box_id)] + [repr(float(v)) for v in lo + hi]) + "\n")


def read_pairs(path):
    with open(path) as handle:
        next(handle)
        return [tuple(int(field) for field in line.split(",")) for line in handle if line.strip()]


def main():
    parser = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    parser.add_argument("--smb", required=True, help="the smb binary")
    parser.add_argument("--trials", type=int, default=100)
    parser.add_argument("--seed", type=int, default=1)
    args = parser.parse_args()

    work = tempfile.mkdtemp(prefix="smb-stress-")
    failures = 0
    for trial in range(args.trials):
        rng = random.Random(args.seed * 1_000_003 + trial)
        dim = rng.choice([2, 3])
        rows = random_scene(rng, dim)
        scene = os.path.join(work, f"scene-{trial}.csv")
        pairs = os.path.join(work, f"pairs-{trial}.csv")
        write_scene(scene, rows, dim)
        run = subprocess.run([args.smb, "pairs", "-i", scene, "-o", pairs], capture_output=True, text=True)
        if run.returncode != 0:
            print(f"trial {trial}: smb pairs exited {run.returncode}: {run.stderr.strip()[:300]} (scene {scene})")
            failures += 1
            continue
        got, expected = read_pairs(pairs), brute_force(rows, dim)
        if got != expected:
            missing = sorted(set(expected) - set(got))[:3]
            extra = sorted(set(got) - set(expected))[:3]
            print(f"trial {trial}: {len(got)} pairs, expected {len(expected)}; missing {missing}, extra {extra} "
                  f"(scene {scene})")
            failures += 1
            continue
        os.remove(scene)
        os.remove(pairs)
    print(f"{args.trials - failures} of {args.trials} scenes exact")
    if not failures:
        os.rmdir(work)
    return 1 if failures else 0


if __name__ == "__main__":
    sys.exit(main())
