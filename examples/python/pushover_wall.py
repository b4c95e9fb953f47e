"""The equivalent-static pushover of a brick wall with a window: the body acceleration lambda g out of plane that
topples it, by bisection; each trial's largest displacement plotted against lambda.

    build/python/blockdem-python examples/python/pushover_wall.py [--courses 20] [--out pushover_wall]
"""
import argparse
import os

import matplotlib

matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402
import numpy as np  # noqa: E402

import blockdem  # noqa: E402

parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
parser.add_argument("--courses", type=int, default=20)
parser.add_argument("--resolution", type=float, default=0.005, help="of the bisection on lambda")
parser.add_argument("--out", default="pushover_wall")
args = parser.parse_args()

head = max(args.courses - 4, 2)
model = blockdem.generate.wall(length=2.0, courses=args.courses, openings=[(0.75, 1.25, head // 3, head)], pushover=True)
model.pushover(axis="y", resolution=args.resolution)
print(model.check()["contact_points"], "contact points;", model.blocks, "blocks")
result = blockdem.run(model, out=args.out)
print(result)

t = result.trials
order = np.argsort(t["lambda"])
fig, ax = plt.subplots(figsize=(7, 4.2))
ax.semilogy(t["lambda"][order], 1e3 * t["max_displacement"][order], "-", color="0.7", zorder=1)
ax.scatter(t["lambda"][t["stands"]], 1e3 * t["max_displacement"][t["stands"]], c="tab:blue", label="stands", zorder=2)
ax.scatter(t["lambda"][~t["stands"]], 1e3 * t["max_displacement"][~t["stands"]], c="tab:red", marker="x",
           label="collapses", zorder=2)
ax.axvline(result.collapse_multiplier, color="k", lw=0.8)
ax.axhline(1e3 * result.collapse_displacement, color="tab:red", lw=0.8, ls="--", label="collapse displacement")
ax.set(xlabel="lambda (body acceleration / g, out of plane)", ylabel="largest displacement [mm]",
       title="%s: collapse multiplier %.3f" % (model.name, result.collapse_multiplier))
ax.legend(fontsize=8)
fig.tight_layout()
png = os.path.join(args.out, "pushover_trials.png")
fig.savefig(png, dpi=130)
print("wrote", png, "(and the blocks as they stood and fell: pushover_*.vtu for ParaView)")
