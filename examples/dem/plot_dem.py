#!/usr/bin/python3
# SPDX-License-Identifier: MIT
"""Draws what smb_dem wrote: the energies against time, and the final packing.

    /usr/bin/python3 examples/dem/plot_dem.py --energy energy.csv --particles particles.csv \
        --prefix pour_ --out docs/dem

writes <out>/<prefix>energy.png and, given --particles, <out>/<prefix>packing.png (numpy and
matplotlib: Debian's python3-numpy, python3-matplotlib).
"""

import argparse
import os

import matplotlib

matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402
import numpy as np  # noqa: E402


def plot_energy(path, out, title):
    data = np.genfromtxt(path, delimiter=",", names=True)
    fig, (ax, drift) = plt.subplots(2, 1, figsize=(7, 6), sharex=True, gridspec_kw={"height_ratios": [2, 1]})
    for name, label in [("total", "total"), ("potential", "gravity"), ("kinetic", "kinetic"),
                        ("rotational", "rotational"), ("elastic", "springs")]:
        if np.any(data[name] != 0):
            ax.plot(data["time"], data[name], label=label)
    ax.set_ylabel("energy  [rho g d^4]")
    ax.set_title(title)
    ax.legend(loc="best")
    ax.grid(alpha=0.3)
    # The total against its start: the integrator's error, or what damping and friction took.
    drift.plot(data["time"], data["total"] / data["total"][0] - 1, color="k", lw=0.8)
    drift.set_ylabel("total / start - 1")
    drift.set_xlabel("time  [sqrt(d / g)]")
    drift.grid(alpha=0.3)
    fig.tight_layout()
    fig.savefig(out, dpi=120)
    plt.close(fig)


def plot_packing(path, out, title):
    data = np.genfromtxt(path, delimiter=",", names=True)
    x, y, z, r = data["x"], data["y"], data["z"], data["radius"]
    fig = plt.figure(figsize=(10, 5))
    # Left: the whole bed in 3D, coloured by height.
    ax = fig.add_subplot(1, 2, 1, projection="3d")
    ax.scatter(x, y, z, c=z, cmap="viridis", s=12, depthshade=True)
    ax.set_box_aspect((np.ptp(x) + 1, np.ptp(y) + 1, np.ptp(z) + 1))
    ax.set_xlabel("x")
    ax.set_ylabel("y")
    ax.set_zlabel("z")
    ax.set_title("the settled bed")
    # Right: a slab through the middle, the spheres cut by the plane y = middle drawn to scale.
    ax2 = fig.add_subplot(1, 2, 2)
    middle = 0.5 * (y.min() + y.max())
    cut = np.abs(y - middle) < r
    for xi, zi, ri, yi in zip(x[cut], z[cut], r[cut], y[cut]):
        rc = np.sqrt(max(ri * ri - (yi - middle) ** 2, 0.0))
        ax2.add_patch(plt.Circle((xi, zi), rc, color=plt.cm.viridis(zi / max(z.max(), 1)), ec="k", lw=0.3))
    ax2.set_xlim(x.min() - 1, x.max() + 1)
    ax2.set_ylim(0, z.max() + 1)
    ax2.set_aspect("equal")
    ax2.set_xlabel("x")
    ax2.set_ylabel("z")
    ax2.set_title("section through the middle (y = %.1f)" % middle)
    fig.suptitle(title)
    fig.tight_layout()
    fig.savefig(out, dpi=120)
    plt.close(fig)


def main():
    parser = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    parser.add_argument("--energy", required=True, help="energy CSV of smb_dem --energy-csv")
    parser.add_argument("--particles", help="particle CSV of smb_dem --particles-csv")
    parser.add_argument("--prefix", default="", help="put before the PNGs' names")
    parser.add_argument("--out", default=".", help="folder of the PNGs")
    parser.add_argument("--title", default="smb_dem", help="title above both pictures")
    args = parser.parse_args()
    os.makedirs(args.out, exist_ok=True)
    plot_energy(args.energy, os.path.join(args.out, args.prefix + "energy.png"), args.title)
    if args.particles:
        plot_packing(args.particles, os.path.join(args.out, args.prefix + "packing.png"), args.title)


if __name__ == "__main__":
    main()
