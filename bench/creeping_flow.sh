#!/usr/bin/env bash
# Creeping flow at a time step set by the motion, for rho_f from 1 down to 0.01 (issue 32 point 4):
#  - Faxen's settling disk (cases/verification/faxen_disk_w1.toml: D = 0.2 midway between walls 1
#    apart, eta = 0.1, rho_p - rho_f = 0.01 so that Faxen's speed is the same at every rho_f,
#    h = 1/96): dt = 0.01 (U dt / h = 0.18), the fall speed's mean over the last half of the run
#    against Faxen's law (docs/evidence/validation_paper.md, "Fall speeds in the Stokes regime");
#  - a fixed disk in a channel (cases/verification/confined_cylinder_oldroyd_b.toml at Wi = 0:
#    blockage 0.5, eta = 1, U = 1, R/h = 24): dt = 1/120 (R / (120 U)), K = F / (eta U) at the end
#    against 132.358 (the creeping-flow limit, confined_cylinder_reference.csv).
# Re = rho_f U D / eta is 0.37 / 0.037 / 0.0037 for the settling disk and 2 / 0.2 / 0.02 for the
# fixed one at rho_f = 1 / 0.1 / 0.01. Prints one line a run; appends them to $WORK/creeping_flow.csv.
# docs/evidence/validation_particles.md, "Creeping flow at a time step set by the motion".
#   bench/creeping_flow.sh       # RHO="1 0.1 0.01" CASES="faxen fixed" SOLVE=build/solver/dlmfd-solve
#                                # WORK=runs/creeping_flow THREADS=1 PYTHON=python3 (with h5py, numpy)
#                                # FAXEN_END=1.5 FIXED_END=1; SETS="--set k=v ..." (every run)
set -euo pipefail
cd "$(dirname "$0")/.."
SOLVE=${SOLVE:-build/solver/dlmfd-solve}
WORK=${WORK:-runs/creeping_flow}
PYTHON=${PYTHON:-python3}
THREADS=${THREADS:-1}
RHO=${RHO:-1 0.1 0.01}
CASES=${CASES:-faxen fixed}
FAXEN_END=${FAXEN_END:-1.5}
FIXED_END=${FIXED_END:-1}
read -r -a EXTRA <<< "${SETS:-}"
mkdir -p "$WORK"
[ -f "$WORK/creeping_flow.csv" ] ||
  echo "case,rho_f,dt,value,reference,error_percent,steps,wall_s" > "$WORK/creeping_flow.csv"

# "value,reference,error_percent,steps,wall_s" of a run.
measure() {  # case, run
  "$PYTHON" - "$1" "$2" <<'EOF'
import json, math, sys
import h5py
import numpy as np
case, run = sys.argv[1], sys.argv[2]
with h5py.File(run + "/particles.h5", "r") as f:
    t, v, fx = f["time"][:], f["velocity"][:, 0, 1], f["force"][:, 0, 0]
if case == "faxen":
    # Faxen (Happel & Brenner 1965, 7-6): a cylinder midway between plane walls 2l apart, k = a / l.
    a, l, eta, drho, g = 0.1, 0.5, 0.1, 0.01, 981.0
    k = a / l
    u = (drho * g * math.pi * a * a / (4 * math.pi * eta)
         * (math.log(1 / k) - 0.9157 + 1.7244 * k**2 - 1.7302 * k**4 + 2.4056 * k**6 - 4.5913 * k**8))
    value, ref = -np.mean(v[t >= t[-1] / 2]), u
else:
    value, ref = fx[-1], 132.358  # eta = U = 1: K = F_x
s = json.load(open(run + "/summary.json"))
print(f"{value:.6g},{ref:.6g},{100 * (value / ref - 1):+.3f},{s['steps']},{s['wall_seconds']:.0f}")
EOF
}

printf "%-6s %6s %8s %12s %10s %8s %7s %7s\n" case rho_f dt value reference "err %" steps wall_s
for case in $CASES; do
  for rho in $RHO; do
    if [ "$case" = faxen ]; then
      scene=cases/verification/faxen_disk_w1.toml
      dt=0.01
      rho_p=$("$PYTHON" -c "print($rho + 0.01)")
      sets=(--set "fluid.density=$rho" --set "particles.0.density=$rho_p" --set "time.dt=$dt"
        --set "time.end=$FAXEN_END" --set output.fields_every=0 --set output.particles_every=0.02)
    else
      scene=cases/verification/confined_cylinder_oldroyd_b.toml
      dt=$("$PYTHON" -c "print(1 / 120)")
      sets=(--set "fluid.density=$rho" --set fluid.relaxation_time=0 --set "time.dt=$dt"
        --set "time.end=$FIXED_END" --set output.fields_every=0)
    fi
    name="${case}_rho$rho"
    "$SOLVE" "$scene" --out "$WORK/$name" --threads "$THREADS" --quiet "${sets[@]}" \
      ${EXTRA[@]+"${EXTRA[@]}"} > "$WORK/$name.log" 2>&1 || {
      echo "$name failed: $(tail -1 "$WORK/$name.log")"
      continue
    }
    line=$(measure "$case" "$WORK/$name")
    echo "$case,$rho,$dt,$line" >> "$WORK/creeping_flow.csv"
    IFS=, read -r value ref err steps wall <<< "$line"
    printf "%-6s %6s %8.5f %12s %10s %8s %7s %7s\n" "$case" "$rho" "$dt" "$value" "$ref" "$err" \
      "$steps" "$wall"
  done
done
