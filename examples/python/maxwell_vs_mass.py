"""The damping ratio of the paper's schemes against frequency (its Fig. 10-12): Maxwell branches fitted to 3 % over
1-40 Hz (N = 1 to 4), mass-proportional damping (4 % at 7.5 Hz, MassProp) and Rayleigh (3 % at 1 and 40 Hz).

    build/python/blockdem-python examples/python/maxwell_vs_mass.py [--out maxwell_vs_mass.png]
"""
import argparse

import matplotlib

matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402
import numpy as np  # noqa: E402

import blockdem  # noqa: E402

parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
parser.add_argument("--out", default="maxwell_vs_mass.png")
parser.add_argument("--zeta", type=float, default=0.03)
parser.add_argument("--band", type=float, nargs=2, default=(1.0, 40.0))
args = parser.parse_args()

f = np.geomspace(0.1, 200, 600)
fig, ax = plt.subplots(figsize=(7.5, 4.5))
for n in (1, 2, 3, 4):
    fit = blockdem.fit_maxwell(zeta=args.zeta, band=tuple(args.band), branches=n)
    print("Maxwell N=%d: alpha %s, tau %s s, band error %+.1f / %+.1f %%, timestep factor %.4f"
          % (n, np.round(fit.alpha, 4), np.round(fit.tau, 5), 100 * fit.rel_error_min, 100 * fit.rel_error_max,
             fit.dt_factor))
    ax.semilogx(f, 100 * fit.damping_ratio(f), lw=2 if n == 3 else 1, label="Maxwell, N = %d" % n)
ax.semilogx(f, 100 * blockdem.damping_ratio("mass", f, zeta=0.04, frequency=7.5), "k--", label="MassProp, 4 % at 7.5 Hz")
ax.semilogx(f, 100 * blockdem.damping_ratio("rayleigh", f, zeta=args.zeta, band=tuple(args.band)), "k:",
            label="Rayleigh, %g %% at %g and %g Hz" % (100 * args.zeta, *args.band))
ax.axvspan(*args.band, color="0.92", zorder=0)
ax.axhline(100 * args.zeta, color="0.5", lw=0.8)
ax.set(xlabel="frequency [Hz]", ylabel="damping ratio [%]", ylim=(0, 4 * 100 * args.zeta), xlim=(f[0], f[-1]),
       title="Damping ratio of the schemes (target %g %% over %g-%g Hz, shaded)" % (100 * args.zeta, *args.band))
ax.legend(fontsize=8, loc="upper right")
fig.tight_layout()
fig.savefig(args.out, dpi=130)
print("wrote", args.out)
