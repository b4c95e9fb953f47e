#!/usr/bin/env python3
"""Plots the stress-displacement curves written by `joint_test --csv FILE.csv` (one panel per file): the driven
stress against its displacement (tension against opening, compression against closure, shear against slip), with the
combined damage on a second axis.

    python3 scripts/plot_joint_curve.py tension.csv [cyclic_shear.csv ...] [--out joint.png]

Needs numpy and matplotlib (Debian: python3-numpy python3-matplotlib; scripts/install-deps.sh --plots)."""
import argparse
import math
import sys
from figures import save_figure
from python_modules import require_modules

require_modules(__file__)  # numpy and matplotlib, or the system Python that has them
import matplotlib  # noqa: E402
matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402
import numpy as np

COLUMNS = ["step", "opening_m", "slip_m", "normal_stress_pa", "shear_stress_pa", "normal_force_n", "shear_force_n",
           "damage", "dissipated_j_m2", "stored_j_m2"]


def read(path):
    """Returns the path name from the '# joint_test path=...' line, and the columns."""
    try:
        with open(path) as f:
            comment = f.readline().strip()
            header = f.readline().strip().split(",")
        data = np.loadtxt(path, delimiter=",", skiprows=2, ndmin=2)
    except (OSError, ValueError) as error:
        sys.exit(f"plot_joint_curve.py: cannot read {path}: {error}")
    if not comment.startswith("# joint_test") or header != COLUMNS:
        sys.exit(f"plot_joint_curve.py: {path}: not a joint_test --csv file (expected '# joint_test ...' and the "
                 f"columns {','.join(COLUMNS)})")
    fields = dict(item.split("=", 1) for item in comment.split()[2:] if "=" in item)
    return fields, {name: data[:, i] for i, name in enumerate(COLUMNS)}


def panel(ax, fields, c):
    path = fields.get("path", "?")
    if "shear" in path:
        x, y = 1e3 * c["slip_m"], 1e-6 * c["shear_stress_pa"]
        xlabel, ylabel = "slip [mm]", "shear stress [MPa]"
        title = f"{path}, normal stress {1e-6 * float(fields.get('normal_stress_pa', 'nan')):g} MPa"
    elif "compression" in path:
        x, y = -1e3 * c["opening_m"], 1e-6 * c["normal_stress_pa"]
        xlabel, ylabel = "closure [mm]", "compressive stress [MPa]"
        title = path
    else:
        x, y = 1e3 * c["opening_m"], -1e-6 * c["normal_stress_pa"]
        xlabel, ylabel = "opening [mm]", "tensile stress [MPa]"
        title = path
    ax.plot(x, y, "b-", lw=1.4)
    ax.axhline(0, color="0.6", lw=0.6)
    ax.set_xlabel(xlabel)
    ax.set_ylabel(ylabel, color="b")
    dissipated = c["dissipated_j_m2"][-1]
    ax.set_title(f"{title}: dissipated {dissipated:.4g} J/m$^2$", fontsize=10)
    ax.grid(True, alpha=0.3)
    twin = ax.twinx()
    twin.plot(x, c["damage"], "r--", lw=1)
    twin.set_ylim(-0.02, 1.05)
    twin.set_ylabel("damage d", color="r")


def main():
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("csv", nargs="+", help="files written by joint_test --csv")
    parser.add_argument("--out", help="PNG to write (default: the first CSV's name with .png)")
    args = parser.parse_args()
    curves = [read(path) for path in args.csv]
    columns = 1 if len(curves) == 1 else 2
    rows = math.ceil(len(curves) / columns)
    fig, axes = plt.subplots(rows, columns, figsize=(5.6 * columns, 3.6 * rows), squeeze=False)
    for ax, (fields, c) in zip(axes.flat, curves):
        panel(ax, fields, c)
    for ax in list(axes.flat)[len(curves):]:
        ax.set_visible(False)
    fig.tight_layout()
    out = args.out or args.csv[0].rsplit(".", 1)[0] + ".png"
    save_figure(fig, out, dpi=90)
    print(f"wrote {out}")


if __name__ == "__main__":
    main()
