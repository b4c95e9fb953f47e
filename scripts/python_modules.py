"""Finding a Python that has the modules a script needs. The `python3` on a user's PATH is often not the system's
(pyenv, conda, a venv, Homebrew) and does not see the modules Debian installs for /usr/bin/python3. A script calls
require_modules() before it imports them: when the running interpreter lacks one and the system Python has them all,
the script runs again there (once, saying so on one line); when neither has them, it stops with a message that names
each interpreter, what it lacks, and the command that installs it.

BLOCKDEM_SYSTEM_PYTHON names the interpreter tried second (default /usr/bin/python3). Standard library only."""
import importlib
import os
import subprocess
import sys

SYSTEM_PYTHON = "/usr/bin/python3"
_RERUN = "BLOCKDEM_PYTHON_RERUN"  # set for the second run, so that a script never re-runs itself in a loop
_PROBE = ("import importlib, sys\n"
          "missing = []\n"
          "for name in sys.argv[1:]:\n"
          "    try:\n"
          "        importlib.import_module(name)\n"
          "    except Exception:\n"
          "        missing.append(name)\n"
          "print(' '.join(missing))\n")

PLOTS = {"modules": ("numpy", "matplotlib"), "packages": ("python3-numpy", "python3-matplotlib"), "option": "--plots"}
MINPACK = {"modules": ("numpy", "scipy"), "packages": ("python3-numpy", "python3-scipy"), "option": "--minpack"}


def _missing_here(modules):
    missing = []
    for name in modules:
        try:
            importlib.import_module(name)
        except Exception:  # ImportError, or a module that is installed but broken (an ABI mismatch raises others)
            missing.append(name)
    return missing


def _missing_in(python, modules):
    """The modules `python` cannot import, or None when it cannot be run."""
    env = dict(os.environ)
    env.pop("PYTHONHOME", None)  # belongs to the running interpreter (conda), not to the system one
    try:
        probe = subprocess.run([python, "-c", _PROBE, *modules], env=env, stdin=subprocess.DEVNULL,
                               capture_output=True, text=True, timeout=120)
    except (OSError, subprocess.SubprocessError):
        return None
    if probe.returncode != 0:
        return None
    return probe.stdout.split()


def _install_deps_command():
    path = os.path.join(os.path.dirname(os.path.abspath(__file__)), "install-deps.sh")
    relative = os.path.relpath(path)
    return path if relative.startswith("..") else os.path.join(".", relative) if os.sep not in relative else relative


def _is_system(here, system):
    """Whether the running interpreter is the system Python itself (a venv made from it is not)."""
    if os.environ.get(_RERUN) == "1":
        return True
    same_binary = os.path.exists(system) and os.path.realpath(here) == os.path.realpath(system)
    return same_binary and sys.prefix == sys.base_prefix


def require_modules(script, needs=PLOTS):
    """Returns when the running interpreter can import every module of `needs`; otherwise runs `script` (a path,
    normally __file__ of the caller) again under the system Python with the same arguments, or exits with a message
    saying which interpreter lacks what and how to install it."""
    name = os.path.basename(script)
    modules = needs["modules"]
    missing = _missing_here(modules)
    if not missing:
        return
    here = sys.executable or "python3"
    system = os.environ.get("BLOCKDEM_SYSTEM_PYTHON") or SYSTEM_PYTHON
    debian = f"{_install_deps_command()} {needs['option']} (Debian's {' '.join(needs['packages'])})"
    if _is_system(here, system):
        sys.exit(f"{name}: {here} has no {' or '.join(missing)}; install: {debian}")

    runnable = os.path.isfile(system) and os.access(system, os.X_OK)
    system_missing = _missing_in(system, modules) if runnable else None
    if system_missing == []:
        print(f"{name}: {here} has no {' or '.join(missing)}; running with {system}, which has them",
              file=sys.stderr, flush=True)
        sys.stdout.flush()
        env = dict(os.environ)
        env[_RERUN] = "1"
        env.pop("PYTHONHOME", None)
        os.execve(system, [system, os.path.abspath(script), *sys.argv[1:]], env)

    lines = [f"{name}: needs {' and '.join(modules)}, and no Python here has them all; install them for either:",
             f"  {here} (the python3 running this script) has no {' or '.join(missing)}: "
             f"{here} -m pip install {' '.join(missing)}"]
    if not runnable:
        lines.append(f"  there is no system Python at {system}: {debian}")
    elif system_missing is None:
        lines.append(f"  {system} (the system Python) could not be run to look for them")
    else:
        lines.append(f"  {system} (the system Python) has no {' or '.join(system_missing)}: {debian}")
    sys.exit("\n".join(lines))
