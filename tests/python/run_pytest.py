"""Runs pytest on the files given (ctest's driver for the Python module's tests): exit status 77 (skipped) when this
interpreter has no pytest, unless BLOCKDEM_REQUIRE_PYTHON_TESTS is set."""
import importlib.util
import os
import sys

if importlib.util.find_spec("pytest") is None:
    print("SKIPPED: %s has no pytest (scripts/install-deps.sh --python installs it)" % sys.executable)
    sys.exit(1 if os.environ.get("BLOCKDEM_REQUIRE_PYTHON_TESTS") else 77)
import pytest  # noqa: E402

sys.exit(pytest.main(["-q", "-p", "no:cacheprovider", *sys.argv[1:]]))
