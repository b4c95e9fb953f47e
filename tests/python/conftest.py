# Shared by the Python module's tests (run by ctest: tests/python/CMakeLists.txt gives the environment): where the
# programs are, to compare with, and the strong-motion records of ../shared/data (tests that read them are skipped
# when it is absent).
import json
import os
import subprocess

import pytest


@pytest.fixture(scope="session")
def programs():
    """The folder of the built programs (blockdem, maxwell_fit, ground_motion)."""
    folder = os.environ.get("BLOCKDEM_PROGRAMS")
    if not folder or not os.path.isdir(folder):
        pytest.skip("BLOCKDEM_PROGRAMS names no folder of built programs")
    return folder


@pytest.fixture(scope="session")
def run_program(programs):
    """run_program(name, *args) -> stdout, failing the test on a non-zero exit."""
    def run(name, *args, cwd=None):
        done = subprocess.run([os.path.join(programs, name), *map(str, args)], capture_output=True, text=True, cwd=cwd)
        assert done.returncode == 0, "%s %s: exit %d\n%s" % (name, " ".join(map(str, args)), done.returncode, done.stderr)
        return done.stdout
    return run


@pytest.fixture(scope="session")
def program_json(run_program):
    return lambda name, *args: json.loads(run_program(name, *args))


@pytest.fixture(scope="session")
def shared_data():
    folder = os.environ.get("BLOCKDEM_SHARED_DATA", "")
    if not folder or not os.path.isdir(folder):
        pytest.skip("the strong-motion records of ../shared/data are absent")
    return folder


@pytest.fixture(scope="session")
def source_dir():
    return os.environ.get("BLOCKDEM_SOURCE_DIR", os.path.dirname(os.path.dirname(os.path.dirname(os.path.abspath(__file__)))))
