#!/usr/bin/env bash
# The cost of a step of the towed disk with cut cells against the same disk fixed (issue 33 point
# 4; docs/evidence/cut_cell_boundary.md, "A body in prescribed motion"): the scene
# cases/verification/towed_disk_cut_cell.toml (D = 1 towed at U = 1 along a periodic channel 4 x 2)
# at each D/h of D_OVER_H with U dt / h = 0.1, in these configurations, run in turn ROUNDS times so
# that a shared machine's load falls on all alike:
#   towed              cut cells, the disk prescribed (cut anew every step);
#   fixed              cut cells, the disk fixed and the walls moving at -U: the towed disk's
#                      flow in its frame (Galileo), as bench/towed_disk.sh runs it;
#   towed_collocation  the default collocation points, the disk prescribed;
#   free               cut cells, the disk free (particles/cut_cell_free_bodies.h: 1 + 3 Stokes
#                      solves a step, K made every step), twice the liquid's density, starting at U and pulled along
#                      the channel by gravity with the towed disk's drag at D/h = 20 (12.35) as
#                      its weight less buoyancy, so that it moves as the towed one;
#   free_kept          the free disk with K kept over steps (particle_mesh.rigid_modes_refresh =
#                      1: K's 3 unit solves once the disk has moved a cell, every 10 steps here;
#                      in between one solve at the new velocity: 2 solves a step);
#   towed_before       the towed disk with the solver BEFORE, when set (a copy of an earlier build:
#                      the cost of a change measured in the same run).
# Each runs FIRST and FIRST + STEPS steps from rest on one thread with no output; printed: the CPU
# ms a step over the STEPS later steps (the difference of the two runs' user + system time: the
# set-up and the first steps left out) and the set-up plus FIRST steps in CPU seconds.
#   bench/towed_disk_cost.sh     # BUILD=build D_OVER_H="10 20 40" FIRST=10 STEPS=100 ROUNDS=2
#                                # BEFORE=/tmp/dlmfd-solve-main WORK=...
#                                # CONFIGURATIONS="free free_kept" (a subset; default: all)
#                                # EXTRA="--set fluid.relaxation_time=0.1 ..." (to every run)
set -euo pipefail
cd "$(dirname "$0")/.."

BUILD=${BUILD:-build}
D_OVER_H=${D_OVER_H:-10 20 40}
FIRST=${FIRST:-10}
STEPS=${STEPS:-100}
ROUNDS=${ROUNDS:-2}
WORK=${WORK:-$(mktemp -d /tmp/towed_disk_cost.XXXXXX)}
SOLVER=${SOLVE:-$BUILD/solver/dlmfd-solve}
SCENE=cases/verification/towed_disk_cut_cell.toml
read -r -a EXTRA_ARGS <<< "${EXTRA:-}"

declare -A KEYS=(
  [towed]=''
  [fixed]='--set particles.0.motion="fixed" --set particles.0.velocity=[0,0]
    --set domain.boundary.bottom.type="velocity" --set domain.boundary.bottom.value=[-1,0]
    --set domain.boundary.top.type="velocity" --set domain.boundary.top.value=[-1,0]'
  [towed_collocation]='--set particle_mesh.kind="collocation"'
  [free]='--set particles.0.motion="free" --set particles.0.density=2 --set gravity=[15.724305,0]
    --set particle_mesh.rigid_modes_refresh=0'
  [free_kept]='--set particles.0.motion="free" --set particles.0.density=2 --set gravity=[15.724305,0]
    --set particle_mesh.rigid_modes_refresh=1'
  [towed_before]=''
)
read -r -a CONFIGURATIONS <<< "${CONFIGURATIONS:-towed fixed towed_collocation free free_kept}"
[[ -n "${BEFORE:-}" ]] && CONFIGURATIONS+=(towed_before)

# CPU seconds (user + system) of a run of n steps of configuration $1 at D/h $2.
cpu_seconds() {  # name, d_over_h, steps
  local h dt end solver=$SOLVER
  h=$(awk -v d="$2" 'BEGIN { printf "%.17g", 1.0 / d }')
  dt=$(awk -v h="$h" 'BEGIN { printf "%.17g", 0.1 * h }')
  end=$(awk -v n="$3" -v dt="$dt" 'BEGIN { printf "%.17g", (n + 0.5) * dt }')
  [[ $1 == towed_before ]] && solver=$BEFORE
  rm -rf "$WORK/run"
  # shellcheck disable=SC2086  # KEYS holds several --set words
  /usr/bin/time -f "%U %S" -o "$WORK/time" "$solver" "$SCENE" --out "$WORK/run" --threads 1 \
    --set "domain.h=$h" --set "time.dt=$dt" --set "time.end=$end" --set output.fields_every=0 \
    --set output.particles_every=0 --set output.checkpoint_every=0 "${EXTRA_ARGS[@]}" \
    ${KEYS[$1]} > /dev/null 2>&1
  awk '{ printf "%.3f", $1 + $2 }' "$WORK/time"
}

echo "configuration,round,d_over_h,steps,cpu_ms_per_step,setup_and_first_steps_cpu_s"
for round in $(seq 1 "$ROUNDS"); do
  for d in $D_OVER_H; do
    for name in "${CONFIGURATIONS[@]}"; do
      short=$(cpu_seconds "$name" "$d" "$FIRST")
      long=$(cpu_seconds "$name" "$d" $((FIRST + STEPS)))
      awk -v n="$name" -v r="$round" -v d="$d" -v s="$STEPS" -v a="$short" -v b="$long" \
        'BEGIN { printf "%s,%d,%s,%d,%.3f,%.2f\n", n, r, d, s, 1000 * (b - a) / s, a }'
    done
  done
done
