#!/usr/bin/env bash
# Builds the libFuzzer harnesses of the readers of outside data (tests/fuzz/fuzz_*.cpp) with clang, AddressSanitizer
# and UndefinedBehaviorSanitizer, and runs each for a while from its seed corpus (tests/fuzz/corpus/<name>/, copied
# to OUT: the repository is only read). A crash, a sanitizer report, a leak, an input slower than 10 s, more than
# 2 GB of memory, an exception other than InvalidArgument/InputError or a harness that does not build fails the
# run; what failed is kept in OUT/artifacts/<name>/ with the command that reproduces it.
#
#   scripts/run-fuzzers.sh [--seconds N] [--jobs J] [--out DIR] [HARNESS...]
#     --seconds N   fuzzing time per harness (default 60)
#     --jobs J      harnesses built and fuzzed at a time (default: the number of cores)
#     --out DIR     binaries, working corpora, logs and artifacts (default build-fuzz)
#     HARNESS       names such as motion_record or fuzz_checkpoint (default: every tests/fuzz/fuzz_*.cpp)
#
# Needs clang++ (FUZZ_CXX=another one) and libFuzzer's runtime: the Debian packages clang and libclang-rt-14-dev.
set -euo pipefail

usage() { sed -n '8,14p' "$0" | sed 's/^# \{0,1\}//'; }

seconds=60
jobs=$(nproc 2>/dev/null || echo 1)
out=build-fuzz
names=()
while [ $# -gt 0 ]; do
  case "$1" in
    --seconds) [ $# -ge 2 ] || { usage >&2; exit 2; }; seconds=$2; shift 2 ;;
    --seconds=*) seconds=${1#*=}; shift ;;
    --jobs) [ $# -ge 2 ] || { usage >&2; exit 2; }; jobs=$2; shift 2 ;;
    --jobs=*) jobs=${1#*=}; shift ;;
    --out) [ $# -ge 2 ] || { usage >&2; exit 2; }; out=$2; shift 2 ;;
    --out=*) out=${1#*=}; shift ;;
    -h|--help) usage; exit 0 ;;
    -*) echo "run-fuzzers.sh: unknown option '$1'" >&2; usage >&2; exit 2 ;;
    *) names+=("${1#fuzz_}"); shift ;;
  esac
done
case "$seconds" in
  ''|*[!0-9]*|0) echo "run-fuzzers.sh: --seconds must be a whole number of seconds >= 1, got '$seconds'" >&2; exit 2 ;;
esac
case "$jobs" in
  ''|*[!0-9]*|0) echo "run-fuzzers.sh: --jobs must be a whole number >= 1, got '$jobs'" >&2; exit 2 ;;
esac

# OUT relative to where the script was called from; everything else relative to the repository.
case "$out" in /*) ;; *) out="$PWD/$out" ;; esac
cd "$(dirname "$0")/.."
repo=$PWD

cxx=${FUZZ_CXX:-clang++}
if ! command -v "$cxx" >/dev/null 2>&1; then
  echo "run-fuzzers.sh: $cxx not found; install clang and libFuzzer's runtime:" >&2
  echo "  apt-get install clang libclang-rt-14-dev   (or: scripts/install-deps.sh --fuzz)" >&2
  exit 1
fi
eigen=/usr/include/eigen3
if [ ! -d "$eigen" ]; then
  echo "run-fuzzers.sh: Eigen not found in $eigen; install it: apt-get install libeigen3-dev" >&2
  exit 1
fi

mkdir -p "$out/bin" "$out/corpus" "$out/logs" "$out/artifacts"
probe="$out/bin/.probe"
printf 'extern "C" int LLVMFuzzerTestOneInput(const unsigned char*, unsigned long) { return 0; }\n' > "$probe.cpp"
if ! "$cxx" -fsanitize=fuzzer,address,undefined "$probe.cpp" -o "$probe" > "$probe.log" 2>&1; then
  echo "run-fuzzers.sh: $cxx cannot link a fuzzer (-fsanitize=fuzzer); install libFuzzer's runtime:" >&2
  echo "  apt-get install clang libclang-rt-14-dev   (or: scripts/install-deps.sh --fuzz)" >&2
  sed 's/^/  /' "$probe.log" >&2
  exit 1
fi
rm -f "$probe" "$probe.cpp" "$probe.log"

if [ ${#names[@]} -eq 0 ]; then
  for source in tests/fuzz/fuzz_*.cpp; do
    name=${source##*/fuzz_}
    names+=("${name%.cpp}")
  done
fi
for name in "${names[@]}"; do
  [ -f "tests/fuzz/fuzz_$name.cpp" ] || {
    echo "run-fuzzers.sh: no harness tests/fuzz/fuzz_$name.cpp (have: $(cd tests/fuzz && ls fuzz_*.cpp | tr '\n' ' '))" >&2
    exit 2
  }
done

# Sanitizer reports stop the run and say where; the options of the caller stay, these win.
sanitizer_env=(
  "ASAN_OPTIONS=${ASAN_OPTIONS:+$ASAN_OPTIONS:}halt_on_error=1:detect_leaks=1:print_stacktrace=1"
  "UBSAN_OPTIONS=${UBSAN_OPTIONS:+$UBSAN_OPTIONS:}halt_on_error=1:print_stacktrace=1"
)
symbolizer=$(command -v llvm-symbolizer || command -v llvm-symbolizer-14 || true)
[ -n "$symbolizer" ] && sanitizer_env+=("ASAN_SYMBOLIZER_PATH=$symbolizer")
# Readers that take a path get their input written under TMPDIR: in memory where there is /dev/shm.
scratch=$(mktemp -d "$( [ -d /dev/shm ] && [ -w /dev/shm ] && echo /dev/shm || echo "${TMPDIR:-/tmp}")/blockdem-fuzz.XXXXXX")
trap 'rm -rf "$scratch"' EXIT
sanitizer_env+=("TMPDIR=$scratch")

flags=(-std=c++20 -O1 -g0 -fsanitize=fuzzer,address,undefined -fno-sanitize-recover=all -Iinclude -isystem "$eigen")

# One harness: build, seeds, fuzz. Its report goes to OUT/logs/NAME.report, its row of the summary to
# OUT/logs/NAME.summary; the status says whether it passed.
fuzz_one() {
  local name=$1
  printf_summary() { echo "$1" > "$out/logs/$name.summary"; }
  bin="$out/bin/fuzz_$name"
  corpus="$out/corpus/$name"
  artifacts="$out/artifacts/$name"
  log="$out/logs/$name.log"
  rm -rf "$artifacts"
  mkdir -p "$corpus" "$artifacts"

  echo "== $name: building"
  build_start=$(date +%s)
  if ! nice -n 10 "$cxx" "${flags[@]}" "tests/fuzz/fuzz_$name.cpp" -o "$bin" > "$out/logs/$name.build.log" 2>&1; then
    echo "   build failed (log: $out/logs/$name.build.log):"
    grep -m 20 -E "error|Error" "$out/logs/$name.build.log" | sed 's/^/   /' || true
    printf_summary "$(printf '%-16s %6s %12s %8s %7s %7s %15s  FAIL (does not build)' "$name" - - - - - -)"
    return 1
  fi
  build_seconds=$(( $(date +%s) - build_start ))

  # Seeds: the files in the repository, and those a harness writes itself (real payloads of the current format).
  if [ -d "tests/fuzz/corpus/$name" ]; then cp -n "tests/fuzz/corpus/$name"/* "$corpus"/ 2>/dev/null || true; fi
  if grep -q BLOCKDEM_FUZZ_WRITE_SEEDS "tests/fuzz/fuzz_$name.cpp"; then
    if ! env "${sanitizer_env[@]}" BLOCKDEM_FUZZ_WRITE_SEEDS="$corpus" "$bin" > "$out/logs/$name.seeds.log" 2>&1; then
      echo "   writing its seeds failed (log: $out/logs/$name.seeds.log)"
      printf_summary "$(printf '%-16s %6s %12s %8s %7s %7s %15s  FAIL (writing its seeds)' "$name" - - - - - -)"
      return 1
    fi
  fi

  echo "== $name: fuzzing for $seconds s (built in $build_seconds s)"
  fuzz_start=$(date +%s)
  status=0
  (cd "$artifacts" && env "${sanitizer_env[@]}" timeout --kill-after=30 $((seconds + 300)) "$bin" \
      -max_total_time="$seconds" -timeout=10 -rss_limit_mb=2048 -print_final_stats=1 \
      -artifact_prefix="$artifacts/" "$corpus") > "$log" 2>&1 || status=$?
  fuzz_seconds=$(( $(date +%s) - fuzz_start ))

  execs=$(grep -a 'stat::number_of_executed_units' "$log" | tail -1 | awk '{print $2}')
  rate=$(grep -a 'stat::average_exec_per_sec' "$log" | tail -1 | awk '{print $2}')
  last=$(grep -a -E '^#[0-9]+.*cov: [0-9]+ ft: [0-9]+' "$log" | tail -1 || true)
  cov=$(sed -n 's/.*cov: \([0-9]*\).*/\1/p' <<< "$last")
  ft=$(sed -n 's/.*ft: \([0-9]*\).*/\1/p' <<< "$last")
  files=$(find "$corpus" -type f | wc -l)
  kbytes=$(find "$corpus" -type f -printf '%s\n' | awk '{s += $1} END {printf "%.0f", s / 1024}')
  found=$(find "$artifacts" -type f ! -name 'slow-unit-*' | head -1)
  if [ "$status" -eq 0 ] && [ -z "$found" ]; then
    verdict=PASS
  else
    kind=$(grep -a -o -m 1 -E 'ERROR: (AddressSanitizer|LeakSanitizer|libFuzzer): [a-z0-9-]+( [a-z0-9-]+){0,3}|runtime error: .{0,90}|terminate called .{0,80}|fuzz_[a-z_]+: .{0,80}' "$log" | head -1 || true)
    verdict="FAIL (${kind:-exit status $status})"
  fi
  printf_summary "$(printf '%-16s %6s %12s %8s %7s %7s %15s  %s' "$name" "$fuzz_seconds" "${execs:--}" "${rate:--}" \
                "${cov:--}" "${ft:--}" "$files/${kbytes}kB" "$verdict")"
  echo "   $verdict after $fuzz_seconds s: ${execs:-?} executions, ${rate:-?}/s, cov ${cov:-?}, ft ${ft:-?}," \
       "corpus $files files (log: $log)"
  if [ "$verdict" != PASS ]; then
    if [ -n "$found" ]; then
      echo "   input kept: $found"
      echo "   reproduce: ASAN_OPTIONS=halt_on_error=1:detect_leaks=1 UBSAN_OPTIONS=halt_on_error=1:print_stacktrace=1 $bin $found"
    fi
    grep -a -m 12 -E 'ERROR:|SUMMARY:|runtime error|terminate called|what\(\)|^    #[0-9] |fuzz_[a-z_]+: ' "$log" | sed 's/^/   | /' || true
  fi
  [ "$verdict" = PASS ]
}

start=$(date +%s)
# J harnesses at a time (libFuzzer runs one process per harness); the reports are printed in the harnesses' order.
pids=()
for name in "${names[@]}"; do
  while [ "$(jobs -rp | wc -l)" -ge "$jobs" ]; do wait -n || true; done
  rm -f "$out/logs/$name.summary" "$out/logs/$name.status"
  ( status=0; fuzz_one "$name" > "$out/logs/$name.report" 2>&1 || status=$?; echo "$status" > "$out/logs/$name.status" ) &
  pids+=($!)
done
wait "${pids[@]}" || true
failed=0
summary=()
for name in "${names[@]}"; do
  cat "$out/logs/$name.report"
  [ "$(cat "$out/logs/$name.status" 2>/dev/null)" = 0 ] || failed=1
  summary+=("$(cat "$out/logs/$name.summary" 2>/dev/null || printf '%-16s  FAIL (no report)' "$name")")
done

echo
echo "fuzzing: $seconds s per harness, $jobs at a time, $(( $(date +%s) - start )) s in all; binaries, corpora and logs in $out"
printf '%-16s %6s %12s %8s %7s %7s %15s  %s\n' harness time_s executions exec/s cov ft corpus result
for line in "${summary[@]}"; do echo "$line"; done
exit "$failed"
