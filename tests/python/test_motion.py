# The ground-motion toolkit from Python against closed forms and the program ground_motion.
import math
import os

import numpy as np
import pytest

import blockdem

G = 9.80665


def test_record_from_samples_in_g_holds_m_s2_and_is_a_view():
    a = np.sin(np.linspace(0, 2 * np.pi, 101))
    r = blockdem.Record(a, dt=0.01, units="g", name="sine")
    assert len(r) == 101 and r.dt == 0.01 and r.units == "g"
    assert r.acceleration.shape == (101,)
    assert np.allclose(r.acceleration, a * G, rtol=0, atol=1e-15)
    assert np.allclose(r.time, 0.01 * np.arange(101))
    r.acceleration[0] = 1.5  # the array is the record's own storage
    assert r.acceleration[0] == 1.5
    assert r.peaks()["pga"] == pytest.approx(G, rel=1e-3)


def test_arias_intensity_of_a_sine_is_pi_over_2g_times_a_squared_t_over_2():
    A, f, T = 2.0, 5.0, 4.0
    dt = 1e-3
    t = np.arange(0, T + dt / 2, dt)
    r = blockdem.Record(A * np.sin(2 * np.pi * f * t), dt=dt)
    expected = math.pi / (2 * G) * A * A / 2 * T
    assert blockdem.arias_intensity(r) == pytest.approx(expected, rel=1e-5)
    history = blockdem.arias_history(r)
    assert history.shape == (len(t),) and history[-1] == pytest.approx(blockdem.arias_intensity(r), rel=1e-12)
    start, end = blockdem.significant_duration(r)
    assert start == pytest.approx(0.05 * T, abs=0.02) and end == pytest.approx(0.95 * T, abs=0.02)


def test_toolkit_on_the_stand_in_is_the_programs(program_json):
    info = program_json("ground_motion", "info", "--synthetic")
    r = blockdem.synthetic_aqa75()
    assert r.synthetic and r.dt == info["dt"] and len(r) == info["npts"]
    assert r.peaks()["pga"] == info["pga_m_s2"]
    assert r.peaks()["pgv"] == info["pgv_m_s"]
    assert blockdem.arias_intensity(r) == info["arias_m_s"]
    assert blockdem.significant_duration(r) == pytest.approx((info["t5_s"], info["t95_s"]), rel=1e-12)
    spectrum = blockdem.response_spectrum(r, periods=[info["dominant_period_s"]])
    assert spectrum["psv"][0] == pytest.approx(info["psv_at_dominant_m_s"], rel=1e-12)
    default = blockdem.response_spectrum(r)
    assert set(default) == {"period", "sd", "psv", "psa"} and default["psa"].shape == (100,)
    w = 2 * np.pi / default["period"]
    assert np.allclose(default["psa"], w * w * default["sd"], rtol=1e-12)


def test_wavelet_truncation_keeps_the_pulse(tmp_path, run_program):
    r = blockdem.synthetic_aqa75()
    w = blockdem.wavelet_truncation(r)
    cut = w["record"]
    assert cut.start_time == w["start"] and w["start"] < w["end"]
    assert w["pulse_velocity"].shape == (len(r),)
    assert 0.5 < w["correlation"] <= 1
    # The same cut as the program's.
    run_program("ground_motion", "truncate", "--synthetic", "--method", "wavelet", "--out", tmp_path / "cut.csv")
    program_cut = np.loadtxt(tmp_path / "cut.csv", delimiter=",", comments="#", skiprows=4)  # 9 significant digits
    assert program_cut.shape == (len(cut), 5)
    assert program_cut[0, 0] == pytest.approx(cut.start_time, abs=1e-9)
    assert np.allclose(program_cut[:, 1], cut.acceleration, rtol=1e-8, atol=1e-12)


def test_baseline_and_window():
    r = blockdem.Record(np.full(1001, 0.3) + np.sin(np.linspace(0, 20 * np.pi, 1001)), dt=0.01)
    corrected = blockdem.correct_baseline(r, "mean")
    assert abs(corrected.acceleration.mean()) < 1e-12
    cut = blockdem.truncate_window(r, 2.0, 5.0)
    assert cut["start"] == pytest.approx(2.0) and cut["end"] == pytest.approx(5.0)
    assert len(cut["record"]) == 301 and 0 < cut["arias_fraction"] < 1


def test_real_record(shared_data):
    path = os.path.join(shared_data, "ImperialValley1979_ElCentroArray4_140.AT2")
    r = blockdem.read_record(path)
    assert r.units == "g" and r.dt > 0 and len(r) > 1000
    assert r.header_pga is None or r.peaks()["pga"] == pytest.approx(r.header_pga, rel=0.05)


def test_bad_input_names_the_file_and_the_range(tmp_path):
    with pytest.raises(blockdem.InputError, match="no such file"):
        blockdem.read_record(str(tmp_path / "missing.AT2"))
    with pytest.raises(ValueError, match="units must be 'g', 'm/s2' or 'cm/s2', got 'furlongs'"):
        blockdem.Record([0.0, 1.0], dt=0.01, units="furlongs")
    with pytest.raises(ValueError, match="time step dt = .* must be > 0"):
        blockdem.Record([0.0, 1.0], dt=0)
    with pytest.raises(ValueError, match="baseline"):
        blockdem.correct_baseline(blockdem.synthetic_aqa75(), "median")
    with pytest.raises(TypeError):
        blockdem.arias_intensity([1.0, 2.0])
