#!/usr/bin/env bash
# Soak: the rigid cross vault under 60 s of simulated time for each damping scheme (the record at its level, then
# the table at rest), run by `cross_vault run` as a user would. For each scheme: the steps and their rate, whether
# every history sample is finite, the energy balance error of the level (report.json, must be below 1 %), and the
# resident memory sampled every second from the first sample after settling to the last (memory must stay flat).
#   benchmarks/soak.sh [--program build/examples/cross_vault] [--record FILE.AT2] [--schemes "none mass ..."]
#                      [--out DIR] [-- extra cross_vault run options]
# Default: the coarse vault (bricks 0.2 x 0.7 m, 178 blocks) so that the five schemes take minutes; pass
# "-- --unit-height 0.1 --unit-length 0.35" (or nothing less than the paper's vault) for the full one.
# Stiffness-proportional and Rayleigh damping run at about 1 % of the undamped timestep (eq. 11: 3 % at the vault's
# frequency gives the factor 0.0095), so their 60 s take about 100 minutes each on two threads, the others 1-2.
set -euo pipefail
cd "$(dirname "$0")/.."
program=build/examples/cross_vault
record=../shared/data/ImperialValley1979_ElCentroArray4_140.AT2
schemes="none mass stiffness rayleigh maxwell"
out=build/soak
extra=(--unit-height 0.2 --unit-length 0.7)
while [ $# -gt 0 ]; do
  case "$1" in
    --program) program=$2; shift 2 ;;
    --record) record=$2; shift 2 ;;
    --schemes) schemes=$2; shift 2 ;;
    --out) out=$2; shift 2 ;;
    --) shift; extra=("$@"); break ;;
    *) echo "soak.sh: unknown option '$1' (see the header of $0)" >&2; exit 2 ;;
  esac
done
[ -x "$program" ] || { echo "soak.sh: no program at '$program' (build first, or give --program)" >&2; exit 2; }
[ -r "$record" ] || { echo "soak.sh: cannot read the record '$record' (give --record)" >&2; exit 2; }
command -v python3 >/dev/null || { echo "soak.sh: needs python3 to read report.json" >&2; exit 2; }

# The record's duration sets the rest that completes 60 s.
duration=$(python3 - "$record" <<'PY'
import re, sys
head = open(sys.argv[1]).read(4000)
m = re.search(r"NPTS=\s*(\d+),\s*DT=\s*([0-9.]+)", head)
print(round((int(m.group(1)) - 1) * float(m.group(2)), 6) if m else 0)  # the last sample's time
PY
)
rest=$(python3 -c "print(max(0.0, round(60 - $duration, 3)))")
mkdir -p "$out"
printf "%-10s %10s %9s %10s %8s %13s %13s %11s %11s %s\n" scheme steps wall_s steps/s finite energy_error rss_start_MB rss_end_MB peak_MB status
failed=0
for scheme in $schemes; do
  dir="$out/$scheme"
  rm -rf "$dir"
  "$program" run --record "$record" --truncate window --window 0 "$duration" --rest "$rest" --levels 25 \
    --damping "$scheme" --quiet --out "$dir" "${extra[@]}" > "$out/$scheme.log" 2>&1 &
  pid=$!
  samples=()
  while kill -0 "$pid" 2>/dev/null; do
    rss=$(awk '/^VmRSS/ {print $2}' "/proc/$pid/status" 2>/dev/null || true)
    [ -n "$rss" ] && samples+=("$rss")
    sleep 1
  done
  set +e; wait "$pid"; status=$?; set -e
  peak=$(printf "%s\n" "${samples[@]:-0}" | sort -n | tail -1)
  # The first sample after settling: the run's own memory from the dynamic run on (a tenth of the way in).
  n=${#samples[@]}
  first=${samples[$((n / 10))]:-0}
  last=${samples[$((n > 0 ? n - 2 : 0))]:-0}  # the last full sample before the process exits
  python3 - "$dir" "$scheme" "$status" "$first" "$last" "$peak" <<'PY' || failed=1
import csv, json, math, os, sys
folder, scheme, status, first, last, peak = sys.argv[1], sys.argv[2], int(sys.argv[3]), *map(int, sys.argv[4:7])
try:
    report = json.load(open(os.path.join(folder, "report.json")))
    level = report["levels"][0]
    steps, wall = level["steps"], level["wall_seconds"]
    error = level["energy"]["balance_error"]  # since the start of the dynamic run
    finite = True
    with open(os.path.join(folder, "history_25.csv")) as f:
        rows = csv.reader(f)
        next(rows)
        for row in rows:
            finite = finite and all(math.isfinite(float(x)) for x in row)
except (OSError, KeyError, IndexError, ValueError) as e:
    print(f"{scheme:<10} no result ({e}); exit status {status}")
    sys.exit(1)
ok = status == 0 and finite and error < 0.01
print(f"{scheme:<10} {steps:>10} {wall:>9.1f} {steps / wall:>10.0f} {str(finite):>8} {100 * error:>12.4f}% "
      f"{first / 1024:>13.1f} {last / 1024:>13.1f} {peak / 1024:>11.1f} {'ok' if ok else 'FAILED'}")
sys.exit(0 if ok else 1)
PY
done
exit $failed
