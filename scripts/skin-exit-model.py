#!/usr/bin/env python3
# SPDX-License-Identifier: MIT
"""How many boxes leave their skin per step under the paper's motion, by simulation.

The paper's environment moves every centre coordinate by a fresh uniform random amount in
(-L x, L x) each step (a random walk). A box whose centre strays more than the skin from where its
fat box was made must be refreshed, and gets a new fat box around its new place. This prints the
fraction of boxes refreshed per step, right after a rebuild and once the list is old.
Box sides change by at most L per step in that environment (b = 1), which this leaves out.

Usage: /usr/bin/python3 scripts/skin-exit-model.py --step 0.095 --skins 0.1,0.2,0.35,0.5
(0.095 = L x at N = 1M in 3D with L = 1e-3: cube side 95.)
"""

import argparse

import numpy as np


def main() -> None:
    parser = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    parser.add_argument("--step", type=float, default=0.095, help="largest displacement per axis and step")
    parser.add_argument("--skins", default="0.1,0.2,0.35,0.5")
    parser.add_argument("--boxes", type=int, default=100000)
    parser.add_argument("--steps", type=int, default=300)
    parser.add_argument("--dim", type=int, default=3)
    parser.add_argument("--seed", type=int, default=1)
    args = parser.parse_args()
    random = np.random.default_rng(args.seed)
    for skin in (float(s) for s in args.skins.split(",")):
        offset = np.zeros((args.boxes, args.dim))
        rates = []
        for _ in range(args.steps):
            offset += random.uniform(-args.step, args.step, offset.shape)
            out = (np.abs(offset) > skin).any(axis=1)
            rates.append(out.mean())
            offset[out] = 0
        old = rates[args.steps * 2 // 3:]
        print(f"skin {skin:g}: refreshed per step, steps 1-6 {[round(r, 4) for r in rates[:6]]}, "
              f"old list (last third) {np.mean(old):.4f}")


if __name__ == "__main__":
    main()
