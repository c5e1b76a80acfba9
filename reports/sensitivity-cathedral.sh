#!/usr/bin/env bash
# Which dimensions decide the cathedral's capacity (reports/sensitivity-cathedral/README.md):
# the standard scenes cathedral-settlement and cathedral-settlement-rotation over the 15
# dimensions cases/README.md had to choose, each within its plausible range, sampled by a Latin
# hypercube (sweep/README.md).
#
#   bash reports/sensitivity-cathedral.sh          # PRD: 300 samples, the base point and 63 one-at-a-time
#                                                  # runs per scene, 1-1.5 CPU minutes per scene (2026-11-26)
#   bash reports/sensitivity-cathedral.sh --dem    # then PRD and DEM at the samples nearest the 5th,
#                                                  # 50th and 95th percentiles of the PRD capacity:
#                                                  # 3 DEM runs per scene, 1-3 CPU minutes each
#
# Writes reports/sensitivity-cathedral/<scene>/ (and <scene>-dem/ with --dem): sweep.csv,
# sweep.json, sensitivity.json, report.md, report.html, figures/. A stopped run resumes where it
# left off; further arguments go to `masonry sweep` (--restart, --jobs N). Uses build/app/masonry
# (override with MASONRY=path) and jq. Prints the numbers the README quotes.
set -euo pipefail
cd "$(dirname "$0")/.."
masonry=${MASONRY:-build/app/masonry}
dir=reports/sensitivity-cathedral
dem=0
if [ "${1:-}" = "--dem" ]; then
  dem=1
  shift
fi

for scene in settlement rotation; do
  if [ $dem = 0 ]; then
    "$masonry" sweep "$dir/$scene.sweep.json" --out "$dir/$scene" --quiet "$@"
    # sweep.json is the table again as JSON (0.5 MB): sweep.csv and sensitivity.json hold the numbers.
    rm -f "$dir/$scene/sweep.json"
  else
    # The same design, its samples nearest the PRD's 5th, 50th and 95th percentiles only, by both methods.
    only=$(jq -c '[.methods.prd.nearest[].sample] | unique' "$dir/$scene/sensitivity.json")
    jq --argjson only "$only" '
        .name += " (PRD and DEM at the samples nearest the 5th, 50th and 95th percentiles)"
      | .description = "The samples of the PRD sweep beside it (\(.sample.count) in all) whose PRD capacities lie nearest its 5th, 50th and 95th percentiles, each run by both methods (reports/sensitivity-cathedral.sh --dem)."
      | .methods = ["prd", "dem"] | .sample.one_at_a_time = 0 | .sample.only = $only' \
      "$dir/$scene.sweep.json" > "$dir/$scene-dem.sweep.json"
    "$masonry" sweep "$dir/$scene-dem.sweep.json" --out "$dir/$scene-dem" "$@"
  fi
done

# The numbers the README quotes: percentiles, elasticities, and what the paper's 180 and 60 cm
# would need: the samples at or above the paper's value (else the best 5%), and where each
# dimension lies in its range among them (0: lo, 1: hi; 0.5 on average over all samples).
python3 - "$dir" <<'PY'
import csv, json, statistics, sys
d = sys.argv[1]
for scene, paper in (("settlement", 1.80), ("rotation", 0.60)):
    s = json.load(open(f"{d}/{scene}/sensitivity.json"))["methods"]["prd"]
    ranges = json.load(open(f"{d}/{scene}.sweep.json"))["sample"]["ranges"]
    rows = [r for r in csv.DictReader(open(f"{d}/{scene}/sweep.csv")) if r["sample"].isdigit() and r["capacity"]]
    base = next(r for r in csv.DictReader(open(f"{d}/{scene}/sweep.csv")) if r["sample"] == "base")
    pc = s["percentiles"]
    print(f"{scene}: {s['located']} of {s['counted']} samples, {s['zero_capacity']} at 0 m; base point {float(base['capacity']):.2f} m; "
          f"percentiles 5/50/95 {pc['5']:.2f} / {pc['50']:.2f} / {pc['95']:.2f} m; largest {s['max']:.2f} m; R2 of the log fit {s['r2']:.2f}")
    for k, p in s["parameters"].items():
        line = p["one_at_a_time"]
        print(f"  {k[10:]:18} elasticity {p['elasticity']:+6.2f} (se {p['standard_error']:.2f})  Spearman {p['spearman']:+.2f}  "
              f"one at a time {min(line['capacities']):.2f}-{max(line['capacities']):.2f} m")
    rows.sort(key=lambda r: -float(r["capacity"]))
    hit = [r for r in rows if float(r["capacity"]) >= paper]
    chosen = hit or rows[: max(1, len(rows) // 20)]
    what = f"{len(hit)} samples at or above the paper's {paper:.2f} m" if hit else \
           f"no sample reaches the paper's {paper:.2f} m; the best 5% ({len(chosen)}, from {float(chosen[-1]['capacity']):.2f} m)"
    print(f"  {what}; where their dimensions lie in the ranges (mean, 0 = lo, 1 = hi):")
    pos = {k: statistics.mean((float(r[k]) - lo) / (hi - lo) for r in chosen) for k, (lo, hi) in ranges.items()}
    print("   " + ", ".join(f"{k[10:]} {v:.2f}" for k, v in sorted(pos.items(), key=lambda kv: -abs(kv[1] - 0.5))))
PY
