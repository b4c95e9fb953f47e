#!/usr/bin/env python3
"""Plots one or several runs of `cross_vault run` (for example one per damping scheme) side by side, like the paper's
figures: the OC1-y displacement per level (Fig. 14), OC2-y and OC4-y (Fig. 16), the ACC18-y acceleration (Fig. 18),
the damage of the vault's joints per level in plan view (Fig. 17) and the timing table (Table 4).

    python3 scripts/plot_vault.py RUN_DIR [RUN_DIR ...] [--out DIR] [--measured-level L FILE.csv]

Writes into --out (default: the first RUN_DIR) displacement_oc1.png, displacement_oc2_oc4.png, acceleration_acc18.png,
damage_map.png and timing.png. Runs on the built-in synthetic record say so in every title.

Needs numpy and matplotlib (Debian: python3-numpy python3-matplotlib; scripts/install-deps.sh --plots)."""
import argparse
import json
import os
import sys
from figures import save_figure
from python_modules import require_modules

require_modules(__file__)  # numpy and matplotlib, or the system Python that has them
import matplotlib  # noqa: E402
matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402
import numpy as np

COLOURS = {"none": "tab:green", "mass": "tab:blue", "maxwell": "tab:red", "stiffness": "tab:purple", "rayleigh": "tab:orange"}
GROUND_FRAME_COLOURS = {"mass": "tab:cyan", "rayleigh": "tab:brown"}
NAMES = {"none": "noDamp", "mass": "MassProp", "maxwell": "Maxwell", "stiffness": "StiffProp", "rayleigh": "Rayleigh"}


class Run:
    def __init__(self, folder):
        self.folder = folder
        path = os.path.join(folder, "report.json")
        try:
            with open(path) as f:
                self.report = json.load(f)
        except (OSError, ValueError) as error:
            sys.exit(f"plot_vault.py: cannot read {path}: {error}")
        self.scheme = self.report["damping"]["scheme"]
        self.label = NAMES.get(self.scheme, self.scheme)
        self.colour = COLOURS.get(self.scheme)
        # The frame of a mass-proportional term (docs/damping.md): the table's, or the ground's as in 3DEC.
        frame = self.report["damping"].get("frame", "")
        if frame:
            self.label += f" ({frame} frame)"
            if frame == "absolute":
                self.colour = GROUND_FRAME_COLOURS.get(self.scheme, self.colour)
        self.synthetic = self.report["input"]["synthetic"]
        self.levels = [level["level_percent"] for level in self.report["levels"]]

    def level_name(self, level):
        return f"{level:g}"

    def history(self, level):
        path = os.path.join(self.folder, f"history_{self.level_name(level)}.csv")
        if not os.path.exists(path) and os.path.exists(path + ".part"):
            path += ".part"  # a level the run did not finish (interrupted, or stopped by the run guard)
        try:
            with open(path) as f:
                header = f.readline().strip().split(",")
            data = np.loadtxt(path, delimiter=",", skiprows=1, ndmin=2)
        except (OSError, ValueError) as error:
            sys.exit(f"plot_vault.py: cannot read {path}: {error}")
        return {name: data[:, i] for i, name in enumerate(header)}

    def contacts(self, level):
        path = os.path.join(self.folder, f"contacts_{self.level_name(level)}.csv")
        try:
            with open(path) as f:
                header = f.readline().strip().split(",")
            rows = [line.strip().split(",") for line in open(path).readlines()[1:]]
        except OSError as error:
            sys.exit(f"plot_vault.py: cannot read {path}: {error}")
        columns = {name: [row[i] for row in rows] for i, name in enumerate(header)}
        numeric = {k: np.array(v, dtype=float) for k, v in columns.items() if k not in ("component_a", "component_b")}
        numeric["component_a"] = np.array(columns["component_a"])
        numeric["component_b"] = np.array(columns["component_b"])
        return numeric


def input_note(runs):
    notes = {("SYNTHETIC AQA75 stand-in, not the AQA recording" if r.synthetic else r.report["input"]["record"]) for r in runs}
    return "; ".join(sorted(notes))


def all_levels(runs):
    levels = []
    for r in runs:
        for level in r.levels:
            if level not in levels:
                levels.append(level)
    return levels


def plot_channels(runs, channels, ylabel, scale, path, title):
    levels = all_levels(runs)
    fig, axes = plt.subplots(len(channels), len(levels), figsize=(4.5 * len(levels), 2.8 * len(channels)), squeeze=False)
    for row, channel in enumerate(channels):
        for col, level in enumerate(levels):
            ax = axes[row][col]
            for r in runs:
                if level not in r.levels:
                    continue
                h = r.history(level)
                if channel not in h:
                    continue
                ax.plot(h["time"], scale * h[channel], lw=0.8, color=r.colour, label=r.label)
            ax.set_title(f"{channel.replace('_u', '-').replace('_a', '-')}, level {level:g} %", fontsize=9)
            ax.grid(alpha=0.3)
            if col == 0:
                ax.set_ylabel(ylabel)
            if row == len(channels) - 1:
                ax.set_xlabel("time [s]")
    axes[0][0].legend(fontsize=8)
    fig.suptitle(f"{title}\n({input_note(runs)})", fontsize=10)
    fig.tight_layout()
    save_figure(fig, path, dpi=110)
    plt.close(fig)
    print(path)


def plot_damage(runs, path):
    levels = all_levels(runs)
    fig, axes = plt.subplots(len(runs), len(levels), figsize=(4.6 * len(levels) + 1.2, 4.6 * len(runs) + 0.8), squeeze=False)
    for row, r in enumerate(runs):
        for col, level in enumerate(levels):
            ax = axes[row][col]
            ax.set_aspect("equal")
            ax.set_xticks([])
            ax.set_yticks([])
            if level not in r.levels:
                ax.set_visible(False)
                continue
            c = r.contacts(level)
            masonry = np.isin(c["component_a"], ["vault", "infill"]) & np.isin(c["component_b"], ["vault", "infill"])
            order = np.argsort(c["z"][masonry])  # the extrados (highest) drawn last, as seen from above
            x, y, d = c["x"][masonry][order], c["y"][masonry][order], c["damage"][masonry][order]
            # Contact points made during the run (never bonded: no tension, no cohesion): a joint that broke,
            # opened and closed again, or blocks that touch anew. Older outputs have no such column.
            new = c["never_bonded"][masonry][order] > 0 if "never_bonded" in c else np.zeros_like(d, dtype=bool)
            intact = (d <= 0) & ~new
            ax.scatter(x[intact], y[intact], s=0.3, color="0.85", linewidths=0)
            ax.scatter(x[new], y[new], s=2, color="0.35", linewidths=0,
                       label="made during the run (no bond)" if row == 0 and col == 0 else None)
            damaged_mask = (d > 0) & ~new
            sc = ax.scatter(x[damaged_mask], y[damaged_mask], c=d[damaged_mask], s=3, linewidths=0, cmap="plasma_r", vmin=0, vmax=1)
            damaged = int(np.count_nonzero(damaged_mask))
            ax.set_title(f"{r.label} {level:g} %: {damaged} damaged, {int(np.count_nonzero(new))} new CPs", fontsize=9)
    fig.colorbar(sc, ax=axes, shrink=0.6, label="joint damage d")
    if any(ax.get_legend_handles_labels()[0] for ax in axes.flat):
        fig.legend(loc="lower center", fontsize=8, markerscale=4, frameon=False)
    fig.suptitle(f"Joint damage, vault and infill, plan view (x east, y north)\n({input_note(runs)})", fontsize=9)
    save_figure(fig, path, dpi=110)
    plt.close(fig)
    print(path)


def plot_timing(runs, path):
    levels = all_levels(runs)
    fig, ax = plt.subplots(figsize=(7, 0.6 + 0.45 * (len(runs) + 1)))
    ax.axis("off")
    header = ["Model", "dt [s]"] + [f"{level:g} % [min]" for level in levels] + ["Total [h]", "mass added [%]"]
    rows = []
    for r in runs:
        minutes = {level["level_percent"]: level["wall_seconds"] / 60 for level in r.report["levels"]}
        total = sum(minutes.values()) / 60
        rows.append([r.label, f"{r.report['timestep']['dt_s']:.3e}"] +
                    [f"{minutes[level]:.2f}" if level in minutes else "-" for level in levels] +
                    [f"{total:.3f}", f"{r.report['timestep']['density_scaling_mass_increase_percent']:.2f}"])
    table = ax.table(cellText=rows, colLabels=header, loc="center")
    table.auto_set_font_size(False)
    table.set_fontsize(9)
    table.scale(1, 1.4)
    ax.set_title("Wall time of the incremental analysis (the paper's Table 4)", fontsize=10)
    fig.tight_layout()
    save_figure(fig, path, dpi=110)
    plt.close(fig)
    print(path)


def main():
    parser = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    parser.add_argument("runs", nargs="+", help="output folders of cross_vault run")
    parser.add_argument("--out", help="folder for the PNGs (default: the first run's)")
    args = parser.parse_args()
    runs = [Run(folder) for folder in args.runs]
    if not any(r.levels for r in runs):
        sys.exit("plot_vault.py: no run has a finished level yet")
    out = args.out or args.runs[0]
    os.makedirs(out, exist_ok=True)
    plot_channels(runs, ["OC1_uy"], "displacement [mm]", 1e3, os.path.join(out, "displacement_oc1.png"),
                  "Crown displacement OC1-y relative to the table (Fig. 14)")
    plot_channels(runs, ["OC2_uy", "OC4_uy"], "displacement [mm]", 1e3, os.path.join(out, "displacement_oc2_oc4.png"),
                  "Displacements OC2-y and OC4-y (Fig. 16)")
    plot_channels(runs, ["ACC18_ay"], "acceleration [m/s$^2$]", 1.0, os.path.join(out, "acceleration_acc18.png"),
                  "Crown acceleration ACC18-y, centred differences of velocity (Fig. 18)")
    plot_damage(runs, os.path.join(out, "damage_map.png"))
    plot_timing(runs, os.path.join(out, "timing.png"))


if __name__ == "__main__":
    main()
