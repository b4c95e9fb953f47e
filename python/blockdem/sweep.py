"""blockdem.sweep: many studies of one model (damping grids, records, levels, intensity targets: IDA), and their
summary as arrays (docs/sweeps.md describes the sweep file)."""

import csv
import hashlib
import json
import os

import numpy as np

from . import _core
from .model import Model, load


class SweepResult:
    """What a sweep wrote: `out` (its folder: cases/<id>/ per case, summary.csv, summary.json), `rows` (summary.json's
    rows, one dict per case in the order of the expansion), `columns` (summary.csv as a dict of arrays: numbers as
    float arrays with NaN where a case has no value, text as arrays of str), and `done`, `failed`, `not_finished`."""

    def __init__(self, out):
        self.out = out
        with open(os.path.join(out, "summary.json")) as f:
            summary = json.load(f)
        self.rows = summary["rows"]
        self.done, self.failed, self.not_finished = summary["done"], summary["failed"], summary["not_finished"]
        with open(os.path.join(out, "summary.csv"), newline="") as f:
            table = list(csv.reader(f))
        header, body = table[0], table[1:]
        self.columns = {}
        for k, name in enumerate(header):
            values = [row[k] for row in body]
            try:
                self.columns[name] = np.array([float(v) if v != "" else np.nan for v in values])
            except ValueError:
                self.columns[name] = np.array(values, dtype=str)

    def case_folder(self, index):
        """The folder of case `index`: its report.json, histories and maps (blockdem.read_history reads them)."""
        return os.path.join(self.out, "cases", self.rows[index]["id"])

    def __repr__(self):
        return "SweepResult('%s': %d cases, %d done, %d failed, %d not finished)" % (
            self.out, len(self.rows), self.done, self.failed, self.not_finished)


def sweep(spec, model=None, out=None, **options):
    """Runs a sweep: the cases of `spec` (a sweep file's path, or its document as a dict: docs/sweeps.md) over the
    structure of `model` (a blockdem.Model or a model file's path; default: the sweep's "model", relative to the
    sweep file), one after another, each into out/cases/<id>/; then the summary. Returns a SweepResult.

    options: the base options of every case, as in blockdem.run (window, rest, baseline, history_dt, ...), except
    those the sweep sets per case (levels, record, damping, zeta, frequency, band, branches) and resume. Finished
    cases are not run again when the same sweep runs again with the same options; Ctrl-C stops the current case after
    its step (KeyboardInterrupt), and the next run continues it from its checkpoint.
    """
    if isinstance(spec, dict):
        text, source, base_dir = json.dumps(spec, indent=1), "<sweep given in Python>", os.getcwd()
        stem = "sweep"
    else:
        spec = os.fspath(spec)
        with open(spec) as f:
            text = f.read()
        source, base_dir = spec, os.path.dirname(os.path.abspath(spec))
        stem = os.path.splitext(os.path.basename(spec))[0]
    if model is None:
        name = json.loads(text).get("model", "")
        if not name:
            raise ValueError("%s: names no model file: add \"model\": \"your_model.json\", or pass model=" % source)
        model = os.path.join(base_dir, name)
    if not isinstance(model, Model):
        model = load(model)
    if out is None:
        out = stem + "_sweep"
    out = os.fspath(out)
    options.setdefault("progress", False)
    model_text = json.dumps(model.data, sort_keys=True)
    fingerprint = "python %s | measured %s | model %s" % (
        json.dumps({k: v for k, v in sorted(options.items()) if k != "progress"}, default=repr),
        json.loads(text).get("measured", ""), hashlib.sha256(model_text.encode()).hexdigest()[:16])
    _core.run_sweep(text, source, base_dir, model._file(), model._describe(), options, out, fingerprint)
    return SweepResult(out)
