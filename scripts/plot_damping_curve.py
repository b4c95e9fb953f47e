#!/usr/bin/env python3
"""Plots the damping curves written by `maxwell_fit --curve FILE.csv` like the paper's Fig. 10-12: damping ratio of
the Maxwell fit, mass-proportional and Rayleigh damping against frequency, and |M_T| of the Maxwell branches.

    python3 scripts/plot_damping_curve.py curve.csv [--out curve.png] [--band 1 40]

Needs numpy and matplotlib (Debian: python3-numpy python3-matplotlib; scripts/install-deps.sh --plots)."""
import argparse
import sys
from figures import save_figure
from python_modules import require_modules

require_modules(__file__)  # numpy and matplotlib, or the system Python that has them
import matplotlib  # noqa: E402
matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402
import numpy as np

COLUMNS = ["frequency_hz", "target", "maxwell", "mass_proportional", "rayleigh", "modulus"]


def main():
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("csv", help="the file written by maxwell_fit --curve")
    parser.add_argument("--out", help="PNG to write (default: CSV name with .png)")
    parser.add_argument("--band", nargs=2, type=float, metavar=("F_LB", "F_UB"), help="shade this band (Hz)")
    args = parser.parse_args()

    try:
        with open(args.csv) as f:
            header = f.readline().strip().split(",")
        data = np.loadtxt(args.csv, delimiter=",", skiprows=1, ndmin=2)
    except (OSError, ValueError) as error:
        sys.exit(f"plot_damping_curve.py: cannot read {args.csv}: {error}")
    if header != COLUMNS:
        sys.exit(f"plot_damping_curve.py: {args.csv}: expected the columns {','.join(COLUMNS)}, got {','.join(header)}")
    c = {name: data[:, i] for i, name in enumerate(COLUMNS)}

    fig, (ax1, ax2) = plt.subplots(1, 2, figsize=(11, 4.2))
    ax1.semilogx(c["frequency_hz"], 100 * c["maxwell"], "r-", lw=2, label="Maxwell (eq. 19)")
    ax1.semilogx(c["frequency_hz"], 100 * c["mass_proportional"], "b--", label="mass-proportional")
    ax1.semilogx(c["frequency_hz"], 100 * c["rayleigh"], "g-.", label="Rayleigh (eq. 10)")
    ax1.semilogx(c["frequency_hz"], 100 * c["target"], "k:", label="target")
    ax1.set_ylim(0, 3 * 100 * c["target"].max())
    ax1.set_xlabel("frequency [Hz]")
    ax1.set_ylabel("damping ratio [%]")
    ax2.semilogx(c["frequency_hz"], c["modulus"], "r-", lw=2)
    ax2.set_xlabel("frequency [Hz]")
    ax2.set_ylabel("|M_T| (eq. 18-19)")
    for ax in (ax1, ax2):
        if args.band:
            ax.axvspan(args.band[0], args.band[1], color="0.92", zorder=0)
        ax.grid(True, which="both", alpha=0.3)
    ax1.legend(loc="upper right")
    ax2.set_title(f"max |M_T| = {c['modulus'].max():.3f}")
    fig.tight_layout()
    out = args.out or args.csv.rsplit(".", 1)[0] + ".png"
    save_figure(fig, out, dpi=110)
    print(f"wrote {out}")


if __name__ == "__main__":
    main()
