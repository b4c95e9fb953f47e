#!/usr/bin/env python3
"""Draw the blocks of one or more blockdem block files (.vtu, as `arch --vtk PREFIX` writes PREFIX_blocks.vtu) in
elevation, seen along y: the faces projected on the x-z plane, the nearest drawn last, fixed blocks grey and free ones
coloured by their displacement. One panel per file, one above the other (for example the arch as built and after its
collapse).

    python3 scripts/plot_blocks_elevation.py before_blocks.vtu after_blocks.vtu --titles "built" "collapsed" \\
        --out arch_collapse.png

Needs numpy and matplotlib (`scripts/install-deps.sh --plots` installs them for the system Python, which the script
uses when the running `python3` lacks them).
"""

import argparse

from python_modules import require_modules

require_modules(__file__)  # numpy and matplotlib, or the system Python that has them
import matplotlib  # noqa: E402

matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402
import numpy as np  # noqa: E402
from matplotlib.collections import PolyCollection  # noqa: E402
from figures import save_figure  # noqa: E402
from vtu import read_vtu  # noqa: E402


def main():
    parser = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    parser.add_argument("vtu", nargs="+", help="block files")
    parser.add_argument("--titles", nargs="*", default=[], help="one title per file")
    parser.add_argument("--out", required=True, help="output PNG")
    args = parser.parse_args()
    drawn = [read_vtu(path) for path in args.vtu]
    top = max((c.get("displacement", np.zeros(1)).max() for _, _, c in drawn), default=0) or 1.0
    lo = np.min([p.min(axis=0) for p, _, _ in drawn], axis=0)
    hi = np.max([p.max(axis=0) for p, _, _ in drawn], axis=0)
    # Panels stacked, each as wide as the page and as high as the blocks' elevation needs.
    aspect = (hi[2] - lo[2] + 0.1) / (hi[0] - lo[0] + 0.1)
    fig, axes = plt.subplots(len(args.vtu), 1, figsize=(10, 0.9 + len(args.vtu) * (10 * aspect + 0.6)), squeeze=False)
    axes = axes.T
    for k, (ax, (points, polygons, cells)) in enumerate(zip(axes[0], drawn)):
        motion = cells.get("motion", np.zeros(len(polygons)))
        displacement = cells.get("displacement", np.zeros(len(polygons)))
        faces = []
        for polygon, m, d in zip(polygons, motion, displacement):
            colour = "#b9b9b9" if m != 0 else plt.cm.viridis(min(d / top, 1.0))
            faces.append((-points[polygon][:, 1].mean(), points[polygon][:, [0, 2]], colour))
        faces.sort(key=lambda f: f[0])  # farthest (largest y) first
        ax.add_collection(PolyCollection([f[1] for f in faces], facecolors=[f[2] for f in faces],
                                         edgecolors="#202020", linewidths=0.3))
        ax.set_xlim(lo[0] - 0.05, hi[0] + 0.05)
        ax.set_ylim(lo[2] - 0.05, hi[2] + 0.05)
        ax.set_aspect("equal")
        ax.set_xlabel("x (m)")
        ax.set_ylabel("z (m)")
        if k < len(args.titles):
            ax.set_title(args.titles[k], fontsize=10)
    mappable = plt.cm.ScalarMappable(cmap="viridis", norm=plt.Normalize(0, top))
    fig.colorbar(mappable, ax=axes[0].tolist(), label="displacement (m)", shrink=0.9, pad=0.02)
    save_figure(fig, args.out, dpi=130)


if __name__ == "__main__":
    main()
