#!/usr/bin/env bash
# A disk settling at Re about 260 (cases/verification/wachs_settling_disk.toml; Wachs 2009: Re =
# U d / nu = 259.5, C_D = 1.785): the Reynolds number of the fall against D/h and the channel's
# length. Re is the mean of -v d / nu over the second half of the run (the disk has then reached
# its terminal speed but sways across the channel; at D/h = 16 the window holds less than one period
# of the sway), with the spread (max - min) of Re over that window and the disk's mean x. Prints
# one line a run; appends them to
# $WORK/wachs_settling.csv. docs/evidence/validation_particles.md, "A disk settling at Re 260 in a long channel".
#   bench/wachs_settling.sh      # DH="8 16 32" SOLVE=build/solver/dlmfd-solve WORK=runs/wachs_settling
#                                # THREADS=1 PYTHON=python3 (with h5py, numpy); SETS="--set k=v ..."
# Cost: D/h = 16 433 s on one thread of this machine, shared (2800 steps); 32 eight times that.
set -euo pipefail
cd "$(dirname "$0")/.."
SOLVE=${SOLVE:-build/solver/dlmfd-solve}
WORK=${WORK:-runs/wachs_settling}
PYTHON=${PYTHON:-python3}
THREADS=${THREADS:-1}
DH=${DH:-8 16 32}
read -r -a EXTRA <<< "${SETS:-}"
SCENE=cases/verification/wachs_settling_disk.toml
mkdir -p "$WORK"
[ -f "$WORK/wachs_settling.csv" ] ||
  echo "d_over_h,re,re_spread,x_mean,re_reference,error_percent,steps,wall_s" > "$WORK/wachs_settling.csv"

printf "%6s %9s %9s %8s %7s %8s %7s %7s\n" D/h Re spread x_mean Re_ref "err %" steps wall_s
for dh in $DH; do
  h=$("$PYTHON" -c "print(1 / $dh)")
  name="dh$dh"
  "$SOLVE" "$SCENE" --out "$WORK/$name" --threads "$THREADS" --quiet --set "domain.h=$h" \
    ${EXTRA[@]+"${EXTRA[@]}"} > "$WORK/$name.log" 2>&1 || {
    echo "$name failed: $(tail -1 "$WORK/$name.log")"
    continue
  }
  line=$("$PYTHON" - "$WORK/$name" <<'EOF'
import json, sys
import h5py
import numpy as np
run = sys.argv[1]
nu, d, re_ref = 0.008088, 1.0, 259.5
with h5py.File(run + "/particles.h5", "r") as f:
    t, x, v = f["time"][:], f["position"][:, 0, 0], f["velocity"][:, 0, 1]
late = t >= t[-1] / 2
re = -v[late] * d / nu
s = json.load(open(run + "/summary.json"))
print(f"{re.mean():.2f},{re.max() - re.min():.2f},{x[late].mean():.4f},{re_ref},"
      f"{100 * (re.mean() / re_ref - 1):+.2f},{s['steps']},{s['wall_seconds']:.0f}")
EOF
)
  echo "$dh,$line" >> "$WORK/wachs_settling.csv"
  IFS=, read -r re spread xm ref err steps wall <<< "$line"
  printf "%6s %9s %9s %8s %7s %8s %7s %7s\n" "$dh" "$re" "$spread" "$xm" "$ref" "$err" "$steps" "$wall"
done
