# blockdem.fit_maxwell and blockdem.damping_ratio against the program maxwell_fit and the closed forms of eq. 10.
import math

import numpy as np
import pytest

import blockdem


def test_fit_is_the_programs_to_the_last_bit(program_json):
    program = program_json("maxwell_fit", "--format", "json", "--zeta", 0.03, "--band", 1, 40, "--branches", 3)
    fit = blockdem.fit_maxwell(zeta=0.03, band=(1, 40), branches=3)
    assert fit.converged
    assert fit.alpha.shape == (3,) and fit.tau.shape == (3,)
    assert list(fit.alpha) == program["alpha"]
    assert list(fit.tau) == program["tau_s"]
    assert fit.max_rel_error == program["max_rel_error"]
    assert fit.dt_factor == pytest.approx(1 / math.sqrt(1 + fit.alpha.sum()), rel=1e-15)


def test_fitted_curve_stays_within_its_band_error():
    fit = blockdem.fit_maxwell(zeta=0.05, band=(2, 20), branches=4)
    f = np.geomspace(2, 20, 200)
    zeta = fit.damping_ratio(f)
    assert zeta.shape == (200,)
    assert np.all(np.abs(zeta / 0.05 - 1) <= fit.max_rel_error * (1 + 1e-9))
    # The study's own curve of the same scheme is the same function.
    assert np.array_equal(blockdem.damping_ratio("maxwell", f, zeta=0.05, band=(2, 20), branches=4), zeta)


def test_schemes_meet_their_ratio_where_eq10_says():
    f = np.array([1.0, 7.5, 40.0])
    mass = blockdem.damping_ratio("mass", f)  # the study's default: 4 % at 7.5 Hz, zeta = alpha / (2 omega)
    assert mass[1] == pytest.approx(0.04, rel=1e-14)
    assert mass[0] == pytest.approx(0.04 * 7.5, rel=1e-14)
    stiffness = blockdem.damping_ratio("stiffness", f, zeta=0.02, frequency=10)  # zeta = beta omega / 2
    assert stiffness == pytest.approx(0.02 * f / 10, rel=1e-14)
    rayleigh = blockdem.damping_ratio("rayleigh", f, zeta=0.03, band=(1, 40))
    assert rayleigh[0] == pytest.approx(0.03, rel=1e-12) and rayleigh[2] == pytest.approx(0.03, rel=1e-12)
    assert rayleigh[1] < 0.03
    assert np.all(blockdem.damping_ratio("none", f) == 0)


def test_bad_arguments_say_what_is_allowed():
    with pytest.raises(ValueError, match="scheme must be one of 'none', 'mass', 'stiffness', 'rayleigh', 'maxwell', got 'maxwel'"):
        blockdem.damping_ratio("maxwel", [1.0])
    with pytest.raises(ValueError, match=r"zeta must be in \(0, 0.5\)"):
        blockdem.damping_ratio("mass", [1.0], zeta=0.7)
    with pytest.raises(ValueError, match=r"band must satisfy 0 < f_lb < f_ub <= 1000 Hz, got 40 1"):
        blockdem.damping_ratio("maxwell", [1.0], band=(40, 1))
    with pytest.raises(ValueError, match=r"branches \(N\) must be in 1..8"):
        blockdem.fit_maxwell(branches=9)
    with pytest.raises(TypeError, match="frequencies_hz: expected numbers"):
        blockdem.damping_ratio("mass", "fast")
