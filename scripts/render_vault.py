#!/usr/bin/env python3
"""Render the blocks of a blockdem .vtu file (as `cross_vault --geometry-only --vtk FILE` writes it: ASCII
polygons with a per-cell `component` field) to a PNG, coloured by component: the whole specimen in 3D, and the plan
of the vault and its infill seen from above (the brick courses, their staggered head joints and the groins).

    python3 scripts/render_vault.py vault.vtu docs/cross_vault.png

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
from matplotlib.patches import Patch  # noqa: E402
from figures import save_figure  # noqa: E402
from vtu import read_vtu  # noqa: E402
from mpl_toolkits.mplot3d.art3d import Poly3DCollection  # noqa: E402

# Component indices as in include/blockdem/models/cross_vault.hpp (enum class Component).
COMPONENTS = ["vault", "infill", "fixed pier", "movable pier", "slab", "tie anchor", "steel frame"]
COLOURS = ["#c8643c", "#e3b778", "#8c6d5a", "#4a78b5", "#b9b9b9", "#6f8f3a", "#37474f"]


def draw(ax, points, polygons, component, keep, elev, azim, title):
    faces, colours = [], []
    for polygon, c in zip(polygons, component):
        if int(c) in keep:
            faces.append(points[polygon])
            colours.append(COLOURS[int(c)])
    ax.add_collection3d(Poly3DCollection(faces, facecolors=colours, edgecolors="#202020", linewidths=0.08))
    corners = np.concatenate(faces)
    lo, hi = corners.min(axis=0), corners.max(axis=0)
    centre, half = 0.5 * (lo + hi), 0.5 * (hi - lo).max()
    ax.set_xlim(centre[0] - half, centre[0] + half)
    ax.set_ylim(centre[1] - half, centre[1] + half)
    ax.set_zlim(centre[2] - half, centre[2] + half)
    ax.set_box_aspect((1, 1, 1))
    ax.view_init(elev=elev, azim=azim)
    ax.set_xlabel("x (m, east)")
    ax.set_ylabel("y (m, north)")
    ax.set_zlabel("z (m)")
    ax.set_title(title, fontsize=10)


def draw_plan(ax, points, polygons, component, keep, title):
    """Top view: faces drawn from the lowest to the highest, so that the extrados hides what lies below it."""
    faces = [(points[p][:, 2].mean(), points[p][:, :2], COLOURS[int(c)])
             for p, c in zip(polygons, component) if int(c) in keep]
    faces.sort(key=lambda f: f[0])
    ax.add_collection(PolyCollection([f[1] for f in faces], facecolors=[f[2] for f in faces],
                                     edgecolors="#202020", linewidths=0.1))
    corners = np.concatenate([f[1] for f in faces])
    ax.set_xlim(corners[:, 0].min() - 0.05, corners[:, 0].max() + 0.05)
    ax.set_ylim(corners[:, 1].min() - 0.05, corners[:, 1].max() + 0.05)
    ax.set_aspect("equal")
    ax.set_xlabel("x (m, east)")
    ax.set_ylabel("y (m, north; the excitation)")
    ax.set_title(title, fontsize=10)


def main():
    parser = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    parser.add_argument("vtu", help="blocks written by cross_vault --vtk")
    parser.add_argument("png", help="output image")
    parser.add_argument("--dpi", type=int, default=130)
    args = parser.parse_args()
    points, polygons, cell_data = read_vtu(args.vtu)
    if "component" not in cell_data:
        raise SystemExit(f"{args.vtu}: no 'component' cell field (write it with cross_vault --vtk)")
    component = cell_data["component"]
    fig = plt.figure(figsize=(13, 6.2))
    draw(fig.add_subplot(1, 2, 1, projection="3d"), points, polygons, component, set(range(len(COMPONENTS))),
         elev=28, azim=-58, title="the specimen: vault, infill, piers, tie anchors, slab, steel frame")
    draw_plan(fig.add_subplot(1, 2, 2), points, polygons, component, {0, 1},
              title="plan from above: brick courses, staggered head joints, groins on x = ±y")
    present = sorted({int(c) for c in component})
    fig.legend(handles=[Patch(facecolor=COLOURS[c], edgecolor="#202020", label=COMPONENTS[c]) for c in present],
               loc="lower center", ncol=len(present), frameon=False)
    fig.tight_layout(rect=(0, 0.06, 1, 1))
    save_figure(fig, args.png, dpi=args.dpi)
    print(f"wrote {args.png}")


if __name__ == "__main__":
    main()
