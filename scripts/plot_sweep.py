#!/usr/bin/env python3
"""Plots the summary of `cross_vault sweep` (OUT/summary.csv, one row per case) like the paper's Sect. 5: the
sensitivity of the peak response to the damping parameters (Fig. 13, Table 3) and, for sweeps whose cases each run
one level, incremental dynamic analysis (IDA) curves over the records.

    python3 scripts/plot_sweep.py OUT [--out-dir DIR] [--show-all]

OUT is the sweep's output folder or its summary.csv. Writes into OUT (or --out-dir):
  sweep_table3.png    best cell of the grid (smallest |signed peak bias|) and the selected setting (MP: 4 % @ 7.5 Hz,
                      Maxwell: 3 % on [1, 40] Hz) per channel, like Table 3; without measured channels, the peak
                      response of every cell instead;
  sweep_heatmaps.png  signed peak bias (or, without measured channels, the absolute peak response) over zeta x centre
                      frequency (MassProp) and zeta x band (Maxwell), for OC1-y and ACC18-y, like Fig. 13;
  sweep_ida.png       peak |OC1-y| against the intensity measure per record, with the median and the 16 %/84 %
                      fractiles across records, one panel per damping setting (only when cases each run one level).
Only cases with status `done` are plotted; the others are listed. A figure the data do not allow is skipped with the
reason. --show-all prints every case's row too and lists every case that is not done (default: the first 10 per
status). Record `aqa75` is the built-in SYNTHETIC AQA75 stand-in, and the figures say so.

Needs numpy and matplotlib (Debian: python3-numpy python3-matplotlib; scripts/install-deps.sh --plots)."""
import argparse
import os
import sys
import textwrap

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))  # the modules beside this script
from python_modules import require_modules  # noqa: E402
require_modules(__file__)  # numpy and matplotlib, or the system Python that has them
import matplotlib  # noqa: E402
matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402
from matplotlib.patches import Rectangle
import numpy as np

from figures import save_figure
from sweep_summary import (ACC18, NAMES, OC1, SELECTED, SYNTHETIC_TAG, fail, grids, groups_text, is_selected,
                           key_number, list_unfinished, percent, print_all, read_summary, record_text,
                           setting_text, summary_path)


# ----------------------------------------------------------------------------------------------------- labels


def wrap(text, width_inches, fontsize=9):
    """Each line of `text` wrapped to a figure `width_inches` wide (about 0.55 fontsize points a character)."""
    chars = max(30, int(width_inches * 72 / (0.56 * fontsize)))
    return "\n".join(textwrap.fill(line, chars) for line in text.split("\n"))


# ----------------------------------------------------------------------------------------------------- table 3


def table3(groups, measured, path):
    several = len(groups) > 1
    rows = []
    if measured:
        header = (["Case group"] if several else []) + ["Channel", "Scheme", "Best cell (grid)", "Selected (validation)"]
        for (kinematics, record), by_scheme in groups.items():
            for scheme, grid in by_scheme.items():
                for channel in (ACC18, OC1):
                    best = grid.best(channel)
                    best_text = f"{grid.cell_label(best)}: {best[channel.bias]:.1f}" if best else "no bias"
                    chosen = grid.selected()
                    if chosen is None:
                        chosen_text = "not in the sweep"
                    elif isinstance(chosen, str):
                        chosen_text = f"{cell_name(scheme)}: {chosen}"
                    elif chosen[channel.bias] is None:
                        chosen_text = f"{grid.cell_label(chosen)}: no bias"
                    else:
                        chosen_text = f"{grid.cell_label(chosen)}: {chosen[channel.bias]:.1f}"
                    rows.append(([f"{kinematics}, {record}"] if several else []) +
                                [channel.name, grid.scheme_label(), best_text, chosen_text])
        title = "Sensitivity analysis: best cells vs. selected settings (signed peak bias, %) - Table 3 analog"
    else:
        header = (["Case group"] if several else []) + ["Scheme", "Cell", f"|peak| {OC1.name} (mm)",
                                                        f"|peak| {ACC18.name} (m/s²)", ""]
        for (kinematics, record), by_scheme in groups.items():
            for scheme, grid in by_scheme.items():
                keys = [(r, k) for r in grid.rows for k in grid.columns]
                for key in keys:
                    c = grid.cell.get(key)
                    group = [f"{kinematics}, {record}"] if several else []
                    if c is None:
                        status = grid.status.get(key)
                        if status is None:
                            continue
                        zeta, column = key
                        rows.append(group + [grid.scheme_label(), f"{percent(zeta)} {grid.column_label(column)}".replace("\n", " "),
                                             "-", "-", status])
                        continue
                    p1, p2 = c.peak(OC1), c.peak(ACC18)
                    rows.append(group + [grid.scheme_label(), grid.cell_label(c),
                                         f"{p1:.2f}" if p1 is not None else "-", f"{p2:.2f}" if p2 is not None else "-",
                                         "selected" if is_selected(c) else ""])
        title = ("Peak response per cell (no measured channels in the summary: no bias, no best cell) - Table 3 analog")
    if not rows:
        print("no mass or maxwell cases: no Table 3 analog")
        return None
    # the printed table
    print(title + ":")
    widths = [max(len(str(r[i])) for r in rows + [header]) for i in range(len(header))]
    for r in [header] + rows:
        print("  " + "  ".join(str(x).ljust(w) for x, w in zip(r, widths)).rstrip())
    notes = table_notes(groups)
    for note in notes:
        print(f"  ({note})")
    # the figure
    lines = [title, f"({groups_text(groups)})"] + notes
    width = max(0.082 * sum(widths) + 0.2 * len(header) + 0.5, 0.068 * max(len(x) for x in lines) + 0.4)
    height = 0.3 + 0.2 * len(lines) + 0.25 * (len(rows) + 1)
    fig = plt.figure(figsize=(width, height))
    ax = fig.add_axes((0.02, 0.02, 0.96, 1 - (0.1 + 0.2 * len(lines)) / height))
    ax.axis("off")
    table = ax.table(cellText=rows, colLabels=header, loc="upper center", cellLoc="left", colLoc="left")
    table.auto_set_font_size(False)
    table.set_fontsize(9)
    table.scale(1, 1.45)
    for (r, _), cell in table.get_celld().items():
        if r == 0:
            cell.set_text_props(weight="bold")
            cell.set_facecolor("0.9")
    table.auto_set_column_width(list(range(len(header))))
    fig.suptitle("\n".join(lines), fontsize=9, y=1 - 0.06 / height, va="top")
    save_figure(fig, path, dpi=110)
    plt.close(fig)
    return path


def cell_name(scheme):
    want = SELECTED[scheme]
    if scheme == "mass":
        return f"{percent(want['zeta'])} @ {want['frequency_hz']:g} Hz"
    return f"{percent(want['zeta'])} [{want['band'][0]:g}, {want['band'][1]:g}] Hz"


def table_notes(groups):
    notes = []
    levels = sorted({c["level_percent"] for by in groups.values() for g in by.values() for c in g.done()
                     if c["level_percent"] is not None})
    if len(levels) == 1:
        notes.append(f"peaks of level {levels[0]:g} %")
    if any(g.several_levels for by in groups.values() for g in by.values()):
        notes.append("cells with several levels: the highest shown")
    return notes


# ----------------------------------------------------------------------------------------------------- heat maps


def heatmaps(groups, measured, path):
    schemes = [s for s in ("mass", "maxwell") if any(s in by for by in groups.values())]
    panels = [(s, ch) for s in schemes for ch in (OC1, ACC18)]

    def value(c, channel):
        return c[channel.bias] if measured else c.peak(channel)

    # colour limits per channel, shared by the schemes and groups
    limits = {}
    for channel in (OC1, ACC18):
        values = [value(c, channel) for by in groups.values() for g in by.values() for c in g.done()]
        values = [v for v in values if v is not None]
        if measured:
            # symmetric about 0, and at least +-10 %: a bias of a few % stays pale even if it is the largest
            top = max(max((abs(v) for v in values), default=0.0), 10.0)
            limits[channel.name] = (-top, top)
        else:
            lo, hi = (min(values), max(values)) if values else (0.0, 1.0)
            if hi - lo < 1e-12 * max(1.0, abs(hi)):
                lo, hi = lo - 0.5 * max(abs(lo), 1e-3), hi + 0.5 * max(abs(hi), 1e-3)
            limits[channel.name] = (lo, hi)
    cmap = plt.get_cmap("RdBu_r" if measured else "viridis")

    ncols = {s: max(len(by[s].columns) for by in groups.values() if s in by) for s in schemes}
    nrows = max(len(g.rows) for by in groups.values() for g in by.values())
    widths = [1.6 + 1.05 * ncols[s] for s, _ in panels]
    height_row = 1.2 + 0.55 * nrows
    fig, axes = plt.subplots(len(groups), len(panels), figsize=(sum(widths) + 0.3, 1.4 + height_row * len(groups)),
                             squeeze=False, gridspec_kw={"width_ratios": widths}, layout="constrained")
    letter = iter("abcdefghijklmnopqrstuvwxyz")
    several_levels = False
    for row, ((kinematics, record), by_scheme) in enumerate(groups.items()):
        for col, (scheme, channel) in enumerate(panels):
            ax = axes[row][col]
            tag = next(letter, "")
            title = f"({tag}) {NAMES[scheme]}, {channel.name}" + (f"\n{kinematics}, {record}" if len(groups) > 1 else "")
            ax.set_title(title, fontsize=9)
            grid = by_scheme.get(scheme)
            if grid is None:
                ax.text(0.5, 0.5, f"no {scheme} cases", ha="center", va="center", transform=ax.transAxes, color="0.4")
                ax.set_xticks([])
                ax.set_yticks([])
                continue
            several_levels |= grid.several_levels
            data = np.full((len(grid.rows), len(grid.columns)), np.nan)
            for i, zeta in enumerate(grid.rows):
                for j, column in enumerate(grid.columns):
                    c = grid.cell.get((zeta, column))
                    v = value(c, channel) if c is not None else None
                    if v is not None:
                        data[i, j] = v
            lo, hi = limits[channel.name]
            mesh = ax.pcolormesh(np.arange(len(grid.columns) + 1), np.arange(len(grid.rows) + 1),
                                 np.ma.masked_invalid(data), cmap=cmap, vmin=lo, vmax=hi, edgecolors="white", linewidth=1.5)
            best = grid.best(channel) if measured else None
            for i, zeta in enumerate(grid.rows):
                for j, column in enumerate(grid.columns):
                    dark = False
                    if np.isfinite(data[i, j]):
                        v = data[i, j]
                        shade = cmap((v - lo) / (hi - lo))
                        dark = 0.299 * shade[0] + 0.587 * shade[1] + 0.114 * shade[2] < 0.5
                        text = f"{v:+.1f}" if measured else f"{v:.3g}"
                        ax.text(j + 0.5, i + 0.5, text, ha="center", va="center", fontsize=9,
                                color="white" if dark else "black")
                    else:
                        c = grid.cell.get((zeta, column))
                        status = grid.status.get((zeta, column), "no bias" if c is not None else "no case")
                        ax.add_patch(Rectangle((j, i), 1, 1, facecolor="0.88", edgecolor="0.55", hatch="///", lw=0))
                        ax.text(j + 0.5, i + 0.5, f"x\n{status}", ha="center", va="center", fontsize=8, color="0.2",
                                bbox={"boxstyle": "round,pad=0.15", "fc": "0.88", "ec": "none"})
                    c = grid.cell.get((zeta, column))
                    frame = "white" if dark else "black"  # the frames in the colour of the annotation
                    if c is not None and best is not None and c is best:
                        ax.add_patch(Rectangle((j + 0.04, i + 0.04), 0.92, 0.92, fill=False, ec=frame, lw=2.2))
                    if c is not None and is_selected(c) or c is None and any(
                            is_selected(x) and (key_number(x["zeta"]), grid.column(x)) == (zeta, column) for x in grid.cases):
                        ax.add_patch(Rectangle((j + 0.12, i + 0.12), 0.76, 0.76, fill=False, ec=frame, lw=1.3, ls="--"))
            ax.set_xlim(0, len(grid.columns))
            ax.set_ylim(0, len(grid.rows))
            ax.set_xticks(np.arange(len(grid.columns)) + 0.5, [grid.column_label(k) for k in grid.columns])
            ax.set_yticks(np.arange(len(grid.rows)) + 0.5, [percent(z) if z is not None else "default" for z in grid.rows])
            ax.tick_params(length=0)
            ax.set_xlabel("centre frequency $f_c$ (Hz)" if scheme == "mass" else "band (Hz)", fontsize=9)
            if col == 0 or panels[col - 1][0] != scheme:
                ax.set_ylabel(r"$\zeta^*$", fontsize=9)
            for side in ax.spines.values():
                side.set_visible(False)
            bar = fig.colorbar(mesh, ax=ax, shrink=0.9, pad=0.03, aspect=max(8, 6 * len(grid.rows)))
            bar.set_label("signed peak bias (%)" if measured else f"|peak| ({channel.unit})", fontsize=8)
            bar.ax.tick_params(labelsize=7)
    chosen = ", ".join(f"{'MP' if s == 'mass' else 'Maxwell'} {cell_name(s)}" for s in schemes)
    if measured:
        head = "Sensitivity of the signed peak bias 100 (max|u_num| / max|u_exp| - 1) to the damping parameters (Fig. 13 analog)"
        legend = f"solid frame: best cell (smallest |bias|); dashed frame: selected setting ({chosen}); hatched x: no result"
    else:
        head = "Absolute peak response per cell - no measured channels in the summary, so no bias and no best cell (Fig. 13 analog)"
        legend = f"dashed frame: selected setting ({chosen}); hatched x: no result"
    notes = table_notes(groups)
    text = f"{head}\n{groups_text(groups)}" + (f"; {'; '.join(notes)}" if notes else "") + f"\n{legend}"
    fig.suptitle(wrap(text, fig.get_figwidth()), fontsize=9)
    save_figure(fig, path, dpi=110)
    plt.close(fig)
    return path


# ----------------------------------------------------------------------------------------------------- IDA


def ida(cases, path):
    """IDA curves: the settings whose cases differ only in level or intensity. Returns the path, or None with the
    reason printed."""
    members = {}
    for c in cases:
        members.setdefault((c.kinematics, c.record, c.setting()), []).append(c)
    multi = {k: v for k, v in members.items() if len(v) > 1}
    if not multi:
        print("no IDA: every setting has one case per record (incremental or single-level sweep): no IDA curves")
        return None
    panels, failed = {}, {}
    for (kinematics, record, setting), group in multi.items():
        done = [c for c in group if c.status == "done" and c.peak(OC1) is not None]
        if done:
            panels.setdefault((kinematics, setting), {})[record] = done
            last = max(c.intensity() for c in done)
            if any(c.status == "failed" and c.intensity() > last for c in group):
                failed.setdefault((kinematics, setting), set()).add(record)
    if not panels:
        print("no IDA: no level of a multi-level setting is done with an OC1-y peak yet")
        return None
    records = []
    for by_record in panels.values():
        for record in by_record:
            if record not in records:
                records.append(record)
    # ten colours, then the next marker: tab20's pale halves are too alike to tell records apart
    colours = {r: plt.get_cmap("tab10")(i % 10) for i, r in enumerate(records)}
    markers = {r: "osD^v<"[(i // 10) % 6] for i, r in enumerate(records)}

    n = len(panels)
    ncols = 2 if n == 4 else min(3, n)
    nrows = (n + ncols - 1) // ncols
    legend_width = 0.7 + 0.065 * max(len(record_text(r)) for r in records + ["16 % / 84 % fractiles"])
    fig, axes = plt.subplots(nrows, ncols, figsize=(5.2 * ncols + legend_width, 4.3 * nrows + 0.9), squeeze=False)
    off_scale = False
    kinematics_all = {k for k, _ in panels}
    handles = {}
    fractile_notes = []
    for ax, ((kinematics, setting), by_record) in zip(axes.flat, panels.items()):
        sample = next(iter(by_record.values()))[0]
        measure = sample.measure
        if measure in ("pga", "sa") and all(c["intensity_g"] is not None for cs in by_record.values() for c in cs):
            im = lambda c: c["intensity_g"]
            ylabel = "PGA (g)" if measure == "pga" else "Sa(T) (g)"
        elif all(c["input_pga_g"] is not None for cs in by_record.values() for c in cs):
            im = lambda c: c["input_pga_g"]
            ylabel = "PGA of the input (g)"
        else:
            im = lambda c: c["level_percent"]
            ylabel = "level (% of the record)"
        curves = {}
        for record, cs in by_record.items():
            points = sorted(((im(c), c.peak(OC1)) for c in cs if im(c) is not None), key=lambda p: p[0])
            if not points:
                continue
            curves[record] = points
        # far outliers (a collapse) would squeeze the other curves: cut the drift axis past the others, draw the
        # outliers at its edge (a flat line, as IDA curves of a collapse are drawn) with their value
        drifts = np.array([x for points in curves.values() for _, x in points])
        edge = None
        if drifts.size >= 6:
            typical = np.percentile(drifts, 90)
            if drifts.max() > 3 * typical > 0:
                edge = 1.12 * drifts[drifts <= 3 * typical].max()
        for record, points in curves.items():
            x = [0.0] + [p[1] if edge is None else min(p[1], edge) for p in points]
            y = [0.0] + [p[0] for p in points]
            line, = ax.plot(x, y, "-", marker=markers[record], lw=0.9, ms=3.5, color=colours[record], alpha=0.85,
                            label=record_text(record))
            handles.setdefault(record_text(record), line)
            if record in failed.get((kinematics, setting), ()):
                mark, = ax.plot(x[-1], y[-1], "x", ms=10, mew=2.2, color="black", zorder=7,
                                label="next level failed")
                handles.setdefault("next level failed", mark)
            for im_value, drift in points:
                if edge is not None and drift > edge:
                    off_scale = True
                    ax.plot(edge, im_value, ">", ms=9, color=colours[record], mec="black", clip_on=False, zorder=6)
                    ax.annotate(f"{drift:.0f} mm" if drift >= 100 else f"{drift:.3g} mm", (edge, im_value),
                                xytext=(-8, 0), textcoords="offset points", ha="right", va="center", fontsize=7,
                                color="0.15", bbox={"boxstyle": "round,pad=0.1", "fc": "white", "ec": "none", "alpha": 0.8})
        # the median and the 16 %/84 % fractiles of the drift across records at each common IM value
        stripes = {}
        for points in curves.values():
            for y, x in points:
                stripes.setdefault(key_number(y), []).append(x)
        common = sorted((y, xs) for y, xs in stripes.items() if len(xs) >= 3)
        label = setting_text(sample) + (f", {kinematics}" if len(kinematics_all) > 1 else "")
        if len(curves) >= 3 and common:
            ims = np.array([0.0] + [y for y, _ in common])
            p16, p50, p84 = (np.concatenate(([0.0], q)) for q in
                             np.array([np.percentile(xs, [16, 50, 84]) for _, xs in common]).T)
            if edge is not None:
                p16, p50, p84 = (np.minimum(q, edge) for q in (p16, p50, p84))
            median, = ax.plot(p50, ims, "-", color="black", lw=2.6, label="median", zorder=5)
            fractile, = ax.plot(p16, ims, "--", color="black", lw=1.5, label="16 % / 84 % fractiles", zorder=5)
            ax.plot(p84, ims, "--", color="black", lw=1.5, zorder=5)
            handles.setdefault("median", median)
            handles.setdefault("16 % / 84 % fractiles", fractile)
        elif len(curves) >= 3:
            fractile_notes.append(f"{label}: the records share no IM value (scale them to targets with measure pga "
                                  f"or sa): no fractiles")
        else:
            fractile_notes.append(f"{label}: {len(curves)} record{'s' if len(curves) != 1 else ''}, fewer than 3: "
                                  f"no fractiles")
        ax.set_xlim(0, edge)
        ax.set_ylim(bottom=0)
        ax.set_title(label, fontsize=9)
        ax.set_xlabel(f"peak |{OC1.name}| drift (mm)")
        ax.set_ylabel(ylabel)
        ax.grid(alpha=0.3)
    for ax in list(axes.flat)[n:]:
        ax.set_visible(False)
    order = [k for k in handles if k not in ("median", "16 % / 84 % fractiles", "next level failed")]
    order += [k for k in ("median", "16 % / 84 % fractiles", "next level failed") if k in handles]
    fig.legend([handles[k] for k in order], order, loc="center left", fontsize=8, frameon=False,
               bbox_to_anchor=(1 - legend_width / fig.get_figwidth(), 0.5))
    synthetic = f" (record {SYNTHETIC_TAG}: the SYNTHETIC AQA75 stand-in)" if SYNTHETIC_TAG in records else ""
    text = (f"Incremental dynamic analysis: crown drift OC1-y against the intensity measure, "
            f"{len(records)} record{'s' if len(records) > 1 else ''}{synthetic}\n"
            "each level a separate analysis from the undamaged vault" +
            ("; triangles at the right edge: off-scale drift (collapse?), value written" if off_scale else ""))
    fig.suptitle(wrap(text, fig.get_figwidth()), fontsize=9)
    fig.tight_layout(rect=(0, 0, 1 - legend_width / fig.get_figwidth(), 1))
    save_figure(fig, path, dpi=110)
    plt.close(fig)
    for note in fractile_notes:
        print(f"IDA: {note}")
    return path


# ----------------------------------------------------------------------------------------------------- main


def main():
    parser = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    parser.add_argument("out", metavar="OUT", help="output folder of cross_vault sweep, or its summary.csv")
    parser.add_argument("--out-dir", help="folder for the PNGs (default: the folder of the summary)")
    parser.add_argument("--show-all", action="store_true",
                        help="print every case's row, and every case that is not done (default: 10 per status)")
    args = parser.parse_args()
    path = summary_path(args.out)
    if not os.path.isfile(path):
        fail(f"no summary: {path} does not exist (give the output folder of `cross_vault sweep` or its summary.csv)")
    cases, notes = read_summary(path)
    out = args.out_dir or os.path.dirname(os.path.abspath(path))
    try:
        os.makedirs(out, exist_ok=True)
    except OSError as error:
        fail(f"cannot make {out}: {error.strerror or error}")

    counts = {}
    for c in cases:
        counts[c.status] = counts.get(c.status, 0) + 1
    print(f"{path}: {len(cases)} case{'s' if len(cases) != 1 else ''}"
          + (": " + ", ".join(f"{n} {s}" for s, n in sorted(counts.items(), key=lambda kv: kv[0] != "done")) if cases else ""))
    for note in notes:
        print(f"note: {note}")
    list_unfinished(cases, args.show_all)
    if args.show_all and cases:
        print_all(cases)
    written = []
    done = [c for c in cases if c.status == "done"]
    if not done:
        print("no case is done: no figures")
    else:
        groups = grids(cases)
        ida_groups = [g for g, by in groups.items() if any(grid.several_levels for grid in by.values())]
        if ida_groups:
            print(f"{len(ida_groups)} (kinematics, record) group{'s' if len(ida_groups) > 1 else ''} with several "
                  "levels per damping setting (an IDA): not in the Table 3 analog and the heat maps, which compare "
                  "settings at one level")
            groups = {g: by for g, by in groups.items() if g not in ida_groups}
        others = [c for c in done if c.scheme not in ("mass", "maxwell")]
        if others:
            print(f"not in the Table 3 analog and the heat maps (mass and maxwell only): {len(others)} case"
                  f"{'s' if len(others) > 1 else ''} of {', '.join(sorted({NAMES.get(c.scheme, c.scheme) for c in others}))}"
                  + (":" if len(others) <= 10 or args.show_all else " (--show-all lists them)"))
            for c in (others if len(others) <= 10 or args.show_all else []):
                if c[OC1.bias] is not None or c[ACC18.bias] is not None:
                    values = ", ".join(f"{ch.name} {c[ch.bias]:+.1f} %" for ch in (OC1, ACC18) if c[ch.bias] is not None)
                    print(f"  {c.id}: signed peak bias {values}")
                else:
                    values = ", ".join(f"{ch.name} {c.peak(ch):.3g} {ch.unit_text.replace('_', '/')}"
                                       for ch in (OC1, ACC18) if c.peak(ch) is not None)
                    print(f"  {c.id}: |peak| {values or 'none'}")
        if not groups:
            if not ida_groups:
                print("no mass or maxwell cases: no Table 3 analog, no heat maps")
        elif not any(g.cell for by in groups.values() for g in by.values()):
            print("no mass or maxwell case is done: no Table 3 analog, no heat maps")
        else:
            measured = any(c[ch.bias] is not None for by in groups.values() for g in by.values() for c in g.done()
                           for ch in (OC1, ACC18))
            if not measured:
                print("no measured channels (bias columns empty): peak responses instead of biases, no best cell")
            for scheme in ("mass", "maxwell"):
                if not any(scheme in by for by in groups.values()):
                    print(f"no {scheme} cases: no {NAMES[scheme]} heat map")
            for function, name in ((table3, "sweep_table3.png"), (heatmaps, "sweep_heatmaps.png")):
                result = function(groups, measured, os.path.join(out, name))
                if result:
                    written.append(result)
        result = ida(cases, os.path.join(out, "sweep_ida.png"))
        if result:
            written.append(result)
    if written:
        print("PNGs written:")
        for p in written:
            print(f"  {p}")
    else:
        print("no PNG written")


if __name__ == "__main__":
    main()
