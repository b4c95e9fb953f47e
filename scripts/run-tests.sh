#!/usr/bin/env bash
# Configures (Release, Ninja), builds and runs every test with ctest. Extra arguments go to the CMake configure step.
set -euo pipefail
cd "$(dirname "$0")/.."
cmake -S . -B build -G Ninja -DCMAKE_BUILD_TYPE=Release "$@"
cmake --build build --parallel 2
ctest --test-dir build --output-on-failure --parallel 2
