#!/bin/sh
# PRD runs of the three standard case files, summarised as Markdown (the data behind
# reports/prd-standard-cases.md). Usage: reports/prd-standard-cases.sh MASONRY_EXE  (needs jq)
# For each case: capacity, run time, every change of the set of cracked joints (joints named by
# the blocks they separate: "+" opened, "-" closed), and the support reactions over the total
# weight at a few steps (force the structure receives from each support: H = Fx / W, V = Fy / W).
set -eu
exe=${1:?usage: $0 MASONRY_EXE}
src=$(cd "$(dirname "$0")/.." && pwd)
tmp=$(mktemp -d)
trap 'rm -rf "$tmp"' EXIT
summarise() {  # case-name, steps to tabulate (step indices, "last" = the last stable step)
  name=$1
  steps=$2
  start=$(date +%s.%N)
  "$exe" prd "$src/cases/$name.json" --out "$tmp/$name" >/dev/null 2>&1 || true
  end=$(date +%s.%N)
  echo "### $name"
  echo
  jq -r --arg wall "$(echo "$end - $start" | bc)" '
    "- capacity: \(.capacity) m after \(.stable_steps) stable steps; stopped: \(.stopped)",
    "- run time: \(.timing.total_s | . * 1000 | round / 1000) s solver (\(.timing.lp_solves) LPs, \(.timing.lp_s | . * 1000 | round / 1000) s in GLPK), \($wall | tonumber | . * 100 | round / 100) s wall with I/O",
    "- total weight W = \(.total_weight | round) N"' "$tmp/$name/results.json"
  echo "- changes of mechanism (d: joints opened +, closed -):"
  jq -r '
    (.joints | map(.blocks | join("|"))) as $jn
    | [ .steps[1:][] | {d, c: (.cracked | sort)} ] as $s
    | "  - d = \($s[0].d): \($s[0].c | map("+" + $jn[.]) | join(" "))",
      ( range(1; $s | length) | select($s[.].c != $s[. - 1].c) | . as $k
        | "  - d = \($s[$k].d * 10000 | round / 10000): \((($s[$k].c - $s[$k - 1].c) | map("+" + $jn[.])) + (($s[$k - 1].c - $s[$k].c) | map("-" + $jn[.])) | join(" "))" )' \
    "$tmp/$name/results.json"
  echo
  jq -r --arg steps "$steps" '
    .total_weight as $w
    | (.steps[0].reactions | map(.support)) as $sup
    | "| step | d (m) | " + ($sup | map("H/W " + . + " | V/W " + .) | join(" | ")) + " |",
      "|" + ([range(0; 2 + 2 * ($sup | length))] | map("---") | join("|")) + "|",
      ( ($steps | split(" ") | map(if . == "last" then -1 else tonumber end)) as $want
        | .steps as $all
        | $want[] | (if . < 0 then ($all | length) - 1 else . end) as $i
        | select($i < ($all | length)) | $all[$i]
        | "| \(.step) | \(.d * 10000 | round / 10000) | " +
          (.reactions | map("\(.force[0] / $w * 10000 | round / 10000) | \(.force[1] / $w * 10000 | round / 10000)") | join(" | ")) + " |" )' \
    "$tmp/$name/results.json"
  echo
}
echo "Made by $("$exe" --version)."
echo
summarise pointed-arch "0 1 2 50 100 150 200 250 last"
summarise cathedral-settlement "0 1 30 60 90 last"
summarise cathedral-settlement-rotation "0 1 2 30 last"
