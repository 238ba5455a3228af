#!/usr/bin/env bash
# The lid-driven cavity of Fattal & Kupferman (2005) (cases/verification/fattal_kupferman_cavity.toml:
# unit square, Oldroyd-B, beta = 0.5, Re = rho U L / eta = 0.01, the regularised lid
# u = 8 [1 + tanh(8 (t - 1/2))] x^2 (1 - x)^2) at Wi = lambda = 0.5, 1, 2, 3 in each representation of
# fluid.conformation (standard, log, sqrt), on h = 1/32 and 1/64 with dt = 0.01 and 0.005 and on
# h = 1/128 with dt = 0.005, to t = 8, wave advection, one thread, JOBS at a time (60 runs, about 6
# minutes of CPU; docs/evidence/stability.md, "Representations: the lid-driven cavity").
#   bench/cavity_representations.sh     # SOLVE=build/solver/dlmfd-solve WORK=runs/cavity_representations
# Output: docs/stability/cavity.csv (one row a run: status, end time, max trA, min eig A, the kinetic
# energy at t = 1 ... 8 from the field snapshots) and Markdown tables on stdout. Needs h5dump.
set -euo pipefail
cd "$(dirname "$0")/.."
SOLVE=$(realpath "${SOLVE:-build/solver/dlmfd-solve}")
WORK=${WORK:-runs/cavity_representations}
JOBS=${JOBS:-2}
mkdir -p "$WORK" docs/stability

for grid in "0.03125 0.01" "0.03125 0.005" "0.015625 0.01" "0.015625 0.005" "0.0078125 0.005"; do
  read -r h dt <<< "$grid"
  for wi in 0.5 1 2 3; do
    for rep in standard log sqrt; do
      cells=$(awk -v h="$h" 'BEGIN { printf "%d", 1 / h + 0.5 }')
      echo "fk_c${cells}_dt${dt}_wi${wi}_${rep}|$h|$dt|$wi|$rep|--set domain.h=$h --set time.dt=$dt --set fluid.relaxation_time=$wi --set fluid.conformation=$rep --set time.end=8 --set output.fields_every=0.5"
    done
  done
done > "$WORK/runs.txt"

run_one() {
  local name h dt wi rep sets
  IFS='|' read -r name h dt wi rep sets <<< "$1"
  [ -f "$WORK/$name/summary.json" ] && return 0
  rm -rf "${WORK:?}/${name:?}"
  # shellcheck disable=SC2086  # sets is a list of flags
  "$SOLVE" cases/verification/fattal_kupferman_cavity.toml --out "$WORK/$name" --threads 1 --quiet \
    $sets > "$WORK/$name.log" 2>&1 || true
}
export -f run_one
export SOLVE WORK
# shellcheck disable=SC2016  # $1 expands in the child bash
tr '\n' '\0' < "$WORK/runs.txt" | OMP_WAIT_POLICY=passive xargs -0 -P "$JOBS" -I{} bash -c 'run_one "$1"' _ {}

python3 bench/cavity_table.py "$WORK"
