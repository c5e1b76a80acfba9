#!/usr/bin/env bash
# Regenerates reports/tradeoff-pointed-arch/ and reports/tradeoff-cathedral-settlement/: run time
# against accuracy of the PRD and DEM settings (masonry tradeoff, tradeoff/README.md).
#
#   bash reports/tradeoff.sh   # runs what is not in $WORK yet (--resume), then writes the reports
#
# The runs (results.json of every setting, several MB each for the cathedral) go to $WORK
# (default out/tradeoff/, not checked in); reports/ keeps only the csv, json, md, html and svg.
# Times (2026-11-25): the pointed arch's PRD plan takes seconds and its DEM plan about a CPU
# minute (the reference, full stiffness at 0.5 mm, 21 s); the cathedral's PRD plan seconds, its
# eight DEM settings 1-3 CPU minutes each, about 16 in all (its reference is the
# 2.3-minute default run of reports/compare-cathedral-settlement/dem/, read back: not in git, so
# bash reports/regenerate.sh writes it first). The DEM
# settings are independent runs: with the case files of `masonry tradeoff ... --dry-run`,
# `masonry dem RUNS/<id>/case.json --out RUNS/<id>` can run them side by side first (--resume
# then reads their times back from results.json, marked wall, though a DEM run's is CPU time). --resume reuses every finished run, so an
# interrupted script picks up where it stopped.
set -euo pipefail
cd "$(dirname "$0")/.."
MASONRY=${MASONRY:-build/app/masonry}
WORK=${WORK:-out/tradeoff}

run() {
  local name=$1; shift
  local out=reports/tradeoff-$name
  mkdir -p "$out" "$WORK/$name"
  "$MASONRY" tradeoff "$@" --out "$WORK/$name/report" --runs-dir "$WORK/$name/runs" --resume
  # Only the compact outputs are checked in; the runs stay in $WORK.
  cp "$WORK/$name/report/"{tradeoff.csv,tradeoff.json,report.md,report.html} "$out/"
  mkdir -p "$out/figures"
  cp "$WORK/$name/report/figures/"*.svg "$out/figures/"
}

# The arch with the paper's DEM stiffness reduction (10) as the baseline, as in
# reports/compare-pointed-arch/.
run pointed-arch cases/pointed-arch.json --methods prd,dem --set dem.stiffness_reduction=10 \
  --plan reports/tradeoff-pointed-arch/plan.json

# The cathedral: the DEM reference is the committed comparison's run (the case's own settings).
run cathedral-settlement cases/cathedral-settlement.json --methods prd,dem \
  --reference-dem reports/compare-cathedral-settlement/dem --plan reports/tradeoff-cathedral-settlement/plan.json
