#!/usr/bin/env bash
# The confined-cylinder benchmark (cases/verification/confined_cylinder_oldroyd_b.toml): the drag
# factor K = F / (eta U) against Wi, the mesh R/h and fluid.conformation, and its error against the
# literature (cases/verification/confined_cylinder_reference.csv). Each run: dt = lambda / 120 and
# end = 15 lambda (Wi > 0), dt = 1 / 120 and end = 1 (Wi = 0, Newtonian: steady in the Stokes limit
# from the first steps); the scene's other keys as shipped (no numerics keys). Prints one line a
# run: K at the end, its change over the last 3 lambda (how steady), and the error; appends them to
# $WORK/confined_cylinder.csv. docs/evidence/validation_particles.md, "The confined cylinder in an Oldroyd-B liquid, at
# the defaults".
#   bench/confined_cylinder.sh                # RH="8 16 24" WI="0 0.3 0.6 0.9" REPR="standard log"
#                                             # SOLVE=build/solver/dlmfd-solve WORK=runs/confined_cylinder
#                                             # THREADS=1 PYTHON=python3 (with h5py); SETS="--set k=v ..."
# Cost: R/h = 24 takes 4-8 min a polymer run on one thread of this machine with the cut cells that
# `auto` picks (2026-12-06; 20-40 min with the collocation points before); R/h = 8 under a minute.
set -euo pipefail
cd "$(dirname "$0")/.."
SOLVE=${SOLVE:-build/solver/dlmfd-solve}
WORK=${WORK:-runs/confined_cylinder}
PYTHON=${PYTHON:-python3}
THREADS=${THREADS:-1}
RH=${RH:-8 16 24}
WI=${WI:-0 0.3 0.6 0.9}
REPR=${REPR:-standard log}
read -r -a EXTRA <<< "${SETS:-}"
SCENE=cases/verification/confined_cylinder_oldroyd_b.toml
REFERENCE=cases/verification/confined_cylinder_reference.csv
mkdir -p "$WORK"
[ -f "$WORK/confined_cylinder.csv" ] ||
  echo "wi,conformation,r_over_h,k_end,k_change_last_3_lambda,k_reference,error_percent,steps,wall_s" \
    > "$WORK/confined_cylinder.csv"

# K at the last record and its change over the last 3 lambda (or the last 0.3 at Wi = 0), the
# reference and the error, from particles.h5 and summary.json.
summarise() {  # run, wi
  "$PYTHON" - "$1" "$2" "$REFERENCE" <<'EOF'
import csv, json, sys
import h5py
run, wi, reference = sys.argv[1], float(sys.argv[2]), sys.argv[3]
with h5py.File(run + "/particles.h5", "r") as f:
    t, k = f["time"][:], f["force"][:, 0, 0]  # eta = U = 1: K = F_x
window = 3 * wi if wi > 0 else 0.3
i = abs(t - (t[-1] - window)).argmin()
ref = {float(r["wi"]): float(r["k"]) for r in csv.DictReader(l for l in open(reference) if l[0] != "#")}
k_ref = ref.get(wi, float("nan"))
s = json.load(open(run + "/summary.json"))
print(f"{k[-1]:.4f},{k[-1] - k[i]:.4f},{k_ref},{100 * (k[-1] / k_ref - 1):+.3f},{s['steps']},"
      f"{s['wall_seconds']:.0f}")
EOF
}

printf "%-5s %-9s %5s %10s %12s %10s %8s %7s %7s\n" Wi conform R/h K "dK(3 lam)" K_ref "err %" steps wall_s
for rh in $RH; do
  h=$("$PYTHON" -c "print(1 / $rh)")
  for wi in $WI; do
    if [ "$wi" = 0 ] || [ "$wi" = 0.0 ]; then
      reprs=standard
      dt=$("$PYTHON" -c "print(1 / 120)")
      end=1
    else
      reprs=$REPR
      dt=$("$PYTHON" -c "print($wi / 120)")
      end=$("$PYTHON" -c "print(15 * $wi)")
    fi
    for repr in $reprs; do
      name="wi${wi}_${repr}_rh${rh}"
      sets=(--set "domain.h=$h" --set "fluid.relaxation_time=$wi" --set "time.dt=$dt"
        --set "time.end=$end" --set "output.fields_every=$end")
      [ "$wi" != 0 ] && [ "$wi" != 0.0 ] && sets+=(--set "fluid.conformation=\"$repr\"")
      "$SOLVE" "$SCENE" --out "$WORK/$name" --threads "$THREADS" --quiet "${sets[@]}" \
        ${EXTRA[@]+"${EXTRA[@]}"} > "$WORK/$name.log" 2>&1 || {
        echo "$name failed: $(tail -1 "$WORK/$name.log")"
        continue
      }
      line=$(summarise "$WORK/$name" "$wi")
      echo "$wi,$repr,$rh,$line" >> "$WORK/confined_cylinder.csv"
      IFS=, read -r k dk kref err steps wall <<< "$line"
      printf "%-5s %-9s %5s %10s %12s %10s %8s %7s %7s\n" "$wi" "$repr" "$rh" "$k" "$dk" "$kref" \
        "$err" "$steps" "$wall"
    done
  done
done
