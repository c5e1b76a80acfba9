#!/usr/bin/env bash
# Regenerates reports/dem-stiffness/<case>.{md,json}: the DEM joint-stiffness study (masonry dem
# --stiffness-study, dem/README.md) of cathedral-settlement, the scene whose DEM answer moves with
# the joints' stiffness (reports/dem-convergence/cathedral-settlement.md): the case's joints, 10
# and 3 times softer, 3, 10 and 30 times stiffer, each run's mechanism against PRD's.
#
#   bash reports/dem-stiffness.sh [JOBS]   # JOBS runs at a time (default 2)
#
# Cost (2026-11-24, CPU of one core each): 2 (x1/10), 3, 7, 7, 15 and 18 minutes (x30): the time
# step goes as 1/sqrt(kn). The runs go to $WORK (default out/stiffness/, not checked in); its
# default and x3 runs are the same settings as the convergence study's default and stiffer-joints.
set -uo pipefail
cd "$(dirname "$0")/.."
masonry=${MASONRY:-build/app/masonry}
jobs=${1:-2}
work=${WORK:-out/stiffness}
mkdir -p reports/dem-stiffness
for name in cathedral-settlement; do
  "$masonry" dem cases/$name.json --stiffness-study --jobs "$jobs" --out "$work/$name" || exit 1
  cp "$work/$name/stiffness.md" "reports/dem-stiffness/$name.md"
  cp "$work/$name/stiffness.json" "reports/dem-stiffness/$name.json"
done
# The branch at 30 times the stiffness: the convergence study's settings over the first 10 cm,
# where the case's joints part between PRD's mechanism and the DEM's other one (dem/README.md,
# "Joint stiffness"), with holds capped at 150 s (stiff joints creep longer at the branch point).
# About 20 CPU minutes, a third of it the x90 run.
"$masonry" dem cases/cathedral-settlement.json --stiffness-reduction 0.03333333333333333 --hold-time 150 --max-steps 10 \
  --convergence --jobs "$jobs" --out "$work/cathedral-settlement-x30-first-10cm" || exit 1
cp "$work/cathedral-settlement-x30-first-10cm/convergence.md" reports/dem-convergence/cathedral-settlement-x30-first-10cm.md
cp "$work/cathedral-settlement-x30-first-10cm/convergence.json" reports/dem-convergence/cathedral-settlement-x30-first-10cm.json
