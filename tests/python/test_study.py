# blockdem.run: the same study from Python as from `blockdem run`, its results as arrays, Ctrl-C and resume, the
# pushover, and bad options.
import json
import os
import signal
import subprocess
import sys
import time

import numpy as np
import pytest

import blockdem
from test_model import two_courses

SHORT = dict(levels=[100], window=(2, 3), rest=0.5, progress=False)


def test_history_is_the_programs_bit_for_bit(tmp_path, run_program):
    m = two_courses()
    r = blockdem.run(m, out=tmp_path / "python", **SHORT)
    m.save(tmp_path / "wall.json")
    run_program("blockdem", "run", tmp_path / "wall.json", "--levels", 100, "--window", 2, 3, "--rest", 0.5, "--quiet",
                "--out", tmp_path / "program")
    python_text = (tmp_path / "python" / "history_100.csv").read_bytes()
    assert python_text == (tmp_path / "program" / "history_100.csv").read_bytes()
    program = json.loads((tmp_path / "program" / "report.json").read_text())
    assert r.report["levels"][0]["peaks"] == program["levels"][0]["peaks"]
    assert r.report["timestep"]["dt_s"] == program["timestep"]["dt_s"]
    # The histories as arrays: time in s, displacements in m relative to the table, accelerations in m/s^2.
    h = r.history(100)
    assert list(h) == ["time", "top_ux", "top_uy", "top_uz", "top_ax", "top_ay", "top_az"]
    assert all(v.shape == h["time"].shape for v in h.values()) and h["time"].ndim == 1
    assert np.diff(h["time"]) == pytest.approx(0.005, abs=r.report["timestep"]["dt_s"])  # sampled on steps
    peak = r.level(100)["peaks"]["top_uy"]
    assert h["top_uy"].max() == pytest.approx(peak["max"], rel=1e-6)
    assert r.levels == [100] and not r.interrupted and r.energy_balance_error.shape == (1,)
    assert r.table4.splitlines()[1].split()[:2] == ["maxwell", "%.3e" % r.report["timestep"]["dt_s"]]


RUN_IN_CHILD = """
import sys
import blockdem
blockdem.run(blockdem.load(sys.argv[1]), out=sys.argv[2], levels=[100], window=(0, 15), rest=0.5, progress=False)
"""


def test_ctrl_c_leaves_a_checkpoint_that_resumes_bit_for_bit(tmp_path):
    m = two_courses()
    m.save(tmp_path / "wall.json")
    full = dict(levels=[100], window=(0, 15), rest=0.5, progress=False)
    whole = blockdem.run(m, out=tmp_path / "whole", **full)
    stopped = tmp_path / "stopped"
    child = subprocess.Popen([sys.executable, "-c", RUN_IN_CHILD, str(tmp_path / "wall.json"), str(stopped)],
                             stderr=subprocess.PIPE, text=True)
    deadline = time.time() + 120
    while not (stopped / "report.json").exists() and time.time() < deadline:  # written once settled
        time.sleep(0.05)
    time.sleep(0.5 * whole.level(100)["wall_seconds"])  # into the level
    child.send_signal(signal.SIGINT)
    _, err = child.communicate(timeout=120)
    assert child.returncode != 0 and "KeyboardInterrupt" in err, err
    assert "resume='%s'" % (stopped / "checkpoint.bin") in err
    assert (stopped / "checkpoint.bin").exists()
    resumed = blockdem.run(m, resume=str(stopped / "checkpoint.bin"), **full)
    assert resumed.out == str(stopped)
    assert (stopped / "history_100.csv").read_bytes() == (tmp_path / "whole" / "history_100.csv").read_bytes()
    assert resumed.report["levels"][0]["steps"] == whole.report["levels"][0]["steps"]


def test_pushover_is_the_programs(tmp_path, run_program):
    arch = blockdem.generate.arch(voussoirs=12, thickness_ratio=0.2)
    arch.pushover(axis="x", resolution=0.02)
    r = blockdem.run(arch, out=tmp_path / "python", progress=False)
    assert isinstance(r, blockdem.PushoverResult)
    arch.save(tmp_path / "arch.json")
    text = run_program("blockdem", "run", tmp_path / "arch.json", "--quiet", "--out", tmp_path / "program")
    assert "collapse multiplier lambda = %.4f" % r.collapse_multiplier in text
    assert r.lower < r.collapse_multiplier < r.upper and r.upper - r.lower <= 0.02
    t = r.trials
    assert set(t) == {"lambda", "stands", "max_displacement", "unbalanced_force_ratio", "steps", "wall_seconds"}
    assert t["stands"].dtype == bool and t["steps"].dtype == np.int64 and t["lambda"].shape == t["stands"].shape
    assert t["stands"][0] and not t["stands"][1]  # lambda 0 stands, the upper end falls


def test_bad_options_name_the_keyword_and_the_range(tmp_path):
    m = two_courses()
    with pytest.raises(ValueError, match=r"levels: each level must be in \(0, 1000\] %, got 2000"):
        blockdem.run(m, out=tmp_path / "a", levels=[2000])
    with pytest.raises(ValueError, match="damping must be one of 'none', 'mass', 'stiffness', 'rayleigh', 'maxwell', got 'maxwel'"):
        blockdem.run(m, out=tmp_path / "b", damping="maxwel")
    with pytest.raises(ValueError, match=r"mass_increase must be in \[0, max_mass_increase 20 \(the default\)\] %, got 30"):
        blockdem.run(m, out=tmp_path / "c", mass_increase=30)
    with pytest.raises(TypeError, match="unknown study option 'level' \\(allowed: axis, band,"):
        blockdem.run(m, out=tmp_path / "d", level=[50])
    with pytest.raises(TypeError, match="branches: expected an integer"):
        blockdem.run(m, out=tmp_path / "e", branches=2.5)
    with pytest.raises(blockdem.InputError, match="missing.AT2: no such file"):
        blockdem.run(m, out=tmp_path / "f", record=str(tmp_path / "missing.AT2"))
    with pytest.raises(TypeError, match="record: expected a blockdem.Record"):
        blockdem.run(m, out=tmp_path / "g", record=[1, 2, 3])


def test_a_record_from_python(tmp_path):
    dt = 0.01
    t = np.arange(0, 2, dt)
    record = blockdem.Record(0.2 * np.sin(2 * np.pi * 2 * t), dt=dt, units="g", name="2 Hz sine")
    r = blockdem.run(two_courses(), out=tmp_path, record=record, record_level=100, levels=[100], rest=0, baseline="none",
                     progress=False)
    assert r.report["input"]["record"] == "2 Hz sine"
    assert r.report["input"]["pga_m_s2"] == pytest.approx(0.2 * 9.80665 * np.abs(np.sin(2 * np.pi * 2 * t)).max(), rel=1e-12)
    assert r.report["input"]["duration_s"] == pytest.approx(t[-1])
