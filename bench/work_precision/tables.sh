#!/bin/bash
# Markdown tables of the work-precision data (docs/work_precision/<problem>.csv, written by
# bench/work_precision.sh) for docs/evidence/work_precision.md, with the observed order between successive
# points of each ladder: log(e_i / e_i+1) / log(x_i / x_i+1), x = h on the h+dt ladder, dt on the dt ladder.
# Usage: bench/work_precision/tables.sh [PROBLEM...]   (default a b c d)
set -euo pipefail
data=$(cd "$(dirname "$0")/../.." && pwd)/docs/work_precision
for problem in "${@:-a b c d}"; do
  for p in $problem; do
    csv=$data/$p.csv
    [[ -f $csv ]] || { echo "($p: no data)"; continue; }
    echo "| series | h | dt | tolerance | status | CPU s | wall s | value | error | order |"
    echo "|---|---|---|---|---|---|---|---|---|---|"
    awk -F, 'NR > 1 {
        order = ""
        if ($2 == prev_series && $13 != "nan" && prev_e != "nan" && $13 > 0 && prev_e > 0) {
          if ($4 == "h+dt" && $5 != prev_h) order = sprintf("%.2f", log(prev_e / $13) / log(prev_h / $5))
          if ($4 == "dt" && $6 != prev_dt) order = sprintf("%.2f", log(prev_e / $13) / log(prev_dt / $6))
        }
        printf "| %s | %s | %s | %s | %s | %s | %.3g | %s | %s | %s |\n", $2, $5, $6, $7, $8, $9, $10, $12, $13, order
        prev_series = $2; prev_e = $13; prev_h = $5; prev_dt = $6 }' "$csv"
    echo
  done
done
