#!/usr/bin/env bash
# Times full DEM capacity runs: runs `masonry dem CASE` N times on one core and prints each run's
# timing.total_s (the run's own thread CPU time without file writing), its wall time, cycles and
# capacity, then the median CPU time and the time per contact point per cycle.
#
#   bash bench/dem-capacity.sh [-n N] [-c CORE] [-b BUILD_DIR] CASE [masonry dem options...]
#
# Examples (the paper's settings; quote the medians):
#   bash bench/dem-capacity.sh -n 5 cases/pointed-arch.json --stiffness-reduction 10
#   bash bench/dem-capacity.sh -n 1 cases/cathedral-settlement.json
set -euo pipefail

runs=3
core=0
build=build
while getopts "n:c:b:" opt; do
  case $opt in
    n) runs=$OPTARG ;;
    c) core=$OPTARG ;;
    b) build=$OPTARG ;;
    *) echo "usage: $0 [-n N] [-c CORE] [-b BUILD_DIR] CASE [masonry dem options...]" >&2; exit 2 ;;
  esac
done
shift $((OPTIND - 1))
if [ $# -lt 1 ]; then
  echo "usage: $0 [-n N] [-c CORE] [-b BUILD_DIR] CASE [masonry dem options...]" >&2
  exit 2
fi
case_file=$1
shift
exe=$build/app/masonry
[ -x "$exe" ] || { echo "$0: no executable $exe (build first, or pass -b BUILD_DIR)" >&2; exit 2; }
[ "$runs" -ge 1 ] 2>/dev/null || { echo "$0: -n must be a positive integer" >&2; exit 2; }

out=$(mktemp -d)
trap 'rm -rf "$out"' EXIT
times=()
for ((i = 1; i <= runs; i++)); do
  # Exit code 1 is a finished run without a located capacity (undecided): still timed.
  rc=0
  taskset -c "$core" "$exe" dem "$case_file" --out "$out/run$i" --quiet "$@" || rc=$?
  [ "$rc" -le 1 ] || exit "$rc"
  line=$(python3 - "$out/run$i/results.json" <<'EOF'
import json, sys
r = json.load(open(sys.argv[1]))
t = r["timing"]
points = sum(s.get("contact_points", 0) * s.get("cycles", 0) for s in r["steps"])
per_point = t["total_s"] / points * 1e9 if points else float("nan")
print(f'{t["total_s"]:.3f} wall {r.get("wall_s", float("nan")):.1f} s, {t["cycles"]} cycles, '
      f'{t["total_s"] / max(t["cycles"], 1) * 1e6:.2f} us/cycle, ~{per_point:.1f} ns per contact point per cycle, '
      f'capacity {r["capacity"]:.6g} m ({r["stopped"]})')
EOF
)
  echo "run $i: cpu $line"
  times+=("${line%% *}")
done
printf '%s\n' "${times[@]}" | sort -g | awk '{a[NR] = $1} END {m = (NR % 2) ? a[(NR + 1) / 2] : (a[NR / 2] + a[NR / 2 + 1]) / 2; printf "median cpu %.3f s over %d runs\n", m, NR}'
