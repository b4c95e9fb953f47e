"""A small incremental dynamic analysis (IDA) of a free-standing brick wall shaken out of plane: each record scaled
to four PGA levels, each run from the wall as built, and the peak out-of-plane drift at its top against the PGA.

    build/python/blockdem-python examples/python/ida.py [RECORD ...] [--pga 0.1 0.2 0.3 0.4] [--out ida]

Without records: the two Imperial Valley components of ../shared/data (if there) and the built-in stand-in.
"""
import argparse
import os

import matplotlib

matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402
import numpy as np  # noqa: E402

import blockdem  # noqa: E402

here = os.path.dirname(os.path.realpath(__file__))
parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
parser.add_argument("records", nargs="*")
parser.add_argument("--pga", type=float, nargs="+", default=[0.1, 0.2, 0.3, 0.4], help="levels, g")
parser.add_argument("--window", type=float, default=5.0, help="s of each record, from its start")
parser.add_argument("--courses", type=int, default=12)
parser.add_argument("--out", default="ida")
args = parser.parse_args()

records = args.records
if not records:
    shared = os.path.join(here, "..", "..", "..", "shared", "data")
    records = [os.path.join(shared, "ImperialValley1979_ElCentroArray4_%s.AT2" % c) for c in ("140", "230")]
    records = [r for r in records if os.path.exists(r)] + [""]  # "": the built-in stand-in

wall = blockdem.generate.wall(length=1.0, courses=args.courses)
height = args.courses * 0.075
curves = {}
for path in records:
    name = os.path.basename(path) or "stand-in"
    drifts = []
    for pga in args.pga:
        case = wall.copy()
        case.excitation(record=os.path.abspath(path) if path else "", pga_g=pga, window=(0, args.window))
        case.study(levels=[100], rest=1.0)
        r = blockdem.run(case, out=os.path.join(args.out, "%s_%.2fg" % (os.path.splitext(name)[0], pga)), progress=False)
        level = r.level(100)
        peak = level["peaks"]["top_uy"]
        drift = max(peak["max"], -peak["min"]) / height
        collapsed = "collapse" in level
        drifts.append((drift, collapsed))
        print("%-45s PGA %.2f g: peak drift %.3f %%%s (%d steps, %.1f s)" % (name, pga, 100 * drift,
              ", COLLAPSED" if collapsed else "", level["steps"], level["wall_seconds"]))
    curves[name] = drifts

fig, ax = plt.subplots(figsize=(6.5, 4.5))
for name, points in curves.items():
    drift = 100 * np.array([d for d, _ in points])
    fallen = np.array([c for _, c in points])
    ax.semilogx(drift, args.pga, "o-", label=name)
    ax.semilogx(drift[fallen], np.array(args.pga)[fallen], "x", color="k", ms=9)
ax.set(xlabel="peak drift at the top of the wall [%]", ylabel="PGA [g]",
       title="IDA of a %d-course dry brick wall, out of plane (x: collapsed)" % args.courses)
ax.grid(True, which="both", color="0.9")
ax.legend(fontsize=8)
fig.tight_layout()
png = os.path.join(args.out, "ida.png")
fig.savefig(png, dpi=130)
print("wrote", png)
