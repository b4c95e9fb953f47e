# The Python examples (examples/python/), each run as a user runs it in a short variant: each must finish and leave
# its plot.
import os
import subprocess
import sys

import pytest


@pytest.fixture(scope="module")
def examples(source_dir):
    return os.path.join(source_dir, "examples", "python")


def run(examples, tmp_path, script, *args):
    done = subprocess.run([sys.executable, os.path.join(examples, script), *map(str, args)], cwd=tmp_path,
                          capture_output=True, text=True, timeout=300)
    assert done.returncode == 0, done.stderr
    return done.stdout


def test_maxwell_vs_mass(examples, tmp_path):
    out = run(examples, tmp_path, "maxwell_vs_mass.py", "--out", "curves.png")
    assert "Maxwell N=3: alpha [0.0958 0.0725 0.1153]" in out
    assert (tmp_path / "curves.png").stat().st_size > 10000


def test_pushover_wall(examples, tmp_path):
    out = run(examples, tmp_path, "pushover_wall.py", "--courses", 8, "--resolution", 0.05, "--out", "push")
    assert "PushoverResult(collapse_multiplier=" in out
    assert (tmp_path / "push" / "pushover_trials.png").stat().st_size > 10000
    assert (tmp_path / "push" / "pushover.csv").exists()


def test_ida(examples, tmp_path):
    out = run(examples, tmp_path, "ida.py", "--pga", 0.1, 0.3, "--window", 2, "--courses", 6, "--out", "ida")
    assert out.count("PGA 0.10 g") >= 1 and "wrote" in out
    assert (tmp_path / "ida" / "ida.png").stat().st_size > 10000
