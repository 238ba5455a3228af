#!/usr/bin/env bash
# The cost of a step with the cut-cell boundary against the default step (issue 33 point 4;
# docs/evidence/cut_cell_boundary.md, "A second-order boundary: the time loop"), on the fixed-body case the cut
# cells run: Schaefer-Turek 2D-1 (cases/verification/schaefer_turek_2d1.toml as shipped, D/h = 20,
# dt = 0.005; D_OVER_H=40 for domain.h = 0.0025). Two configurations, run in turn ROUNDS times so
# that a shared machine's load falls on both alike:
#   defaults   no numerics key: collocation points, both diagonals, wave, auto (incremental here);
#   cut_cell   particle_mesh.kind = "cut_cell", the rest as shipped;
#   cut_cell_before   the same with the solver BEFORE, when set (a copy of an earlier build: the
#              cost of a change measured in the same run).
# Each configuration runs FIRST steps and FIRST + STEPS steps from rest on one thread with no
# output; the script prints the CPU ms a step over the STEPS later steps (the difference of the
# two runs' user + system time, so the set-up and the start-up's first steps are left out) and the
# set-up plus FIRST steps in CPU seconds.
#   bench/cut_cell_step_cost.sh      # BUILD=build FIRST=20 STEPS=60 ROUNDS=3 D_OVER_H=20 WORK=...
#                                    # BEFORE=/tmp/dlmfd-solve-main
set -euo pipefail
cd "$(dirname "$0")/.."

BUILD=${BUILD:-build}
FIRST=${FIRST:-20}
STEPS=${STEPS:-60}
ROUNDS=${ROUNDS:-3}
D_OVER_H=${D_OVER_H:-20}
WORK=${WORK:-$(mktemp -d /tmp/cut_cell_step_cost.XXXXXX)}
SOLVER=${SOLVE:-$BUILD/solver/dlmfd-solve}
SCENE=cases/verification/schaefer_turek_2d1.toml
H=$(awk -v d="$D_OVER_H" 'BEGIN { printf "%.17g", 0.1 / d }')

declare -A KEYS=(
  [defaults]=''
  [cut_cell]='--set particle_mesh.kind="cut_cell"'
  [cut_cell_before]='--set particle_mesh.kind="cut_cell"'
)
CONFIGURATIONS=(defaults cut_cell)
[[ -n "${BEFORE:-}" ]] && CONFIGURATIONS+=(cut_cell_before)

# CPU seconds (user + system) of a run of n steps of configuration $1.
cpu_seconds() {  # name, steps
  local end
  end=$(awk -v n="$2" 'BEGIN { printf "%.6g", n * 0.005 }')
  rm -rf "$WORK/run"
  local solver=$SOLVER
  [[ $1 == cut_cell_before ]] && solver=$BEFORE
  # shellcheck disable=SC2086  # KEYS holds several --set words
  /usr/bin/time -f "%U %S" -o "$WORK/time" "$solver" "$SCENE" --out "$WORK/run" --threads 1 \
    --set "domain.h=$H" --set "time.end=$end" --set output.fields_every=0 \
    --set output.particles_every=0 --set output.checkpoint_every=0 ${KEYS[$1]} > /dev/null 2>&1
  awk '{ printf "%.3f", $1 + $2 }' "$WORK/time"
}

echo "configuration,round,d_over_h,steps,cpu_ms_per_step,setup_and_first_steps_cpu_s"
for round in $(seq 1 "$ROUNDS"); do
  for name in "${CONFIGURATIONS[@]}"; do
    short=$(cpu_seconds "$name" "$FIRST")
    long=$(cpu_seconds "$name" $((FIRST + STEPS)))
    awk -v n="$name" -v r="$round" -v d="$D_OVER_H" -v s="$STEPS" -v a="$short" -v b="$long" \
      'BEGIN { printf "%s,%d,%s,%d,%.2f,%.2f\n", n, r, d, s, 1000 * (b - a) / s, a }'
  done
done
