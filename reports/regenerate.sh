#!/usr/bin/env bash
# Rebuilds the PRD-against-DEM reports of the three standard cases at the paper's friction angle
# (35 degrees) into reports/compare-<case>/, each checked against reports/paper-tolerances.json.
#
#   bash reports/regenerate.sh            # runs PRD and DEM again (the cathedrals' DEM runs take 1-2.5 CPU minutes each, 2026-11-25)
#   bash reports/regenerate.sh --render   # only redraws the reports from the results already there
#                                         # (not in git: a full run writes them, reports/README.md)
#
# Uses build/app/masonry (override with MASONRY=path). A case that exceeds a limit still gets
# its report (which says which limit); the script lists those cases and exits 1.
#
# The runs are kept compressed (results.json.xz, xz -9e: a sixth of the 2-10 MB of JSON each;
# `masonry compare --runs`, `prd --from` and `tradeoff --reference-dem` read a results.json.xz
# where results.json is asked for). A results.json found in a run directory (a new run, or one
# copied in from a DEM study) is compressed after the report is drawn, replacing the older .xz.
set -uo pipefail
cd "$(dirname "$0")/.."
masonry=${MASONRY:-build/app/masonry}
tolerances=reports/paper-tolerances.json
render=0
[ "${1:-}" = "--render" ] && render=1

# Per case: the DEM settings of the paper (Section 3.3: the arch's joint stiffnesses divided by 10;
# the cathedral's as they are), and the case's own increments (1 mm for the arch, 1 cm for the
# cathedral).
declare -A extra=(
  [pointed-arch]="--stiffness-reduction 10"
  [cathedral-settlement]=""
  [cathedral-settlement-rotation]=""
)
failed=()
if [ $render = 1 ]; then
  for d in reports/compare-*/prd reports/compare-*/dem; do
    [ -f "$d/results.json.xz" ] || [ -f "$d/results.json" ] || {
      echo "regenerate: --render needs the runs, and $d has none (they are not in git): run bash reports/regenerate.sh first" >&2
      exit 2
    }
  done
fi
# Compresses the runs of a comparison directory (every results.json under it).
pack() { find "$1" -mindepth 2 -maxdepth 2 -name results.json -exec xz -9e -f {} \; ; }
# A report's notes.txt, where there is one, says in mechanical terms why a check fails.
notes() { [ -f "$1/notes.txt" ] && echo "--notes $1/notes.txt"; }
for name in pointed-arch cathedral-settlement cathedral-settlement-rotation; do
  out=reports/compare-$name
  if [ $render = 1 ]; then
    # shellcheck disable=SC2086
    "$masonry" compare cases/$name.json --out "$out" --runs "$out/prd" "$out/dem" --tolerances $tolerances $(notes "$out") --quiet || failed+=("$name")
  else
    # shellcheck disable=SC2086
    "$masonry" compare cases/$name.json --out "$out" --friction 35 ${extra[$name]} --tolerances $tolerances $(notes "$out") || failed+=("$name")
  fi
  pack "$out"
done
# The settlement scene with joints 30 times stiffer than the case's (dem/README.md, "Joint
# stiffness"): PRD's blocks are rigid, the limit of stiffening joints, so this shows whether the
# settlement comparison's difference is the elastic model's. Not a paper case: its limits are
# reported, not required. Its PRD run is compare-cathedral-settlement's. The DEM's holds are capped
# at 150 s: at this stiffness the structure near its capacity moves so slowly that at the 30 s cap
# the run stops undecided (reports/dem-stiffness/). About 30-40 CPU minutes (1798-1953 s on 2026-11-25, 2373 s on 2026-11-27).
out=reports/compare-cathedral-settlement-stiff-joints
if [ $render = 0 ]; then
  "$masonry" dem cases/cathedral-settlement.json --friction 35 --stiffness-reduction 0.03333333333333333 --hold-time 150 --out "$out/dem" --quiet
fi
"$masonry" compare cases/cathedral-settlement.json --out "$out" --runs reports/compare-cathedral-settlement/prd "$out/dem" --tolerances $tolerances $(notes "$out") --quiet
pack "$out"
# The same joints with contact damping (dem/README.md, "Contact damping"; not the default): the
# crown of the run above slides because joints this stiff ratchet on the vibration that local
# damping leaves alone; with the joints' relative motion damped they do not. About 8-10 CPU
# minutes (2026-11-28).
out=reports/compare-cathedral-settlement-stiff-joints-contact-damping
if [ $render = 0 ]; then
  "$masonry" dem cases/cathedral-settlement.json --friction 35 --stiffness-reduction 0.03333333333333333 --hold-time 150 --contact-damping 0.3 --out "$out/dem" --quiet
fi
"$masonry" compare cases/cathedral-settlement.json --out "$out" --runs reports/compare-cathedral-settlement/prd "$out/dem" --tolerances $tolerances $(notes "$out") --quiet
pack "$out"
if [ ${#failed[@]} -gt 0 ]; then
  echo "regenerate: limits exceeded (or a run failed) for: ${failed[*]} (see their report.md)" >&2
  exit 1
fi
