#!/usr/bin/env python3
"""Plots one or several output folders of a study (`blockdem run MODEL.json --out DIR`, `cross_vault run --out DIR`),
for example one per damping scheme, knowing nothing of the structure: its monitor points and groups come from the
folder (history_<level>.csv, contacts_<level>.csv, report.json).

    python3 scripts/plot_study.py RUN_DIR [RUN_DIR ...] [--out DIR] [--points NAME,NAME] [--axis x|y|z]
                                  [--view x|y|z|six]

Writes into --out (default: the first RUN_DIR):
  histories.png        the displacement of each monitor point (or those of --points) along the excitation axis
                       (report.json input.axis, or --axis), relative to the table, in mm, against the time into the
                       level: one row per point, the levels side by side, one line per run; a collapse is marked;
  accelerations.png    the same for the (absolute) accelerations along the axis, m/s^2;
  damage_<level>.png   per level (damage_<level>_<run>.png with several runs): the contact points of
                       contacts_<level>.csv seen from +x, +y, +z, -x, -y, -z (--view six, the default) or from +x, +y
                       or +z alone, coloured by damage; the intact ones small, the damaged ones over them (the nearest
                       last), and the points made during the run (never bonded) small and grey under all the others;
  damage_by_group.png  the damaged contact points of each group at each level (report.json), one panel per run;
  pushover.png         the load multiplier against the largest displacement, for the runs with a pushover.csv.
Runs are labelled by their damping scheme, or by their folder when two share one. Runs on the built-in synthetic
record say so in every title. A level the run did not finish is drawn from its history_<level>.csv.part and has no
damage figure (its contacts_<level>.csv is written only when a level ends).

Needs numpy and matplotlib (Debian: python3-numpy python3-matplotlib; scripts/install-deps.sh --plots)."""
import argparse
import csv
import json
import os
import re
import sys
import textwrap

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))  # the modules beside this script
from python_modules import require_modules  # noqa: E402
require_modules(__file__)  # numpy and matplotlib, or the system Python that has them
import matplotlib  # noqa: E402
matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402
import numpy as np  # noqa: E402
from matplotlib.colors import LinearSegmentedColormap  # noqa: E402
from matplotlib.ticker import MaxNLocator  # noqa: E402
from figures import save_figure  # noqa: E402

SCRIPT = "plot_study.py"
COLOURS = {"none": "tab:green", "mass": "tab:blue", "maxwell": "tab:red", "stiffness": "tab:purple", "rayleigh": "tab:orange"}
NAMES = {"none": "noDamp", "mass": "MassProp", "maxwell": "Maxwell", "stiffness": "StiffProp", "rayleigh": "Rayleigh"}
NOT_GROUPS = ("total", "loose_blocks")  # the keys of a level's "damage" that are not groups
# A view from outside along an axis: (horizontal axis, vertical axis, depth axis, horizontal axis reversed, the nearest
# point has the largest depth coordinate). Seen from +x the viewer looks towards -x with z up, so y runs to the right.
VIEWS = {"+x": ("y", "z", "x", False, True), "-x": ("y", "z", "x", True, False),
         "+y": ("x", "z", "y", True, True), "-y": ("x", "z", "y", False, False),
         "+z": ("x", "y", "z", False, True), "-z": ("x", "y", "z", True, False)}
SIX = ["+x", "+y", "+z", "-x", "-y", "-z"]
# Damage from orange (slight) to dark purple (broken): plasma_r without its palest yellow, which vanishes on white and
# among the intact points (light grey); the points made during the run are a darker grey, smaller, under both.
CMAP = LinearSegmentedColormap.from_list("damage", plt.get_cmap("plasma_r")(np.linspace(0.22, 1, 256)))
INTACT_COLOUR, NEW_COLOUR = "0.82", "0.55"


def fail(message):
    sys.exit(f"{SCRIPT}: {message}")


def read_table(path, numeric_except=()):
    """The columns of a CSV file by name: numpy arrays (strings for `numeric_except`). Rows cut short (the last one
    of a .part file that is being written) are left out."""
    try:
        with open(path, newline="") as f:
            rows = list(csv.reader(f))
    except OSError as error:
        fail(f"cannot read {path}: {error.strerror or error}")
    if not rows:
        fail(f"{path} is empty (no header)")
    header, body = [name.strip() for name in rows[0]], [row for row in rows[1:] if len(row) == len(rows[0])]
    columns = {}
    for i, name in enumerate(header):
        values = [row[i] for row in body]
        try:
            columns[name] = np.array(values) if name in numeric_except else np.array(values, dtype=float)
        except ValueError:
            fail(f"{path}: column {name} is not numeric")
    return columns


def wrap(text, fig, fontsize=10):
    """Each line of `text` wrapped to the width of `fig` (about 0.56 fontsize points a character)."""
    chars = max(40, int(fig.get_figwidth() * 72 / (0.56 * fontsize)))
    return "\n".join(textwrap.fill(line, chars) for line in text.split("\n"))


def short_record(record):
    """A record's name without its folders: '/data/x/ElCentro.AT2 [4-6 s]' -> 'ElCentro.AT2 [4-6 s]'."""
    match = re.match(r"^(.*?)(\s*\[[^\]]*\])?$", record)
    return os.path.basename(match.group(1)) + (match.group(2) or "")


class Run:
    """One output folder: its report, and its histories and contact tables as they are asked for."""

    def __init__(self, folder):
        self.folder = folder
        path = os.path.join(folder, "report.json")
        if not os.path.isfile(path):
            fail(f"cannot read {path}: no such file (is {folder} the output folder of a study?)")
        try:
            with open(path) as f:
                self.report = json.load(f)
        except (OSError, ValueError) as error:
            fail(f"cannot read {path}: {error}")
        # A pushover's report (blockdem run with "analysis": "pushover"): its curve only.
        self.pushover = isinstance(self.report, dict) and "pushover" in self.report and "levels" not in self.report
        if self.pushover:
            push = self.report["pushover"]
            self.scheme, self.axis, self.synthetic, self.record = "pushover", push.get("axis", "x"), False, ""
            self.level_reports, self.levels, self.groups = {}, [], []
            self.model = self.report.get("model", {}).get("name", "")
            self.name = os.path.basename(os.path.normpath(folder))
            self.label, self.colour, self.title = self.name, None, self.name
            self._histories = {}
            return
        try:
            self.scheme = self.report["damping"]["scheme"]
            self.axis = self.report["input"]["axis"]
            self.synthetic = bool(self.report["input"]["synthetic"])
            self.record = self.report["input"]["record"]
            self.level_reports = {level["level_percent"]: level for level in self.report["levels"]}
        except (OSError, ValueError) as error:
            fail(f"cannot read {path}: {error}")
        except (KeyError, TypeError) as error:
            fail(f"{path}: not a study's report (no {error})")
        self.levels = list(self.level_reports)
        model = self.report.get("model", {})
        # Older reports (cross_vault before the generic study) have no "groups": the damage entries name them.
        first = self.report["levels"][0]["damage"] if self.report["levels"] else {}
        self.groups = model.get("groups") or [key for key in first if key not in NOT_GROUPS]
        self.model = model.get("name", "")
        self.name = os.path.basename(os.path.normpath(folder))
        self.label, self.colour = self.name, None  # set by label_runs
        self.title = f"{self.name} ({NAMES.get(self.scheme, self.scheme)})"  # folder and damping scheme, for titles
        self._histories = {}

    def history(self, level):
        """The columns of history_<level>.csv (or of its .part: a level the run did not finish), and whether partial."""
        if level not in self._histories:
            path = os.path.join(self.folder, f"history_{level:g}.csv")
            partial = not os.path.exists(path) and os.path.exists(path + ".part")
            self._histories[level] = (read_table(path + ".part" if partial else path), partial)
        return self._histories[level]

    def points(self):
        """The monitor points, in the order of the first level's history columns."""
        if not self.levels:
            return []
        return [name[:-3] for name in self.history(self.levels[0])[0] if name.endswith("_ux")]

    def contacts(self, level):
        return read_table(os.path.join(self.folder, f"contacts_{level:g}.csv"), ("component_a", "component_b"))


def label_runs(runs):
    """By damping scheme when every run has its own, else by folder (with its parent when two folders share a name)."""
    schemes = [r.scheme for r in runs]
    by_scheme = len(set(schemes)) == len(schemes)
    names = [r.name for r in runs]
    for k, r in enumerate(runs):
        if by_scheme:
            r.label, r.colour = NAMES.get(r.scheme, r.scheme), COLOURS.get(r.scheme, f"C{k}")
        else:
            tail = os.path.normpath(r.folder).split(os.sep)[-2:]
            r.label, r.colour = (r.name if names.count(r.name) == 1 else "/".join(tail)), f"C{k % 10}"


def input_note(runs):
    """What shook the runs, said in every title: the synthetic stand-in loudly, a record by its file name."""
    if all(r.pushover for r in runs):
        return "lambda g along " + ", ".join(sorted({r.axis for r in runs}))
    notes = {f"SYNTHETIC {re.sub(r'(?i)^synthetic ', '', short_record(r.record))}" if r.synthetic
             else short_record(r.record) for r in runs}
    return "; ".join(sorted(notes))


def model_note(runs):
    names = sorted({r.model for r in runs if r.model})
    return f"{', '.join(names)}: " if names else ""


def all_levels(runs):
    return sorted({level for r in runs for level in r.levels})


def finish(fig, path):
    """Saves `fig` as `path` (atomically) and prints the path."""
    save_figure(fig, path, dpi=110)
    plt.close(fig)
    print(path, flush=True)


def plot_histories(runs, points, axis, quantity, path):
    """One panel per monitor point (rows) and level (columns), one line per run: the displacement ('u', mm) or the
    acceleration ('a', m/s^2) along the excitation axis."""
    levels = all_levels(runs)
    scale, unit = (1e3, "mm") if quantity == "u" else (1.0, "m/s$^2$")
    fig, axes = plt.subplots(len(points), len(levels), squeeze=False, layout="constrained",
                             figsize=(max(4.6 * len(levels) + 0.6, 7), 2.3 * len(points) + 1.3))
    for row, point in enumerate(points):
        for col, level in enumerate(levels):
            ax, drawn, partial, axes_used, why = axes[row][col], False, False, set(), "no run has this level"
            for r in runs:
                if level not in r.levels:
                    continue
                a = axis or r.axis
                h, part = r.history(level)
                channel = f"{point}_{quantity}{a}"
                partial = partial or part
                axes_used.add(a)
                if channel not in h:
                    why = f"no {channel} in the history"
                    continue
                if not len(h["time"]):
                    why = "no sample written yet"
                    continue
                ax.plot(h["time"], scale * h[channel], lw=0.8, color=r.colour, label=r.label)
                drawn = True
                collapse = r.level_reports[level].get("collapse")
                if collapse:
                    t = collapse["time_into_level_s"]
                    ax.axvline(t, color=r.colour, ls="--", lw=1)
                    moved = 1e3 * collapse.get("displacement_m", float("nan"))  # how far in all, not along the axis
                    ax.text(t, 0.96, f"collapse: {collapse['monitor_point']} moved {moved:.0f} mm ", color=r.colour,
                            fontsize=7, va="top", ha="right", rotation=90, transform=ax.get_xaxis_transform(),
                            bbox=dict(fc="white", ec="none", alpha=0.75, pad=1))
            title = f"{point}-{'/'.join(sorted(axes_used)) or axis or '?'}, level {level:g} %"
            ax.set_title(title + (" (unfinished)" if partial else ""), fontsize=9)
            if not drawn:
                ax.text(0.5, 0.5, why, ha="center", va="center", color="0.5", transform=ax.transAxes)
            ax.grid(alpha=0.3)
            if col == 0:
                ax.set_ylabel(f"{quantity} [{unit}]")
            if row == len(points) - 1:
                ax.set_xlabel("time into the level [s]")
    handles = {}
    for ax in axes.flat:
        for handle, label in zip(*ax.get_legend_handles_labels()):
            handles.setdefault(label, handle)
    if handles:  # below the panels, in a strip kept free for it
        ncol = max(1, min(len(handles), int(fig.get_figwidth() / 2.8)))
        strip = (0.1 + 0.22 * -(-len(handles) // ncol)) / fig.get_figheight()
        fig.get_layout_engine().set(rect=(0, strip, 1, 1 - strip))
        fig.legend(handles.values(), handles.keys(), loc="lower center", fontsize=8, ncol=ncol, frameon=False)
    along = "/".join(sorted({axis or r.axis for r in runs}))
    excitation = "/".join(sorted({r.axis for r in runs}))
    along += " (the excitation axis)" if along == excitation else f" (the excitation axis is {excitation})"
    what = (f"Displacement along {along}, relative to the table" if quantity == "u"
            else f"Acceleration along {along}, absolute")
    fig.suptitle(wrap(f"{model_note(runs)}{what}\n({input_note(runs)})", fig), fontsize=10, x=0.02, ha="left")
    finish(fig, path)


def draw_view(ax, c, view, size):
    """The contact points seen from `view`: never bonded (grey) first, then the intact, then the damaged ones, each
    layer from the farthest to the nearest, so that only a nearer damaged point can hide a damaged point."""
    h, v, depth, reverse, nearest_max = VIEWS[view]
    key = c[depth] if nearest_max else -c[depth]
    new = c["never_bonded"] > 0 if "never_bonded" in c else np.zeros(len(key), dtype=bool)
    damaged = ~new & (c["damage"] > 0)
    layers = ((new, dict(s=0.4 * size, color=NEW_COLOUR)), (~new & ~damaged, dict(s=0.6 * size, color=INTACT_COLOUR)),
              (damaged, None))
    mappable = None
    for mask, style in layers:
        index = np.flatnonzero(mask)
        index = index[np.argsort(key[index], kind="stable")]
        if style is None:
            mappable = ax.scatter(c[h][index], c[v][index], c=c["damage"][index], s=1.5 * size, cmap=CMAP,
                                  vmin=0, vmax=1, linewidths=0)
        else:
            ax.scatter(c[h][index], c[v][index], linewidths=0, **style)
    ax.set_aspect("equal")
    if reverse:
        ax.invert_xaxis()
    ax.set_xlabel(f"{h} [m]", fontsize=8)
    ax.set_ylabel(f"{v} [m]", fontsize=8)
    ax.tick_params(labelsize=7)
    right = f"{'-' if reverse else '+'}{h}"
    ax.set_title(f"from {view} ({right} to the right, +{v} up)", fontsize=9)
    return mappable


def plot_damage(run, level, views, path):
    c = run.contacts(level)
    n = len(c["x"])
    size = float(np.clip((30000.0 if len(views) == 6 else 60000.0) / max(n, 1), 1.5, 15))  # smaller as they are more
    columns = 3 if len(views) == 6 else 1
    rows = len(views) // columns
    width = 4.6 * columns + 1.2 + (2.0 if columns == 1 else 0)  # one view: room for the title
    fig, axes = plt.subplots(rows, columns, figsize=(width, 3.6 * rows + 1.0), squeeze=False, layout="constrained")
    mappable = None
    for ax, view in zip(axes.flat, views):
        mappable = draw_view(ax, c, view, size) or mappable
    bar = fig.colorbar(mappable or plt.cm.ScalarMappable(plt.Normalize(0, 1), CMAP), ax=axes, shrink=0.6,
                       label="contact point damage d")
    marks = [plt.Line2D([], [], ls="", marker="o", ms=4, color=INTACT_COLOUR, label="intact (d = 0)"),
             plt.Line2D([], [], ls="", marker="o", ms=3, color=NEW_COLOUR,
                        label="made during\nthe run (never\nbonded)")]
    bar.ax.legend(handles=marks, loc="upper right", bbox_to_anchor=(1.0, -0.04), fontsize=8, frameon=False)
    report = run.level_reports[level]
    total = report["damage"]["total"]
    title = (f"{model_note([run])}level {level:g} %\n{total['damaged']} of {total['contact_points']} contact points "
             f"damaged, {total.get('new_contacts', 0)} made during the run")
    collapse = report.get("collapse")
    if collapse:
        title += f"; collapsed {collapse['time_into_level_s']:.2f} s into the level ({collapse['monitor_point']})"
    fig.suptitle(wrap(f"{title}\n({run.title}; {input_note([run])})", fig), fontsize=10)
    finish(fig, path)


def plot_damage_by_group(runs, path):
    """Bars of the damaged contact points of each group (clusters), one bar per level; a contact point between two
    groups counts for both."""
    fig, axes = plt.subplots(len(runs), 1, figsize=(max(7.0, 1.1 * max(len(r.groups) for r in runs) + 2),
                                                    3.2 * len(runs) + 1.0), squeeze=False)
    for ax, r in zip(axes[:, 0], runs):
        x = np.arange(len(r.groups))
        width = 0.8 / max(len(r.levels), 1)
        shades = plt.get_cmap("viridis")(np.linspace(0.15, 0.85, max(len(r.levels), 1)))
        for k, level in enumerate(r.levels):
            damage = r.level_reports[level]["damage"]
            counts = [damage.get(g, {}).get("damaged", 0) for g in r.groups]
            bars = ax.bar(x + (k - (len(r.levels) - 1) / 2) * width, counts, width, color=shades[k],
                          label=f"{level:g} % ({damage['total']['damaged']} in all)" +
                          (", unfinished" if r.level_reports[level].get("interrupted") else ""))
            ax.bar_label(bars, fontsize=7, padding=1)
        ax.set_xticks(x)
        ax.set_xticklabels(r.groups, fontsize=8)
        ax.set_ylabel("damaged contact points")
        ax.yaxis.set_major_locator(MaxNLocator(integer=True))
        ax.set_title(r.title, fontsize=9)
        ax.grid(axis="y", alpha=0.3)
        ax.margins(y=0.15)
        ax.legend(fontsize=8, title="level", title_fontsize=8)
    fig.suptitle(wrap(f"{model_note(runs)}damaged contact points by group (one between two groups counts in both)\n"
                      f"({input_note(runs)})", fig), fontsize=10)
    fig.tight_layout()
    finish(fig, path)


def plot_pushover(runs, path):
    """The load multiplier against the largest displacement, for the runs with a pushover.csv (none: no figure)."""
    curves = [(r, os.path.join(r.folder, "pushover.csv")) for r in runs]
    curves = [(r, read_table(p)) for r, p in curves if os.path.exists(p)]
    if not curves:
        return
    fig, ax = plt.subplots(figsize=(7, 4.8))
    for r, c in curves:
        for column in ("lambda", "max_displacement_m"):
            if column not in c:
                fail(f"{os.path.join(r.folder, 'pushover.csv')}: no column {column}")
        ax.plot(1e3 * c["max_displacement_m"], c["lambda"], "-o", ms=3, color=r.colour, label=r.label)
        if "stands" in c and np.any(c["stands"] == 0):
            fallen = c["stands"] == 0
            ax.plot(1e3 * c["max_displacement_m"][fallen], c["lambda"][fallen], "x", ms=8, color="k",
                    label="does not stand" if r is curves[0][0] else None)
    ax.set_xlabel("largest displacement [mm]")
    ax.set_ylabel("load multiplier $\\lambda$")
    ax.grid(alpha=0.3)
    ax.legend(fontsize=8)
    ax.set_title(wrap(f"{model_note(runs)}pushover\n({input_note(runs)})", fig), fontsize=10)
    fig.tight_layout()
    finish(fig, path)


def main():
    parser = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    parser.add_argument("runs", nargs="+", help="output folders of `blockdem run` or `cross_vault run`")
    parser.add_argument("--out", help="folder for the PNGs (default: the first run's)")
    parser.add_argument("--points", help="monitor points to plot, comma-separated (default: all)")
    parser.add_argument("--axis", choices=("x", "y", "z"), help="component plotted (default: the excitation axis)")
    parser.add_argument("--view", choices=("x", "y", "z", "six"), default="six",
                        help="damage maps seen from +x, +y, +z, or from all six sides (default)")
    args = parser.parse_args()
    runs = [Run(folder) for folder in args.runs]
    pushed = [r for r in runs if r.pushover]
    if pushed:  # pushovers: their curve, and nothing else of theirs
        out = args.out or args.runs[0]
        os.makedirs(out, exist_ok=True)
        label_runs(pushed)
        plot_pushover(pushed, os.path.join(out, "pushover.png"))
        runs = [r for r in runs if not r.pushover]
        if not runs:
            return
    for r in runs:
        if not r.levels:
            print(f"{SCRIPT}: {r.folder}: report.json lists no level: left out", file=sys.stderr)
    runs = [r for r in runs if r.levels]
    if not runs:
        fail("no run has a level yet (report.json lists none)")
    label_runs(runs)
    for r in runs:  # every file a level needs, before any figure is written
        for level in r.levels:
            history = os.path.join(r.folder, f"history_{level:g}.csv")
            if not os.path.exists(history) and not os.path.exists(history + ".part"):
                fail(f"cannot read {history}: no such file (nor {os.path.basename(history)}.part)")
            contacts = os.path.join(r.folder, f"contacts_{level:g}.csv")
            if not r.level_reports[level].get("interrupted") and not os.path.exists(contacts):
                fail(f"cannot read {contacts}: no such file")
    points = []
    for r in runs:
        points += [p for p in r.points() if p not in points]
    if args.points:
        asked = [p.strip() for p in args.points.split(",") if p.strip()]
        unknown = [p for p in asked if p not in points]
        if unknown:
            fail(f"no monitor point {', '.join(unknown)} in the histories (they have {', '.join(points)})")
        points = asked
    if not points:
        fail("the histories have no monitor point (no <name>_ux column)")
    out = args.out or args.runs[0]
    os.makedirs(out, exist_ok=True)
    if any(len(r.history(level)[0].get("time", [])) for r in runs for level in r.levels):
        plot_histories(runs, points, args.axis, "u", os.path.join(out, "histories.png"))
        plot_histories(runs, points, args.axis, "a", os.path.join(out, "accelerations.png"))
    else:
        print(f"{SCRIPT}: the histories have no sample yet: no histories.png, accelerations.png", file=sys.stderr)
    views = SIX if args.view == "six" else [f"+{args.view}"]
    for r in runs:
        for level in r.levels:
            if r.level_reports[level].get("interrupted"):
                print(f"{SCRIPT}: {r.folder}: level {level:g} % is unfinished, no contacts_{level:g}.csv: no damage "
                      "figure", file=sys.stderr)
                continue
            name = f"damage_{level:g}" + (f"_{re.sub(r'[^A-Za-z0-9._-]+', '_', r.label)}" if len(runs) > 1 else "")
            plot_damage(r, level, views, os.path.join(out, name + ".png"))
    plot_damage_by_group(runs, os.path.join(out, "damage_by_group.png"))
    plot_pushover(runs, os.path.join(out, "pushover.png"))


if __name__ == "__main__":
    main()
