"""What calling blockdem from Python costs on real runs (docs/python.md): the vault's level run by blockdem.run and
by `blockdem run` on the same model file, taking turns (medians and spread of the level's wall time); and reading the
state of the vault's contact points into numpy (Simulation.contacts(), median of many calls).

    build/python/blockdem-python benchmarks/python_overhead.py [--rounds 3] [--window 2 3]
"""
import argparse
import json
import os
import statistics
import subprocess
import tempfile
import time

import blockdem

parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
parser.add_argument("--rounds", type=int, default=3)
parser.add_argument("--window", type=float, nargs=2, default=(2.0, 3.0))
parser.add_argument("--program", default=os.path.join("build", "examples", "blockdem"))
args = parser.parse_args()

vault = blockdem.generate.cross_vault()
work = tempfile.mkdtemp(prefix="python_overhead_")
path = os.path.join(work, "vault.json")
vault.save(path)
options = ["--levels", "75", "--window", str(args.window[0]), str(args.window[1]), "--rest", "0.5", "--quiet"]

python_s, program_s = [], []


def python_run(k):
    r = blockdem.run(vault, out=os.path.join(work, "python_%d" % k), levels=[75], window=tuple(args.window), rest=0.5,
                     progress=False)
    python_s.append(r.level(75)["wall_seconds"])


def program_run(k):
    subprocess.run([args.program, "run", path, *options, "--out", os.path.join(work, "program_%d" % k)], check=True,
                   capture_output=True)
    with open(os.path.join(work, "program_%d" % k, "report.json")) as f:
        program_s.append(json.load(f)["levels"][0]["wall_seconds"])


for k in range(args.rounds):  # taking turns, each first in every other round
    for run in ((python_run, program_run) if k % 2 == 0 else (program_run, python_run)):
        run(k)
    print("round %d: Python %.2f s, program %.2f s" % (k, python_s[-1], program_s[-1]))
ratios = [p / q for p, q in zip(python_s, program_s)]
print("level at 75 %%, %g-%g s: Python median %.2f s (%.2f-%.2f), program median %.2f s (%.2f-%.2f); "
      "paired ratio Python/program median %.4f (%.4f-%.4f)"
      % (*args.window, statistics.median(python_s), min(python_s), max(python_s), statistics.median(program_s),
         min(program_s), max(program_s), statistics.median(ratios), min(ratios), max(ratios)))

sim = blockdem.Simulation(vault, progress=False)
calls = []
for _ in range(30):
    t0 = time.perf_counter()
    c = sim.contacts()
    calls.append(time.perf_counter() - t0)
print("contacts(): %d contact points into numpy in %.3f ms (median of 30; %.3f-%.3f)"
      % (len(c["area"]), 1e3 * statistics.median(calls), 1e3 * min(calls), 1e3 * max(calls)))
t0 = time.perf_counter()
for _ in range(1000):
    sim.block_positions
print("block_positions (a view of %d blocks): %.2f us per read" % (len(sim.block_names), 1e3 * (time.perf_counter() - t0)))
