#!/usr/bin/env bash
# The cost of a step at the defaults against the defaults before issue 32 (docs/evidence/performance.md,
# "The default step"), on the paper's case 5.2 (cases/paper/5.2_pair_oldroyd_b.toml: two disks in an
# Oldroyd-B liquid on the paper's grid, h = 1/96, dt = 4e-4). Three configurations, run in turn
# ROUNDS times so that a shared machine's load falls on each alike:
#   before      the defaults before issue 32: ring mesh, SW-NE mesh, least-squares advection, the
#               lagged multiplier (incremental), DEVSS;
#   before_wave the same with the wave-like advection (issue 32's target: the new default step
#               no dearer than this one);
#   defaults    no numerics key: collocation points, both diagonals, wave, auto (incremental here).
# Each run makes STEPS steps on one thread with no output; the script prints CPU ms a step (user +
# system time of the process over its steps, set-up included), which a loaded machine perturbs less
# than wall time.
#
#   bench/default_step.sh            # BUILD=build STEPS=50 ROUNDS=3 WORK=...
set -euo pipefail
cd "$(dirname "$0")/.."

BUILD=${BUILD:-build}
STEPS=${STEPS:-50}
ROUNDS=${ROUNDS:-3}
WORK=${WORK:-$(mktemp -d /tmp/default_step.XXXXXX)}
SOLVER="$BUILD/solver/dlmfd-solve"
SCENE=cases/paper/5.2_pair_oldroyd_b.toml
END=$(awk -v n="$STEPS" 'BEGIN { printf "%.6g", n * 4e-4 }')

declare -A KEYS=(
  [before]='--set particle_mesh.kind="ring" --set domain.diagonals="sw_ne" --set splitting.advection="least_squares" --set splitting.constraint="incremental"'
  [before_wave]='--set particle_mesh.kind="ring" --set domain.diagonals="sw_ne" --set splitting.advection="wave" --set splitting.constraint="incremental"'
  [defaults]=''
)

echo "configuration,round,steps,cpu_ms_per_step"
for round in $(seq 1 "$ROUNDS"); do
  for name in before before_wave defaults; do
    out="$WORK/$name.$round"
    rm -rf "$out"
    # shellcheck disable=SC2086  # KEYS holds several --set words
    /usr/bin/time -f "%U %S" -o "$WORK/time" "$SOLVER" "$SCENE" --out "$out" --threads 1 \
      --set "time.end=$END" --set output.fields_every=0 --set output.particles_every=0 \
      --set output.checkpoint_every=0 ${KEYS[$name]} >/dev/null 2>&1
    read -r user system <"$WORK/time"
    awk -v n="$name" -v r="$round" -v s="$STEPS" -v u="$user" -v y="$system" \
      'BEGIN { printf "%s,%d,%d,%.2f\n", n, r, s, 1000 * (u + y) / s }'
  done
done
