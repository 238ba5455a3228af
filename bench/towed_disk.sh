#!/usr/bin/env bash
# The towed disk with cut cells (issue 33 point 2; docs/evidence/cut_cell_boundary.md, "A body in
# prescribed motion"): cases/verification/towed_disk_cut_cell.toml (a disk of D = 1 towed at U = 1
# along a periodic channel 4 x 2, Re = 1) at each D/h of D_OVER_H and each time step of DT_CELLS
# (U dt / h), to t = END, and its Galilean equivalent, the disk at rest with the walls at -U, at the
# sub-grid shifts FIXED_SHIFTS (units of h), to the same END. Then bench/towed_disk.py's table per
# D/h (the mean drag after t = FROM over whole cell crossings, the crossing oscillation, the mean
# against the fixed disk's) and the spectrum figure of D/h = 20 (FIGURE).
#   bench/towed_disk.sh     # D_OVER_H="10 20 40" DT_CELLS="0.1" FIXED_SHIFTS="0 0.25 0.5 0.75"
#                           # END=4 FROM=2 WORK=runs/towed SOLVE=build/solver/dlmfd-solve
#                           # FIGURE=docs/figures/towed_disk_spectrum.png
#                           # EXTRA="--set fluid.relaxation_time=0.1 ..." (to every run)
set -euo pipefail
cd "$(dirname "$0")/.."
SOLVE=${SOLVE:-build/solver/dlmfd-solve}
WORK=${WORK:-runs/towed}
D_OVER_H=${D_OVER_H:-10 20 40}
DT_CELLS=${DT_CELLS:-0.1}
FIXED_SHIFTS=${FIXED_SHIFTS:-0 0.25 0.5 0.75}
END=${END:-4}
FROM=${FROM:-2}
FIGURE=${FIGURE:-docs/figures/towed_disk_spectrum.png}
PYTHON=${PYTHON:-/usr/bin/python3}
read -r -a EXTRA_ARGS <<< "${EXTRA:-}"
SCENE=cases/verification/towed_disk_cut_cell.toml
mkdir -p "$WORK"

run() {  # out, then overrides
  local out=$1
  shift
  rm -rf "$out"
  /usr/bin/time -f "%U %S" -o "$out.time" "$SOLVE" "$SCENE" --out "$out" --threads 1 \
    --set "time.end=$END" "${EXTRA_ARGS[@]}" "$@" > "$out.log" 2>&1
  echo "$out: $(cat "$out.time") CPU s (user, system)"
}

for d in $D_OVER_H; do
  h=$(awk -v d="$d" 'BEGIN { printf "%.17g", 1.0 / d }')
  towed=()
  for c in $DT_CELLS; do
    dt=$(awk -v h="$h" -v c="$c" 'BEGIN { printf "%.17g", c * h }')
    run "$WORK/towed_${d}_${c}" --set "domain.h=$h" --set "time.dt=$dt" \
      --set "output.particles_every=$dt"
    towed+=("$WORK/towed_${d}_${c}")
  done
  fixed=()
  dt=$(awk -v h="$h" 'BEGIN { printf "%.17g", 0.1 * h }')
  for s in $FIXED_SHIFTS; do
    x=$(awk -v h="$h" -v s="$s" 'BEGIN { printf "%.17g", 2.0 + s * h }')
    run "$WORK/fixed_${d}_${s}" --set "domain.h=$h" --set "time.dt=$dt" \
      --set "output.particles_every=$dt" --set particles.0.motion=fixed \
      --set "particles.0.velocity=[0, 0]" --set "particles.0.center=[$x, 1.0]" \
      --set domain.boundary.bottom.type=velocity --set "domain.boundary.bottom.value=[-1, 0]" \
      --set domain.boundary.top.type=velocity --set "domain.boundary.top.value=[-1, 0]"
    fixed+=("$WORK/fixed_${d}_${s}")
  done
  "$PYTHON" bench/towed_disk.py table "${towed[@]}" --fixed "${fixed[@]}" --from "$FROM"
  if [ "$d" = 20 ]; then
    "$PYTHON" bench/towed_disk.py spectrum "${towed[@]}" --from "$FROM" --out "$FIGURE"
  fi
done
