#!/usr/bin/python3
# SPDX-License-Identifier: MIT
"""Plots smb_bullet_step_bench's CSV files: broad-phase and whole-step time per step, steady
state, for each broad phase, scene and body count (the mean of a broad phase's passes, where a
run repeats it).

    /usr/bin/python3 examples/bullet/plot_step_bench.py bench/results/bullet/step_*.csv \
        --out bench/results/bullet/step.png
"""
import argparse
import csv

import matplotlib

matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402

NAMES = {"smb": "smb::bullet::Broadphase", "dbvt": "btDbvtBroadphase", "sap": "btAxisSweep3 / bt32BitAxisSweep3"}


def main():
    parser = argparse.ArgumentParser(description=__doc__)
    parser.add_argument("csv", nargs="+")
    parser.add_argument("--out", required=True)
    args = parser.parse_args()
    rows = []
    for path in args.csv:
        with open(path, newline="") as f:
            rows += [r for r in csv.DictReader(f) if r["part"] == "steady"]
    groups = sorted({(int(r["bodies"]), r["scene"]) for r in rows})
    broadphases = [b for b in NAMES if any(r["broadphase"] == b for r in rows)]
    fig, axes = plt.subplots(1, 2, figsize=(max(11.0, 2.6 * len(groups)), 4.6))
    for axis, column, title in ((axes[0], "broadphase_ms", "broad phase"), (axes[1], "step_ms", "whole step")):
        width = 0.8 / len(broadphases)
        for i, name in enumerate(broadphases):
            values = []
            for bodies, scene in groups:
                match = [r for r in rows if r["broadphase"] == name and int(r["bodies"]) == bodies and r["scene"] == scene]
                values.append(sum(float(r[column]) for r in match) / len(match) if match else 0.0)
            axis.bar([g + i * width for g in range(len(groups))], values, width, label=NAMES[name])
        axis.set_xticks([g + 0.4 - width / 2 for g in range(len(groups))])
        axis.set_xticklabels([f"{bodies:,}\n{scene}" for bodies, scene in groups], fontsize=8)
        axis.set_yscale("log")
        axis.set_ylabel("ms per step (steady state, mean of passes)")
        axis.set_title(f"Bullet pile: {title}")
        axis.grid(axis="y", alpha=0.3)
    handles, labels = axes[0].get_legend_handles_labels()
    fig.legend(handles, labels, loc="upper center", ncol=len(broadphases), fontsize=9)
    fig.tight_layout(rect=(0, 0, 1, 0.92))
    fig.savefig(args.out, dpi=110)


if __name__ == "__main__":
    main()
