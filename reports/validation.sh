#!/usr/bin/env bash
# Regenerates reports/validation.md and reports/validation.json: the full built-in catalogue of
# `masonry validate` (both cathedral scenes on the DEM included: about 6 minutes on one core, 2026-11-25).
# A progress line per benchmark goes to stderr. Exit code: masonry validate's (1 when a row fails).
set -u
cd "$(dirname "$0")/.."
exe=${MASONRY:-build/app/masonry}
"$exe" validate --markdown reports/validation.md --json reports/validation.json
