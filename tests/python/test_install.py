# `cmake --install` puts the package where its interpreter finds it (staged here with DESTDIR), and that copy imports
# and runs on its own, away from the build folder.
import os
import subprocess
import sys

import pytest


def test_installed_package_imports_and_runs(tmp_path):
    build = os.environ.get("BLOCKDEM_BUILD_DIR")
    if not build:
        pytest.skip("BLOCKDEM_BUILD_DIR is not set")
    stage = tmp_path / "stage"
    done = subprocess.run(["cmake", "--install", build, "--component", "python"], env={**os.environ, "DESTDIR": str(stage)},
                          capture_output=True, text=True)
    assert done.returncode == 0, done.stderr
    found = [root for root, _, files in os.walk(stage) if "__init__.py" in files and os.path.basename(root) == "blockdem"]
    assert len(found) == 1, found
    site = os.path.dirname(found[0])
    assert sorted(f for f in os.listdir(found[0]) if not f.startswith("__pycache__"))[:2] == ["__init__.py", "_build.py"]
    env = {k: v for k, v in os.environ.items() if k != "PYTHONPATH"}
    env["PYTHONPATH"] = site
    script = "import blockdem; print(blockdem.__file__); print(blockdem.fit_maxwell().alpha.sum())"
    done = subprocess.run([sys.executable, "-c", script], env=env, cwd=tmp_path, capture_output=True, text=True)
    assert done.returncode == 0, done.stderr
    assert done.stdout.splitlines()[0].startswith(site)
    assert float(done.stdout.splitlines()[1]) == pytest.approx(0.28364, rel=1e-4)
