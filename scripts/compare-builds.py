#!/usr/bin/python3
# SPDX-License-Identifier: MIT
"""Times two or more builds of `smb` side by side on one `smb run` scene.

The builds run in alternating rounds (A, B, A, B, ...), so that the noise of a shared machine
falls on all of them alike, and each run's summary is read from `smb run --json`. Prints, per
build, the median over the rounds (and the range) of: the median detection of the run, its
cut+regroup and check phases, the build step, and the bytes held per box; and whether every
run's reference check passed.

Usage (the build before a change in ../before, after it in build):
    /usr/bin/python3 scripts/compare-builds.py --rounds 3 ../before/build/tools/smb/smb \\
        build/tools/smb/smb -- -n 1000000 -L 1e-3 -s 8 --pipeline detector
"""

import argparse
import json
import statistics
import subprocess
import sys


def run_once(binary, run_args):
    result = subprocess.run([binary, "run", *run_args, "--no-progress", "--json"],
                            capture_output=True, text=True, check=False)
    if result.returncode != 0:
        sys.exit(f"{binary} run {' '.join(run_args)} failed ({result.returncode}):\n{result.stderr}")
    summary = json.loads(result.stdout)
    phases = summary["phase_seconds_median"]
    return {
        "step": (summary["detect_seconds"]["median"] or 0.0) * 1e3,
        "cut+regroup": phases["cut_regroup"] * 1e3,
        "check": phases["check"] * 1e3,
        "build": summary["build_seconds"] * 1e3,
        "bytes/box": summary["bytes_per_box"],
        "ok": summary["check"]["ok"],
    }


def describe(values):
    return f"{statistics.median(values):.1f} [{min(values):.1f}-{max(values):.1f}]"


def main():
    parser = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    parser.add_argument("--rounds", type=int, default=3, help="alternating rounds (default 3)")
    parser.add_argument("binaries", nargs="+", help="smb executables to compare, then -- and the smb run options")
    argv = sys.argv[1:]
    split = argv.index("--") if "--" in argv else len(argv)
    args = parser.parse_args(argv[:split])
    run_args = argv[split + 1:]
    if len(args.binaries) < 2:
        parser.error("give at least two builds")
    runs = {binary: [] for binary in args.binaries}
    for _ in range(args.rounds):
        for binary in args.binaries:
            runs[binary].append(run_once(binary, run_args))
    print("smb run " + " ".join(run_args) + f"  ({args.rounds} alternating rounds; ms, median [min-max])")
    for binary, results in runs.items():
        fields = " | ".join(f"{name} {describe([r[name] for r in results])}"
                            for name in ("step", "cut+regroup", "check", "build"))
        ok = all(r["ok"] for r in results)
        print(f"  {binary}: {fields} | {results[0]['bytes/box']:.1f} B/box | check {'ok' if ok else 'FAILED'}")


if __name__ == "__main__":
    main()
