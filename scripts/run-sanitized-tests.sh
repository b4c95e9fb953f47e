#!/usr/bin/env bash
# Builds the tests and programs with AddressSanitizer and UndefinedBehaviorSanitizer (BLOCKDEM_SANITIZE: -O1, no debug
# information) in build-sanitize/ and runs every test there: any report (out-of-bounds access, use after free, leak,
# signed overflow, misaligned or null access...) aborts its test, and the script fails. Extra arguments go to the
# CMake configure step. BLOCKDEM_SANITIZE_TESTS=REGEX runs only the tests that match.
set -euo pipefail
cd "$(dirname "$0")/.."
build=${BLOCKDEM_SANITIZE_BUILD:-build-sanitize}
cmake -S . -B "$build" -G Ninja -DCMAKE_BUILD_TYPE=Sanitize -DBLOCKDEM_SANITIZE=ON -DBLOCKDEM_BUILD_BENCHMARKS=OFF \
      -DBLOCKDEM_WITH_MPI=OFF -DBLOCKDEM_INSTALL=OFF "$@"
cmake --build "$build" --parallel 2
export ASAN_OPTIONS=abort_on_error=1:detect_leaks=1:strict_string_checks=1:detect_stack_use_after_return=1:check_initialization_order=1
export UBSAN_OPTIONS=halt_on_error=1:print_stacktrace=1
ctest --test-dir "$build" --output-on-failure --parallel 2 ${BLOCKDEM_SANITIZE_TESTS:+-R "$BLOCKDEM_SANITIZE_TESTS"}
