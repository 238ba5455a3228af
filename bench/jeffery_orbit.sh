#!/usr/bin/env bash
# Jeffery's orbit of a neutrally buoyant ellipse in Couette flow (issue 37, point 2;
# cases/shapes/jeffery_orbit.toml: a = 0.2, Re = 0.01): runs the case on each grid and
# confinement and prints, per run, the period against 2 pi (r + 1/r) / G and the angular velocity
# against Jeffery's law (bench/jeffery_orbit.py); appends them to $WORK/jeffery.csv.
# docs/evidence/validation_particles.md, "Jeffery's orbit".
#   bench/jeffery_orbit.sh   # CELLS="32 48" (cells per unit length) HEIGHTS="2" (channel height H,
#                            # walls at +-H/2 moving at +-G H/2, G = 1) RATIOS="2" (b = a / r)
#                            # DIFFUSION=2.048 (nu dt / h^2; 32 cells: the case) END=12.5 WORK=runs/jeffery
#                            # SOLVE=build/solver/dlmfd-solve PYTHON=/usr/bin/python3 THREADS=1
#                            # SHIFT=0 (the centre moved by SHIFT h along x and y off the node)
#                            # SETS="--set k=v ..." (every run)
set -euo pipefail
cd "$(dirname "$0")/.."
SOLVE=${SOLVE:-build/solver/dlmfd-solve}
WORK=${WORK:-runs/jeffery}
PYTHON=${PYTHON:-/usr/bin/python3}
THREADS=${THREADS:-1}
CELLS=${CELLS:-32 48}
HEIGHTS=${HEIGHTS:-2}
RATIOS=${RATIOS:-2}
DIFFUSION=${DIFFUSION:-2.048}
END=${END:-12.5}
SHIFT=${SHIFT:-0}
read -r -a EXTRA <<< "${SETS:-}"
mkdir -p "$WORK"
for r in $RATIOS; do
  for height in $HEIGHTS; do
    for n in $CELLS; do
      h=$(awk -v n="$n" 'BEGIN { printf "%.17g", 1 / n }')
      dt=$(awk -v n="$n" -v d="$DIFFUSION" 'BEGIN { printf "%.17g", d / (4 * n * n) }')  # nu = 4
      b=$(awk -v r="$r" 'BEGIN { printf "%.17g", 0.2 / r }')
      speed=$(awk -v H="$height" 'BEGIN { printf "%.17g", H / 2 }')
      x=$(awk -v n="$n" -v f="$SHIFT" 'BEGIN { printf "%.17g", 1 + f / n }')
      y=$(awk -v n="$n" -v f="$SHIFT" -v H="$height" 'BEGIN { printf "%.17g", H / 2 + f / n }')
      run="$WORK/r${r}_H${height}_n${n}_s${SHIFT}"
      start=$(date +%s)
      OMP_NUM_THREADS=$THREADS "$SOLVE" cases/shapes/jeffery_orbit.toml --out "$run" --quiet \
        --set domain.h="$h" --set time.dt="$dt" --set time.end="$END" \
        --set domain.size="[2.0, $height]" --set particles.0.center="[$x, $y]" \
        --set particles.0.semi_axes="[0.2, $b]" \
        --set domain.boundary.bottom.value="[-$speed, 0.0]" \
        --set domain.boundary.top.value="[$speed, 0.0]" "${EXTRA[@]}" > "$run.log" 2>&1 || true
      wall=$(( $(date +%s) - start ))
      line="r=$r H=$height h=1/$n shift=$SHIFT dt=$dt wall_s=$wall $("$PYTHON" bench/jeffery_orbit.py "$run" --ratio "$r")"
      echo "$line"
      echo "$line" >> "$WORK/jeffery.csv"
    done
  done
done
