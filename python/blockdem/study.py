"""blockdem.run: a model's study as `blockdem run` runs it, and its results as Python objects and numpy arrays."""

import json
import os
import re
import sys

import numpy as np

from . import _core
from .model import Model, load


def read_history(path):
    """A history file of a study (history_<level>.csv) as a dict of numpy arrays: 'time' (s), then per monitor
    point <name>_ux, _uy, _uz (m, relative to the table) and <name>_ax, _ay, _az (m/s^2, absolute)."""
    with open(path) as f:
        header = f.readline().strip().split(",")
    data = np.loadtxt(path, delimiter=",", skiprows=1, ndmin=2)
    return {name: data[:, k].copy() for k, name in enumerate(header)}


def _label(level):
    """The level's label in file names, as the study writes it (25, 50, 12.5)."""
    return ("%.15g" % float(level))


class StudyResult:
    """What a seismic study wrote and found. `report` is report.json as a dict (input, model, settling, damping,
    timestep, levels with their peaks, damage and energy); `out` the folder of the outputs; `levels` the levels
    run (%); `table4` the run's Table 4 as text; `interrupted`: stopped early (resume with resume=out/checkpoint.bin).
    history(level) reads a level's monitor histories as numpy arrays."""

    def __init__(self, raw):
        self.report = json.loads(raw["report"])
        self.out = raw["out"]
        self.table4 = raw["table4"]
        self.interrupted = raw["interrupted"]
        self.warnings = list(raw["warnings"])

    @property
    def levels(self):
        return [L["level_percent"] for L in self.report["levels"]]

    def level(self, level):
        """The report of one level (a dict: peaks, damage, energy, steps, wall_seconds, ...)."""
        for L in self.report["levels"]:
            if abs(L["level_percent"] - float(level)) < 1e-9:
                return L
        raise KeyError("no level %s %% in this study (levels run: %s)" % (level, self.levels))

    def history(self, level=None):
        """The monitor histories of a level (default: the last run) as a dict of numpy arrays: 'time' (s), then
        <point>_ux, _uy, _uz (m, relative to the table) and <point>_ax, _ay, _az (m/s^2)."""
        if not self.out:
            raise ValueError("this study wrote no outputs (out was empty)")
        if level is None:
            if not self.levels:
                raise ValueError("no level was run")
            level = self.levels[-1]
        self.level(level)
        return read_history(os.path.join(self.out, "history_%s.csv" % _label(level)))

    @property
    def energy_balance_error(self):
        """The energy balance error at the end of each level, as an array."""
        return np.array([L["energy"]["balance_error"] for L in self.report["levels"]])

    def __repr__(self):
        return "StudyResult('%s', levels %s, out '%s'%s)" % (self.report["model"]["name"], self.levels, self.out,
                                                              ", interrupted" if self.interrupted else "")


class PushoverResult:
    """What an equivalent-static pushover found: collapse_multiplier (lambda at collapse, the middle of the final
    bracket [lower, upper]), stands_at_upper, falls_under_weight, collapse_displacement (m) and `trials`, a dict of
    arrays in the order run: lambda, stands, max_displacement (m), unbalanced_force_ratio, steps, wall_seconds."""

    def __init__(self, raw):
        for key in ("collapse_multiplier", "lower", "upper", "stands_at_upper", "falls_under_weight",
                    "collapse_displacement", "wall_seconds", "trials", "out", "warnings"):
            setattr(self, key, raw[key])

    def __repr__(self):
        return "PushoverResult(collapse_multiplier=%.4f, bracket=[%.4f, %.4f], %d trials)" % (
            self.collapse_multiplier, self.lower, self.upper, len(self.trials["lambda"]))


def _default_out(model):
    if model.source and not model.source.startswith("<"):
        stem = os.path.splitext(os.path.basename(model.source))[0]
    else:
        stem = re.sub(r"[^A-Za-z0-9_.-]+", "_", model.name).strip("_") or "model"
    return stem + "_run"


def run(model, out=None, **options):
    """Runs a model's study as `blockdem run` does: settles the structure under gravity, then shakes it at each level
    of its record in turn (or runs its pushover, if the model says so), writing histories, damage maps (VTK) and
    report.json into `out` (default: <model name>_run). Returns a StudyResult (or a PushoverResult).

    model: a blockdem.Model or the path of a model file. options override the model's study, under the names of
    `blockdem run`'s options: record (a path or a blockdem.Record), units, axis, record_level, levels, truncate,
    window, baseline, rest, damping, zeta, frequency, band, branches, damping_frame, target_dt, mass_increase,
    max_mass_increase, settling, settle_tolerance, settle_steps, contacts, collapse_displacement, runaway_displacement,
    max_speed, history_dt, snapshots_every, free_vibration, checkpoint_minutes, resume, stop_after_steps, progress
    (a progress line on stderr, default True).

    The computation runs without the GIL. Ctrl-C stops it cleanly after the current step, with a checkpoint in
    `out`, and raises KeyboardInterrupt; run again with resume=out + '/checkpoint.bin' and the same options to go on,
    bitwise as if it had not stopped.
    """
    if not isinstance(model, Model):
        model = load(model)
    options = dict(options)
    if out is None and not options.get("resume"):
        out = _default_out(model)
    if out is not None:
        options["out"] = os.fspath(out)
    file = model._file()
    try:
        raw = _core.run_model(file, model._describe(), options)
    except KeyboardInterrupt:
        folder = options.get("out") or os.path.dirname(options.get("resume", ""))
        checkpoint = os.path.join(folder, "checkpoint.bin")
        if os.path.exists(checkpoint):
            print("blockdem: stopped; what was written stays in %s/; go on with the same options and resume='%s'"
                  % (folder, checkpoint), file=sys.stderr)
        raise
    if raw["analysis"] == "pushover":
        return PushoverResult(raw)
    return StudyResult(raw)
