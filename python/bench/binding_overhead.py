# SPDX-License-Identifier: MIT
"""The binding's overhead: smb.find_overlapping_pairs and smb.Detector.detect beside the C++ calls
they make (smb_python_call_timer), on the same boxes, in alternating rounds so that the load of a
shared machine falls on both alike. Each round times every call --repeats times; the report gives
the median of the rounds' medians and the least time seen, and their Python / C++ ratios.

Detector.detect is compared with two C++ callers: one that reuses its vector of pairs (its
memory stays mapped from call to call), and one that takes a new vector each call, as the
binding must when it returns a new array (which owns its pairs). Detector.detect(out=buffer),
which writes into one array reused from call to call, is compared with the first. Beside them, the Python call's time over the
library's own total_seconds of the same call (Detector.stats): the binding's share alone.

  cmake --build <build> --target smb_python smb_python_call_timer
  /usr/bin/python3 python/bench/binding_overhead.py --build <build> [--boxes 1000000] [--dims 2 3]
      [--rounds 5] [--repeats 5] [--clock wall|cpu] [--no-find]

--clock cpu times the calling thread's CPU time on both sides (the detections run on it, with
threads=1), which the other jobs of a shared machine disturb less than the wall clock.
--no-find leaves out the one-shot find_overlapping_pairs rows.
"""

import argparse
import os
import statistics
import sys
import time

import numpy as np

from compare_peers import cpp_call, scene, timed


def main():
    parser = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    parser.add_argument("--build", default="build")
    parser.add_argument("--boxes", type=int, default=1_000_000)
    parser.add_argument("--dims", type=int, nargs="+", default=[2, 3])
    parser.add_argument("--rounds", type=int, default=5)
    parser.add_argument("--repeats", type=int, default=5)
    parser.add_argument("--clock", choices=["wall", "cpu"], default="wall")
    parser.add_argument("--no-find", action="store_true")
    args = parser.parse_args()
    clock = time.thread_time if args.clock == "cpu" else time.perf_counter
    sys.path.insert(0, os.path.join(args.build, "python"))
    import smb

    timer = os.path.join(args.build, "python", "smb_python_call_timer")
    print("| dim | boxes | call | Python median s | C++ median s | ratio | Python min s | C++ min s | ratio |")
    print("|---|---|---|---|---|---|---|---|---|")
    for dim in args.dims:
        boxes, _, _ = scene(args.boxes, dim)
        seen = {key: [] for key in ("py_find", "py_detect", "py_out", "cpp_find", "cpp_detect", "cpp_fresh")}
        own_share = []
        least = {key: float("inf") for key in seen}
        detector = smb.Detector(dim)
        buffer = np.empty((len(detector.detect(boxes)) * 9 // 8, 2), dtype=np.int64)
        calls = [("py_detect", lambda: detector.detect(boxes)),
                 ("py_out", lambda: detector.detect(boxes, out=buffer))]
        if not args.no_find:
            calls.insert(0, ("py_find", lambda: smb.find_overlapping_pairs(boxes)))
        for _ in range(args.rounds):
            for key, call in calls:
                median, best, _ = timed(call, args.repeats, clock)
                seen[key].append(median)
                least[key] = min(least[key], best)
            for _ in range(args.repeats if args.clock == "wall" else 0):  # total_seconds is wall time
                call_seconds, _, _ = timed(lambda: detector.detect(boxes), 1, clock)
                own_share.append(call_seconds / detector.stats["total_seconds"])
            cpp = cpp_call(timer, boxes, args.repeats, args.clock)
            for call in ("find", "detect", "fresh"):
                seen[f"cpp_{call}"].append(cpp[f"{call}_median"])
                least[f"cpp_{call}"] = min(least[f"cpp_{call}"], cpp[f"{call}_min"])
        rows = [("detect", "detect", "Detector.detect again; C++ reuses its vector"),
                ("detect", "fresh", "Detector.detect again; C++ takes a new vector"),
                ("out", "detect", "Detector.detect(out=) again; C++ reuses its vector")]
        if not args.no_find:
            rows.insert(0, ("find", "find", "find_overlapping_pairs (sorted)"))
        for py, cpp_key, name in rows:
            py_median = statistics.median(seen[f"py_{py}"])
            cpp_median = statistics.median(seen[f"cpp_{cpp_key}"])
            print(f"| {dim}D | {args.boxes} | {name} | {py_median:.4f} | {cpp_median:.4f} | "
                  f"{py_median / cpp_median:.3f} | {least[f'py_{py}']:.4f} | {least[f'cpp_{cpp_key}']:.4f} | "
                  f"{least[f'py_{py}'] / least[f'cpp_{cpp_key}']:.3f} |", flush=True)
        if not own_share:
            continue
        print(f"| {dim}D | {args.boxes} | Detector.detect call / its own total_seconds | median "
              f"{statistics.median(own_share):.3f} | | | least {min(own_share):.3f} | | |", flush=True)


if __name__ == "__main__":
    main()
