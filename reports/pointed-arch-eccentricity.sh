#!/bin/sh
# PRD capacity of the paper's pointed arch (Rcirc = 1 m, t = 0.12 m, embrace 150 deg,
# 14 voussoirs, right support spreading in 1 mm steps) over e/Rcirc = 0 .. 0.30.
# Usage: reports/pointed-arch-eccentricity.sh MASONRY_EXE [OUT.csv]   (needs jq)
# Columns: e/Rcirc, capacity (mm), stable steps, hinges at d = 1 mm (joints, by the blocks they
# separate), then every change of the set of cracked joints: d (mm) and the new set.
set -eu
exe=${1:?usage: $0 MASONRY_EXE [OUT.csv]}
out=${2:-/dev/stdout}
tmp=$(mktemp -d)
trap 'rm -rf "$tmp"' EXIT
echo "e_over_rcirc,capacity_mm,stable_steps,lp_time_s,hinges_at_1mm,changes" > "$out"
for i in $(seq 0 30); do
  e=$(printf '0.%02d' "$i")
  "$exe" cases pointed-arch --eccentricity "$e" --out "$tmp/arch.json" 2>/dev/null
  "$exe" prd "$tmp/arch.json" --out "$tmp/run" >/dev/null 2>&1 || true
  jq -r --arg e "$e" '
    def names($s): [$s[] | (.joints_by_id[.] // .)] ;
    . as $r
    | ($r.joints | map(.blocks | join("|"))) as $jn
    | [ $r.steps[1:][] | {d: .d, c: (.cracked | sort)} ] as $s
    | ($s[0].c | map($jn[.]) | join(" ")) as $first
    | [ range(1; $s | length) | select($s[.].c != $s[. - 1].c)
        | "\($s[.].d * 1000 | round)mm: \($s[.].c | map($jn[.]) | join(" "))" ] as $chg
    | [$e, ($r.capacity * 1000 | round), $r.stable_steps, $r.timing.total_s, $first, ($chg | join("; "))]
    | @csv' "$tmp/run/results.json" >> "$out"
done
