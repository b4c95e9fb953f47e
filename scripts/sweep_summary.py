"""The reader of the summary.csv of `cross_vault sweep` and `blockdem sweep` (one row per case) and its case model,
used by plot_sweep.py: the columns, a case (Case) and its damping setting, the text of settings and records in the
paper's words, the listing of unfinished cases, and the grouping of the mass and maxwell cases into grids (zeta x
centre frequency or band) per (kinematics, record). Data and grouping only; the figures are in plot_sweep.py."""
import csv
import math
import os
import sys

COLUMNS = ["index", "id", "status", "message", "kinematics", "record", "scheme", "zeta", "frequency_hz",
           "band_lower_hz", "band_upper_hz", "branches", "measure", "intensity_g", "level_percent", "input_pga_g",
           "input_sa_g", "wall_seconds", "steps", "cracked", "crushed", "damaged", "eps_rmsd_uy_percent"]
TEXT = {"id", "status", "message", "kinematics", "record", "scheme", "measure"}
NAMES = {"none": "noDamp", "mass": "MassProp", "maxwell": "Maxwell", "stiffness": "StiffProp", "rayleigh": "Rayleigh"}
SYNTHETIC_TAG = "aqa75"  # the record tag of the built-in synthetic stand-in


class Channel:
    def __init__(self, name, prefix, unit, unit_text):
        self.unit, self.unit_text = unit, unit_text
        self.rename(name, prefix)

    def rename(self, name, prefix):
        self.name, self.prefix = name, prefix
        self.max, self.min = f"{prefix}_max_{self.unit_text}", f"{prefix}_min_{self.unit_text}"
        self.bias = f"peak_bias_{prefix}_percent"

    def columns(self):
        return [self.max, self.min, self.bias, f"bias_{self.prefix}_max_percent", f"bias_{self.prefix}_min_percent"]


# The summary's two channels: the vault's crown drift and accelerometer (Fig. 13), or a model file's first monitor
# point (blockdem sweep), as read_summary finds them in the header.
OC1 = Channel("OC1-y", "oc1_uy", "mm", "mm")
ACC18 = Channel("ACC18-y", "acc18_ay", "m/s$^2$", "m_s2")


def find_channels(header):
    """Names OC1 and ACC18 after the columns <channel>_max_mm and <channel>_max_m_s2 of the header."""
    for channel in (OC1, ACC18):
        suffix = f"_max_{channel.unit_text}"
        prefix = next((h[:-len(suffix)] for h in header if h.endswith(suffix) and not h.startswith("bias_")), None)
        if prefix is None or prefix == channel.prefix:
            continue
        point, _, component = prefix.rpartition("_")
        channel.rename(f"{point}-{component[-1:]}", prefix)


# The settings retained for validation in the paper (Sect. 5): MP 4 % at 7.5 Hz, Maxwell 3 % on [1, 40] Hz.
SELECTED = {"mass": {"zeta": 0.04, "frequency_hz": 7.5}, "maxwell": {"zeta": 0.03, "band": (1.0, 40.0)}}


def fail(message):
    print(f"plot_sweep.py: {message}", file=sys.stderr)
    sys.exit(2)


def key_number(v):
    """A float as a dictionary key that ignores the last bits (0.1 + 0.2 == 0.3)."""
    return None if v is None else round(v, 9)


# ----------------------------------------------------------------------------------------------------- reading


class Case:
    def __init__(self, values):
        self.v = values
        for name in ("id", "status", "message", "kinematics", "record", "scheme", "measure"):
            setattr(self, name, values[name])

    def __getitem__(self, name):
        return self.v[name]

    def setting(self):
        """The damping scheme and its parameters (everything but kinematics, record and level)."""
        v = self.v
        return (self.scheme, key_number(v["zeta"]), key_number(v["frequency_hz"]), key_number(v["band_lower_hz"]),
                key_number(v["band_upper_hz"]), key_number(v["branches"]))

    def intensity(self):
        """What orders the levels of one setting: the target (g), else the level (%)."""
        v = self.v
        return v["intensity_g"] if v["intensity_g"] is not None else (v["level_percent"] if v["level_percent"] is not None else -1)

    def peak(self, channel):
        a, b = self.v[channel.max], self.v[channel.min]
        values = [abs(x) for x in (a, b) if x is not None]
        return max(values) if values else None


def summary_path(out):
    return os.path.join(out, "summary.csv") if os.path.isdir(out) else out


def read_summary(path):
    try:
        with open(path, newline="") as f:
            lines = list(csv.reader(f))
    except OSError as error:
        fail(f"cannot read {path}: {error.strerror or error}")
    except csv.Error as error:
        fail(f"{path}: not a readable CSV: {error}")
    if not lines:
        fail(f"{path} is empty: no header row (has the sweep started?)")
    header = [name.strip() for name in lines[0]]
    find_channels(header)
    columns = COLUMNS + OC1.columns() + ACC18.columns()
    missing = [name for name in columns if name not in header]
    if missing:
        fail(f"{path}: not a sweep summary (cross_vault sweep, blockdem sweep): missing the column{'s' if len(missing) > 1 else ''} "
             f"{', '.join(missing)}")
    column = {name: header.index(name) for name in columns}
    cases, notes = [], []
    bad_numbers = 0
    for number, fields in enumerate(lines[1:], start=2):
        if not fields or all(not x.strip() for x in fields):
            continue
        if len(fields) < len(header):
            notes.append(f"line {number} has {len(fields)} of {len(header)} fields (being written?): skipped")
            continue
        values = {}
        for name, i in column.items():
            text = fields[i].strip()
            if name in TEXT:
                values[name] = text
                continue
            if not text:
                values[name] = None
                continue
            try:
                x = float(text)
            except ValueError:
                x = None
                bad_numbers += 1
            if x is not None and not math.isfinite(x):
                x, bad_numbers = None, bad_numbers + 1
            values[name] = x
        values["status"] = values["status"].lower() or "pending"
        cases.append(Case(values))
    if bad_numbers:
        notes.append(f"{bad_numbers} field{'s' if bad_numbers > 1 else ''} not a finite number: read as empty")
    return cases, notes


# ----------------------------------------------------------------------------------------------------- labels


def percent(zeta):
    return f"{100 * zeta:.4g}%" if zeta is not None else "default"


def band_text(case):
    lo, hi = case["band_lower_hz"], case["band_upper_hz"]
    return f"[{lo:g}, {hi:g}] Hz" if lo is not None and hi is not None else "band ?"


def setting_text(case):
    """The scheme and its parameters in the paper's words: 'MassProp 4% @ 7.5 Hz', 'Maxwell 3% [1, 40] Hz n3'."""
    name = NAMES.get(case.scheme, case.scheme)
    if case.scheme == "none":
        return name
    text = f"{name} {percent(case['zeta'])}"
    if case["frequency_hz"] is not None:
        text += f" @ {case['frequency_hz']:g} Hz"
    if case.scheme in ("maxwell", "rayleigh"):
        text += f" {band_text(case)}"
    if case["branches"] is not None:
        text += f" n{case['branches']:g}"
    return text


def record_text(record):
    return f"{record} (SYNTHETIC AQA75 stand-in)" if record == SYNTHETIC_TAG else record


def group_text(kinematics, record):
    return f"{kinematics}, record {record_text(record)}"


def groups_text(groups):
    """'rigid, record aqa75 (SYNTHETIC ...)' for one group; for several, the groups and the synthetic note once."""
    if len(groups) == 1:
        return group_text(*next(iter(groups)))
    synthetic = any(r == SYNTHETIC_TAG for _, r in groups)
    return ("; ".join(f"{k}, {r}" for k, r in groups) +
            (f" (record {SYNTHETIC_TAG}: the SYNTHETIC AQA75 stand-in)" if synthetic else ""))


def is_selected(case):
    want = SELECTED.get(case.scheme)
    if want is None or case["zeta"] is None or abs(case["zeta"] - want["zeta"]) > 1e-9:
        return False
    if case.scheme == "mass":
        return case["frequency_hz"] is not None and abs(case["frequency_hz"] - want["frequency_hz"]) < 1e-9
    lo, hi = case["band_lower_hz"], case["band_upper_hz"]
    return lo is not None and hi is not None and abs(lo - want["band"][0]) < 1e-9 and abs(hi - want["band"][1]) < 1e-9


def list_unfinished(cases, show_all):
    for status in ("failed", "interrupted", "pending"):
        some = [c for c in cases if c.status == status]
        if not some:
            continue
        print(f"{len(some)} case{'s' if len(some) > 1 else ''} {status}:")
        shown = some if show_all else some[:10]
        for c in shown:
            print(f"  {c.id}: {c.message}" if c.message else f"  {c.id}")
        if len(shown) < len(some):
            print(f"  ... and {len(some) - len(shown)} more (--show-all lists them)")
    other = [c for c in cases if c.status not in ("done", "failed", "interrupted", "pending")]
    if other:
        print(f"{len(other)} case{'s' if len(other) > 1 else ''} with an unknown status "
              f"({', '.join(sorted({c.status for c in other}))}): not plotted")


def print_all(cases):
    print(f"every case (|peak| {OC1.name} mm, {ACC18.name} m/s^2; signed peak bias %):")
    for c in cases:
        def number(x, form):
            return format(x, form) if x is not None else "-"
        print(f"  {int(c['index']) if c['index'] is not None else '?':>4} {c.id:<48} {c.status:<11} "
              f"level {number(c['level_percent'], 'g'):>5} %  |OC1-y| {number(c.peak(OC1), '.3g'):>7}  "
              f"|{ACC18.name}| {number(c.peak(ACC18), '.3g'):>7}  bias {OC1.name} {number(c[OC1.bias], '+.1f'):>7}  "
              f"{ACC18.name} {number(c[ACC18.bias], '+.1f'):>7}")


# ----------------------------------------------------------------------------------------------------- grid


class Grid:
    """The cells of one scheme in one (kinematics, record) group: rows zeta, columns centre frequency (mass) or band
    and branches (maxwell). A cell holds its `done` case (at its highest level if it has several), or the status of
    its case when none is done."""

    def __init__(self, scheme, cases):
        self.scheme = scheme
        self.rows = sorted({key_number(c["zeta"]) for c in cases}, key=lambda z: (z is None, z))
        self.columns = sorted({self.column(c) for c in cases}, key=lambda k: tuple((x is None, x) for x in k))
        self.cell, self.status, self.several_levels = {}, {}, False
        for c in cases:
            key = (key_number(c["zeta"]), self.column(c))
            if c.status == "done":
                old = self.cell.get(key)
                if old is not None:
                    self.several_levels = True
                if old is None or c.intensity() > old.intensity():
                    self.cell[key] = c
            else:
                self.status.setdefault(key, c.status)
        branches = {c["branches"] for c in cases}
        bands = {(c["band_lower_hz"], c["band_upper_hz"]) for c in cases}
        self.one_band = len(bands) == 1
        self.one_branches = len(branches) == 1
        self.cases = cases

    def column(self, c):
        if self.scheme == "mass":
            return (key_number(c["frequency_hz"]),)
        return (key_number(c["band_lower_hz"]), key_number(c["band_upper_hz"]), key_number(c["branches"]))

    def column_label(self, k):
        if self.scheme == "mass":
            return f"{k[0]:g}" if k[0] is not None else "?"
        text = f"{k[0]:g}-{k[1]:g}" if k[0] is not None and k[1] is not None else "?"
        return text if self.one_branches or k[2] is None else f"{text}\nn{k[2]:g}"

    def cell_label(self, c):
        """The cell as in Table 3: '5% @ 15 Hz', '5%', '5% [1, 40] Hz'."""
        text = percent(c["zeta"])
        if self.scheme == "mass":
            return f"{text} @ {c['frequency_hz']:g} Hz" if c["frequency_hz"] is not None else text
        if not self.one_band:
            text += f" {band_text(c)}"
        if not self.one_branches and c["branches"] is not None:
            text += f" n{c['branches']:g}"
        return text

    def scheme_label(self):
        if self.scheme == "mass":
            return "MP"
        if self.one_band and self.cases:
            return f"Maxwell {band_text(self.cases[0])}"
        return "Maxwell"

    def done(self):
        return [self.cell[k] for k in sorted(self.cell, key=lambda k: (self.rows.index(k[0]), self.columns.index(k[1])))]

    def best(self, channel):
        candidates = [c for c in self.done() if c[channel.bias] is not None]
        return min(candidates, key=lambda c: abs(c[channel.bias])) if candidates else None

    def selected(self):
        """The selected setting's case (maxwell: preferring 3 branches), or the status of its case, or None."""
        done = [c for c in self.done() if is_selected(c)]
        if done:
            return sorted(done, key=lambda c: c["branches"] != 3)[0]
        statuses = [c.status for c in self.cases if is_selected(c)]
        return statuses[0] if statuses else None


def grids(cases):
    """{(kinematics, record): {scheme: Grid}} for the schemes mass and maxwell, in the order of the cases."""
    out = {}
    for c in cases:
        if c.scheme in ("mass", "maxwell"):
            out.setdefault((c.kinematics, c.record), {}).setdefault(c.scheme, []).append(c)
    return {group: {s: Grid(s, members) for s, members in sorted(by_scheme.items(), key=lambda kv: kv[0] != "mass")}
            for group, by_scheme in out.items()}
