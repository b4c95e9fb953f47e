#!/usr/bin/env python3
"""MINPACK's Levenberg-Marquardt (scipy.optimize.least_squares, method='lm', analytic Jacobian) on the problem of
bench_maxwell_fit: 3 Maxwell branches, zeta* = 4 % over 1-40 Hz, 500 log-spaced points, the same parametrisation
(cumulative ordering map, centre margin 2) and the same start. Prints the optimum and the time per fit.
Needs numpy and scipy (Debian: python3-numpy python3-scipy; scripts/install-deps.sh --minpack installs them for the
system Python, which the script uses when the running `python3` lacks them)."""
import os
import sys
import time

sys.path.insert(0, os.path.join(os.path.dirname(os.path.abspath(__file__)), "..", "scripts"))
from python_modules import MINPACK, require_modules  # noqa: E402

require_modules(__file__, MINPACK)
import numpy as np  # noqa: E402
from scipy.optimize import least_squares  # noqa: E402

ZETA, F_LB, F_UB, N, M, MARGIN = 0.04, 1.0, 40.0, 3, 500, 2.0
w = 2 * np.pi * np.geomspace(F_LB, F_UB, M)
log_lo, log_hi = np.log(2 * np.pi * F_LB / MARGIN), np.log(2 * np.pi * F_UB * MARGIN)
band = log_hi - log_lo
sig = lambda u: 1 / (1 + np.exp(-u))


def unpack(p):
    nu, alpha = p[:N], np.exp(p[N:])
    rest = np.exp(-np.cumsum(np.logaddexp(0, nu)))  # 1 - s_r
    log_w = log_lo + (1 - rest) * band
    tau = np.exp(-log_w) / np.sqrt(1 + alpha)
    return nu, alpha, rest, tau


def modulus_terms(p):
    """x = w tau, d = 1 + x^2, Re and Im of M_T (eq. 19) and zeta at every evaluation frequency."""
    nu, alpha, rest, tau = unpack(p)
    x = np.outer(w, tau)
    d = 1 + x * x
    re = 1 + (alpha * x * x / d).sum(1)
    im = (alpha * x / d).sum(1)
    return nu, alpha, rest, x, d, re, im / (2 * re)


def residuals(p):
    return modulus_terms(p)[-1] - ZETA  # eq. 22


def jacobian(p):
    nu, alpha, rest, x, d, re, z = modulus_terms(p)
    c = (1 / (2 * re))[:, None]
    a, b = alpha * x * x / d, alpha * x / d
    dlogx = alpha * x / d**2 * ((1 - x * x) - 4 * z[:, None] * x) * c
    j_rho = (b - 2 * z[:, None] * a) * c + dlogx * (-0.5 * alpha / (1 + alpha))
    dlogw = band * rest[:, None] * sig(nu)[None, :] * np.tril(np.ones((N, N)))
    j_nu = -dlogx @ dlogw
    return np.hstack([j_nu, j_rho])


s = (np.arange(N) + 0.5) / N
prev = np.concatenate([[0], s[:-1]])
sigma = 1 - (1 - s) / (1 - prev)
peak = ZETA * min(np.log(F_UB / F_LB) / (N * np.pi) + 0.5, 1.0)
sq = 2 * peak + np.sqrt(4 * peak * peak + 1)
p0 = np.concatenate([np.log(sigma / (1 - sigma)), np.full(N, np.log(sq * sq - 1))])

repeats = 200
start = time.perf_counter()
for _ in range(repeats):
    result = least_squares(residuals, p0, jac=jacobian, method="lm", gtol=1e-9, xtol=1e-12, ftol=1e-14)  # MINPACK lmder
per_fit = (time.perf_counter() - start) / repeats
_, alpha, _, tau = unpack(result.x)
z = residuals(result.x) / ZETA
print(f"MINPACK lm from Python: {1e6 * per_fit:.0f} us per fit, {result.nfev} evaluations, status {result.status}")
print(f"1 + sum alpha = {1 + alpha.sum():.4f}, relative error {100 * z.min():+.3f} % / {100 * z.max():+.3f} %")
print("peak Hz:", np.round(1 / (tau * np.sqrt(1 + alpha)) / (2 * np.pi), 3), "alpha:", np.round(alpha, 4))
