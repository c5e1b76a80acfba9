#!/usr/bin/env bash
# Regenerates reports/dem-convergence/<case>.{md,json}: the DEM convergence studies of the three
# standard scenes (masonry dem --convergence, dem/README.md): each case at its DEM settings and at
# every setting that must not matter, with PRD beside them.
#
#   bash reports/dem-convergence.sh [JOBS]   # JOBS runs at a time (default 2)
#
# Cost (2026-11-25): the pointed arch about a CPU minute; the rotation scene 9 runs of 1-2 CPU
# minutes, the settlement scene 9 runs of 1.5-5 (the half time step and the stiffer joints are the
# slow ones), so about 20 minutes on 2 cores for all three. The runs go to $WORK (default out/convergence/, not checked in); each default run is the
# DEM run of the matching reports/compare-<case>/ (bash reports/regenerate.sh --render redraws
# those from it after copying it there). Exit code 1 when a study is not shown converged.
set -uo pipefail
cd "$(dirname "$0")/.."
masonry=${MASONRY:-build/app/masonry}
jobs=${1:-2}
work=${WORK:-out/convergence}
mkdir -p reports/dem-convergence
failed=()
declare -A extra=(
  [pointed-arch]="--stiffness-reduction 10"
  [cathedral-settlement]=""
  [cathedral-settlement-rotation]=""
)
for name in pointed-arch cathedral-settlement cathedral-settlement-rotation; do
  # shellcheck disable=SC2086
  "$masonry" dem cases/$name.json ${extra[$name]} --convergence --jobs "$jobs" --out "$work/$name" || failed+=("$name")
  cp "$work/$name/convergence.md" "reports/dem-convergence/$name.md"
  cp "$work/$name/convergence.json" "reports/dem-convergence/$name.json"
done
if [ ${#failed[@]} -gt 0 ]; then
  echo "dem-convergence: not shown converged: ${failed[*]} (see reports/dem-convergence/)" >&2
  exit 1
fi
