#!/usr/bin/env bash
# Installs, from Debian packages, what blockdem needs to build, test, run its examples and benchmarks: only what is
# missing, non-interactively. Idempotent: a second run installs nothing.
#   scripts/install-deps.sh            compiler, CMake, Ninja, Eigen, Boost, doctest, CLI11, fmt, Google Benchmark,
#                                      OpenMPI (for `cross_vault sweep` on MPI ranks)
#   scripts/install-deps.sh --plots    also Python with numpy and matplotlib for the plotting scripts
#   scripts/install-deps.sh --minpack  also scipy, for benchmarks/minpack_reference.py
#   scripts/install-deps.sh --python   also pybind11, Python's headers, numpy, matplotlib and pytest: the Python module
#                                      (built by CMake for the system's Python, docs/python.md), its examples and tests
#   scripts/install-deps.sh --fuzz     also clang, libFuzzer and OpenMP for clang: scripts/run-fuzzers.sh and
#                                      scripts/run-sanitized-tests.sh
set -euo pipefail

packages=(g++ cmake ninja-build libeigen3-dev libboost-dev doctest-dev libcli11-dev libfmt-dev libbenchmark-dev
          libopenmpi-dev openmpi-bin)
for arg in "$@"; do
  case "$arg" in
    --plots) packages+=(python3 python3-numpy python3-matplotlib) ;;
    --minpack) packages+=(python3 python3-numpy python3-scipy) ;;
    --python) packages+=(python3 python3-dev python3-numpy python3-matplotlib python3-pytest pybind11-dev) ;;
    --fuzz) packages+=(clang libclang-rt-14-dev libomp-dev) ;;
    -h|--help) sed -n '2,11p' "$0"; exit 0 ;;
    *) echo "install-deps.sh: unknown option '$arg' (allowed: --plots, --minpack, --python, --fuzz)" >&2; exit 2 ;;
  esac
done

missing=()
for p in "${packages[@]}"; do
  if ! dpkg-query -W -f='${Status}' "$p" 2>/dev/null | grep -q "install ok installed"; then
    missing+=("$p")
  fi
done
if [ ${#missing[@]} -eq 0 ]; then
  echo "install-deps.sh: all dependencies are installed"
  exit 0
fi

sudo=""
if [ "$(id -u)" -ne 0 ]; then
  command -v sudo >/dev/null 2>&1 || { echo "install-deps.sh: run as root or install sudo" >&2; exit 1; }
  sudo="sudo"
fi
echo "install-deps.sh: installing ${missing[*]}"
export DEBIAN_FRONTEND=noninteractive
$sudo apt-get update -qq
$sudo apt-get install -y -qq --no-install-recommends "${missing[@]}"
