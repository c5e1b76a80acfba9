#!/usr/bin/env bash
# Regenerates reports/dem-stiffness/<case>.{md,json}: the DEM joint-stiffness study (masonry dem
# --stiffness-study, dem/README.md) of cathedral-settlement, the scene whose DEM answer moves with
# the joints' stiffness (reports/dem-convergence/cathedral-settlement.md): the case's joints, 10
# and 3 times softer, 3, 10 and 30 times stiffer, each run's mechanism against PRD's.
#
#   bash reports/dem-stiffness.sh [JOBS]   # JOBS runs at a time (default 2)
#
# Cost (2026-11-25, CPU of one core each): about 1 (x1/10), 1.5, 2.5, 5, 10 and 14 minutes (x30,
# which ends undecided: its collapse creeps for longer than the 30 s hold cap); the time step goes
# as 1/sqrt(kn). The runs go to $WORK (default out/stiffness/, not checked in); its
# default and x3 runs are the same settings as the convergence study's default and stiffer-joints.
set -uo pipefail
cd "$(dirname "$0")/.."
masonry=${MASONRY:-build/app/masonry}
jobs=${1:-2}
work=${WORK:-out/stiffness}
mkdir -p reports/dem-stiffness
status=0
for name in cathedral-settlement; do
  # Exit code 1 when a run ends without a located collapse: the study is written all the same.
  "$masonry" dem cases/$name.json --stiffness-study --jobs "$jobs" --out "$work/$name" || status=$?
  [ -f "$work/$name/stiffness.md" ] || exit "$status"
  cp "$work/$name/stiffness.md" "reports/dem-stiffness/$name.md"
  cp "$work/$name/stiffness.json" "reports/dem-stiffness/$name.json"
done
exit "$status"
