#!/usr/bin/env bash
# Regenerates reports/dem-convergence/<study>.{md,json}: the DEM convergence studies of the three
# standard scenes and of the settlement scene at joints three and ten times softer (masonry dem
# --convergence, dem/README.md): each at its DEM settings and at every setting that must not
# matter, with PRD beside them.
#
#   bash reports/dem-convergence.sh [JOBS [--read-back]]   # JOBS runs at a time (default 2)
#
# --read-back redraws the studies from the runs already in $WORK (masonry dem --read-back).
#
# Cost (2026-11-25): the pointed arch about a CPU minute; the rotation scene 9 runs of 1-2 CPU
# minutes, the settlement scene 9 runs of 1.5-5 (the half time step and the stiffer joints are the
# slow ones), so about 20 minutes on 2 cores for the three scenes; the two softer-joint studies
# about 30 CPU minutes more (2026-11-26, on 16 cores in 5 minutes). The runs go to $WORK (default out/convergence/, not checked in); each default run is the
# DEM run of the matching reports/compare-<case>/ (bash reports/regenerate.sh --render redraws
# those from it after copying it there). Exit code 1 when a study is not shown converged, or
# converged over the protocol only (its joints' stiffness moves it beyond the spread limit).
set -uo pipefail
cd "$(dirname "$0")/.."
masonry=${MASONRY:-build/app/masonry}
jobs=${1:-2}
work=${WORK:-out/convergence}
mkdir -p reports/dem-convergence
failed=()
# study name -> case and options. The two softer-joint studies run the protocol's settings on
# the settlement scene's joints three and ten times softer: whether the DEM answers there for the
# structure too (reports/README.md, "DEM convergence").
studies=(pointed-arch cathedral-settlement cathedral-settlement-rotation
         cathedral-settlement-joints-3x-softer cathedral-settlement-joints-10x-softer)
declare -A case=(
  [pointed-arch]=pointed-arch [cathedral-settlement]=cathedral-settlement
  [cathedral-settlement-rotation]=cathedral-settlement-rotation
  [cathedral-settlement-joints-3x-softer]=cathedral-settlement
  [cathedral-settlement-joints-10x-softer]=cathedral-settlement
)
declare -A extra=(
  [pointed-arch]="--stiffness-reduction 10"
  [cathedral-settlement]=""
  [cathedral-settlement-rotation]=""
  [cathedral-settlement-joints-3x-softer]="--stiffness-reduction 3"
  [cathedral-settlement-joints-10x-softer]="--stiffness-reduction 10"
)
for name in "${studies[@]}"; do
  # shellcheck disable=SC2086
  "$masonry" dem cases/${case[$name]}.json ${extra[$name]} --convergence --jobs "$jobs" --out "$work/$name" "${@:2}" || failed+=("$name")
  cp "$work/$name/convergence.md" "reports/dem-convergence/$name.md"
  cp "$work/$name/convergence.json" "reports/dem-convergence/$name.json"
done
if [ ${#failed[@]} -gt 0 ]; then
  echo "dem-convergence: beyond a limit: ${failed[*]} (see reports/dem-convergence/)" >&2
  exit 1
fi
