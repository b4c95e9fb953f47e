#!/usr/bin/env bash
# Builds the tests and programs with AddressSanitizer and UndefinedBehaviorSanitizer (BLOCKDEM_SANITIZE: -O1, no debug
# information) in build-sanitize/ and runs every test there: any report (out-of-bounds access, use after free, leak,
# signed overflow, misaligned or null access...) aborts its test, and the script fails. Extra arguments go to the
# CMake configure step. BLOCKDEM_SANITIZE_TESTS=REGEX runs only the tests that match.
#
# Left out by default (BLOCKDEM_SANITIZE_EXCLUDE, a ctest -E regex; set it empty to run them), each a long run whose
# code runs instrumented in shorter tests; the instrumented -O1 build runs 10-15 times slower than Release:
# - the mixed and deformable vaults at rest and the deformable twin of a sliding block (50 s and 11 s in Release,
#   minutes for the vaults instrumented): thousands of tetrahedra for hundreds of thousands of steps. The
#   element, node-contact and mixed-step code runs in the smaller deformable tests, the random mixed and deformable
#   models of the model fuzz and the programs' deformable runs (program.arch.deformable,
#   program.rocking_block.deformable);
# - the vault under general contacts against face-to-face ones (six runs of the coarse vault) and its collapse past
#   the paper's levels (27 s in Release: thousands of re-detections as the webs fall), and the 40-voussoir arch's
#   complete collapse onto the floor (12 s in Release, 200 s instrumented). General detection and the collapse path
#   run in the tests of general contacts, the short vault collapse at 500 % (a thousand re-detections) and the
#   arch's collapse in program.arch.collapses;
# - three vault-study checks of physics that step whole levels (the energy balance of three schemes, the free decay,
#   the vault at rest: 5-16 s in Release, 1-2 minutes each instrumented): the study's code runs in the shorter vault
#   tests (resume, outputs, threads, the table's motion, the short collapse) and in the programs' runs;
# - the undamped rocking landing over 61 timesteps (3 s in Release, 40 s instrumented): the same code in the other
#   rocking tests;
# - the vault's model file against the vault study (two coarse-vault runs, 14 s in Release), the 40-voussoir arch's
#   pushover from a model file (eight trials, 9 s in Release) and the typologies' (the window wall's and the barrel
#   vault's, 11 s in Release): the model file, the generic study and the pushover
#   run instrumented in the reader's tests, the block's and the dry wall's pushovers and the vault-study tests;
# - the programs' sweeps (program.cross_vault.sweep: fourteen coarse-vault runs on two ranks and alone, 3.5 minutes
#   instrumented; program.blockdem.sweep) and the vault's short collapse at 500 % (2 minutes instrumented, 10 s in
#   Release): the sweep's code runs instrumented in the sweep-run tests (failed, skipped, collapsed and resumed
#   cases), re-detection as blocks scatter in the general-contact tests and the arch's collapse in
#   program.arch.collapses;
# - four tests of about a minute each instrumented whose code runs instrumented in shorter ones: the arch exported
#   to OBJ and pushed over (OBJ in the geometry-file tests and program.blockdem.run_obj, the pushover in the dry
#   wall's), the vault's timestep bound against power iteration (the bound in every simulation), split local damping
#   on a sliding deformable block (program.arch.deformable) and the deformable wall's density scaling (the partial
#   density scaling of nodes in the timestep tests);
# - the arch's verdicts under inertial relaxation and the deformable 12-voussoir arch's collapse multiplier (two
#   bisections, 6 s in Release): inertial relaxation runs instrumented in its own tests (a deformable column, a mixed
#   model, one and two threads) and in the vaults' settling of the vault-study tests.
# The plotting scripts' tests (plot.*) and the CMake consumers' (cmake.*) run in the Release stage only: they test
# Python and the package, not the instrumented code; the Python module is not built here (an instrumented extension
# needs the sanitizers' runtime preloaded into the interpreter).
set -euo pipefail
cd "$(dirname "$0")/.."
build=${BLOCKDEM_SANITIZE_BUILD:-build-sanitize}
# Clang when there is one (scripts/install-deps.sh --fuzz): it builds this code with the sanitizers in about 60 % of
# GCC's time, and a second compiler reads the code too. CXX=g++ chooses GCC.
compiler=()
if [ -z "${CXX:-}" ] && command -v clang++ >/dev/null; then compiler=(-DCMAKE_CXX_COMPILER=clang++); fi
cmake -S . -B "$build" -G Ninja -DCMAKE_BUILD_TYPE=Sanitize -DBLOCKDEM_SANITIZE=ON -DBLOCKDEM_BUILD_BENCHMARKS=OFF \
      -DBLOCKDEM_WITH_MPI=OFF -DBLOCKDEM_INSTALL=OFF -DBLOCKDEM_PYTHON=OFF "${compiler[@]}" "$@"
cmake --build "$build" --parallel 2
export ASAN_OPTIONS=abort_on_error=1:detect_leaks=1:strict_string_checks=1:detect_stack_use_after_return=1:check_initialization_order=1
export UBSAN_OPTIONS=halt_on_error=1:print_stacktrace=1
exclude=${BLOCKDEM_SANITIZE_EXCLUDE-settled mixed and deformable vaults|deformable twin: a stiff deformable block|the vault runs the paper.s levels close to|the vault collapses and the study ends there|the energy balance of a level closes|the settled vault in free decay|under zero input the settled vault stays|arch collapses completely, onto the floor|the stocky block.s undamped landing never gives back|the vault.s model file through the generic study|the 40-voussoir arch as a model file|typology pushover: a free-standing dry wall with a window|typology pushover: a barrel vault pushed across|^program\\.[a-z_]+\\.sweep$|a short collapse, shaken at 500 %|the arch exported to OBJ and read back|found by power iteration on the stiffness|split local damping: a deformable block slides as a rigid one|deformable density scaling: the target timestep is reached|arch: inertial relaxation finds local damping|^plot\\.|^cmake\\.}
ctest --test-dir "$build" --output-on-failure --parallel 2 ${BLOCKDEM_SANITIZE_TESTS:+-R "$BLOCKDEM_SANITIZE_TESTS"} \
      ${exclude:+-E "$exclude"}
