# blockdem.sweep: a sweep file's cases over a model from Python, against `blockdem sweep` on the same files.
import csv
import json

import numpy as np
import pytest

import blockdem
from test_model import two_courses

SPEC = {"model": "wall.json", "records": [""], "levels": [50, 100],
        "schemes": [{"scheme": "none"}, {"scheme": "maxwell", "zeta": 0.03, "band_hz": [1, 40], "branches": 3}]}


def test_summary_is_the_programs(tmp_path, run_program):
    two_courses().save(tmp_path / "wall.json")
    (tmp_path / "sweep.json").write_text(json.dumps(SPEC))
    r = blockdem.sweep(tmp_path / "sweep.json", out=tmp_path / "python", window=(2, 2.5), rest=0)
    assert r.done == 2 and r.failed == 0 and r.not_finished == 0 and len(r.rows) == 2
    assert list(r.columns["scheme"]) == ["none", "maxwell"]
    assert r.columns["top_uy_max_mm"].shape == (2,) and np.all(np.isfinite(r.columns["top_uy_max_mm"]))
    assert (r.columns["level_percent"] == 100).all()
    history = blockdem.read_history(r.case_folder(1) + "/history_100.csv")
    assert history["top_uy"].max() * 1e3 == pytest.approx(r.columns["top_uy_max_mm"][1], rel=1e-6)
    run_program("blockdem", "sweep", tmp_path / "sweep.json", "--window", 2, 2.5, "--rest", 0, "--quiet", "--out", tmp_path / "program")

    def rows(folder):  # every column but the wall time, the one that differs between two runs of a sweep
        with open(folder / "summary.csv", newline="") as f:
            return [row[:-1] for row in csv.reader(f)]
    assert rows(tmp_path / "python") == rows(tmp_path / "program")
    # A second run skips the finished cases, and says the same.
    again = blockdem.sweep(tmp_path / "sweep.json", out=tmp_path / "python", window=(2, 2.5), rest=0)
    assert again.rows == r.rows


def test_a_sweep_given_as_a_dict_over_a_model_in_memory(tmp_path):
    spec = {"records": [""], "levels": [100], "schemes": [{"scheme": "mass", "zeta": [0.02, 0.05]}]}
    r = blockdem.sweep(spec, model=two_courses(), out=tmp_path, window=(2, 2.3), rest=0)
    assert list(r.columns["zeta"]) == [0.02, 0.05] and r.done == 2


def test_grid_options_are_the_sweeps(tmp_path):
    with pytest.raises(TypeError, match="sweep: damping is not a base option"):
        blockdem.sweep(dict(SPEC), model=two_courses(), out=tmp_path, damping="none")
    with pytest.raises(ValueError, match="names no model file"):
        blockdem.sweep({"records": [""], "levels": [50], "schemes": [{"scheme": "none"}]}, out=tmp_path)
