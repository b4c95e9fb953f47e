"""blockdem: the distinct element method for the seismic analysis of masonry, from Python.

Build a block structure (or load a model file, or generate a wall, arch or vault), run its seismic study or its
pushover, and read the results as numpy arrays:

    import blockdem
    model = blockdem.generate.wall(courses=10, openings=[(0.75, 1.25, 3, 8)])
    result = blockdem.run(model, out="wall_run", levels=[50, 100])
    history = result.history(100)          # {'time': s, 'top_uy': m, ...}

Units are SI throughout (m, kg, s, N, Pa). The manual: docs/python.md. Parts:

- models: Model, load, generate (wall, barrel_vault, arch, cross_vault), Model.check, Model.save;
- studies: run (the levels of a record, or the pushover), StudyResult, PushoverResult; Simulation (your own loop:
  settle, set_record, run, and the state as numpy arrays); sweep (many studies: damping grids, records, IDA),
  SweepResult;
- damping: fit_maxwell, damping_ratio;
- ground motion: Record, read_record, synthetic_aqa75, correct_baseline, arias_intensity, arias_history,
  significant_duration, response_spectrum, truncate_window, wavelet_truncation.
"""

import sys as _sys

from . import _build

_here = "%d.%d" % _sys.version_info[:2]
_built = ".".join(_build.python_version.split(".")[:2])


def _wrong_interpreter(why):
    return ImportError(
        "blockdem was built for %s (Python %s, numpy %s); this is %s (Python %s), %s. Run it with %s (the build's "
        "launcher: build/python/blockdem-python script.py), or build blockdem for this interpreter: "
        "cmake -S . -B build -DPython_EXECUTABLE=%s (it needs Python's headers and numpy)"
        % (_build.python, _build.python_version, _build.numpy_version, _sys.executable,
           "%d.%d.%d" % _sys.version_info[:3], why, _build.python, _sys.executable))


if _here != _built:
    raise _wrong_interpreter("another version")
try:
    import numpy as _numpy  # noqa: F401  (the compiled part returns numpy arrays)
except ImportError:
    raise _wrong_interpreter("which has no numpy") from None
try:
    from . import _core
except ImportError as _error:
    raise _wrong_interpreter("which cannot load the compiled part (%s)" % _error) from None

from ._core import (InputError, MaxwellFit, Record, RunawayError, arias_history, arias_intensity, correct_baseline,
                    damping_ratio, fit_maxwell, read_record, response_spectrum, significant_duration, synthetic_aqa75,
                    truncate_window, wavelet_truncation)
from . import generate
from .model import Model, load
from .simulation import Simulation
from .study import PushoverResult, StudyResult, read_history, run
from .sweep import SweepResult, sweep

__version__ = _build.blockdem_version
__all__ = ["Model", "load", "generate", "run", "Simulation", "sweep", "SweepResult", "StudyResult", "PushoverResult", "read_history", "fit_maxwell",
           "MaxwellFit", "damping_ratio", "Record", "read_record", "synthetic_aqa75", "correct_baseline",
           "arias_intensity", "arias_history", "significant_duration", "response_spectrum", "truncate_window",
           "wavelet_truncation", "InputError", "RunawayError"]
