#!/usr/bin/env bash
# Sangani and Acrivos's square array (cases/verification/sangani_acrivos_square_array.toml): the
# drag K = F / (mu U) against the area fraction, the mesh and the disk's sub-grid position, and its
# error against cases/verification/sangani_acrivos_reference.csv. F is the disk's force
# (summary.json), U the mean velocity over the box: the flux through its edge x = 0 (trapezoid rule
# on the last snapshot's u, periodic) over its height. The disk's centre moves along x by SHIFTS
# (in units of h) from the box's centre. Prints one line a run and, per area fraction and mesh, the
# node-centred error, the mean over the shifts, their spread and the largest error; appends the
# runs to $WORK/sangani_acrivos.csv. docs/evidence/validation_particles.md, "Sangani and Acrivos's square array".
#   bench/sangani_acrivos.sh     # PHI="0.1 0.2 0.3 0.4" CELLS=64 SHIFTS="0 0.25 0.5 0.75 1 1.25 1.5 1.75"
#                                # SOLVE=build/solver/dlmfd-solve WORK=runs/sangani_acrivos
#                                # PYTHON=python3 (with h5py, numpy); SETS="--set k=v ..."
#                                # MESH=cut_cell (particle_mesh.kind; default: the scene's)
# Cost: about 5 s a run at 64 cells on one thread of this machine (32 runs as shipped).
set -euo pipefail
cd "$(dirname "$0")/.."
SOLVE=${SOLVE:-build/solver/dlmfd-solve}
WORK=${WORK:-runs/sangani_acrivos}
PYTHON=${PYTHON:-python3}
PHI=${PHI:-0.1 0.2 0.3 0.4}
CELLS=${CELLS:-64}
SHIFTS=${SHIFTS:-0 0.25 0.5 0.75 1 1.25 1.5 1.75}
MESH=${MESH:-}
read -r -a EXTRA <<< "${SETS:-}"
[ -z "$MESH" ] || EXTRA+=(--set "particle_mesh.kind=$MESH")
SCENE=cases/verification/sangani_acrivos_square_array.toml
REFERENCE=cases/verification/sangani_acrivos_reference.csv
mkdir -p "$WORK"
[ -f "$WORK/sangani_acrivos.csv" ] ||
  echo "phi,cells,shift,k,k_reference,error_percent,mesh" > "$WORK/sangani_acrivos.csv"

# K of a run and its error against the reference, as "k,k_reference,error_percent".
measure() {  # run, phi
  "$PYTHON" - "$1" "$2" "$REFERENCE" <<'EOF'
import csv, glob, json, sys
import h5py
run, phi, reference = sys.argv[1], float(sys.argv[2]), sys.argv[3]
with h5py.File(sorted(glob.glob(run + "/fields/snap_*.h5"))[-1], "r") as f:
    u, h = f["u"][:], f.attrs["h"]
flux = u[:-1, 0].sum() * h  # the periodic column x = 0, its duplicate top row left out
height = h * (u.shape[0] - 1)
force = json.load(open(run + "/summary.json"))["particles"][0]["force"][0]
k = force / (flux / height)  # mu = 1
ref = {float(r["phi"]): float(r["k"]) for r in csv.DictReader(l for l in open(reference) if l[0] != "#")}
print(f"{k:.4f},{ref[phi]},{100 * (k / ref[phi] - 1):+.3f}")
EOF
}

printf "%-5s %6s %6s %10s %9s %8s\n" phi cells shift K K_ref "err %"
for cells in $CELLS; do
  h=$("$PYTHON" -c "print(1 / $cells)")
  for phi in $PHI; do
    d=$("$PYTHON" -c "import math; print(2 * math.sqrt($phi / math.pi))")
    errors=()
    for shift in $SHIFTS; do
      x=$("$PYTHON" -c "print(0.5 + $shift * $h)")
      name="phi${phi}_n${cells}_s${shift}${MESH:+_$MESH}"
      "$SOLVE" "$SCENE" --out "$WORK/$name" --threads 1 --quiet --set "domain.h=$h" \
        --set "particles.0.diameter=$d" --set "particles.0.center=[$x, 0.5]" \
        ${EXTRA[@]+"${EXTRA[@]}"} > "$WORK/$name.log" 2>&1 || {
        echo "$name failed: $(tail -1 "$WORK/$name.log")"
        continue
      }
      line=$(measure "$WORK/$name" "$phi")
      echo "$phi,$cells,$shift,$line,${MESH:-scene}" >> "$WORK/sangani_acrivos.csv"
      IFS=, read -r k kref err <<< "$line"
      errors+=("$err")
      printf "%-5s %6s %6s %10s %9s %8s\n" "$phi" "$cells" "$shift" "$k" "$kref" "$err"
    done
    "$PYTHON" -c "
import sys
e = [float(x) for x in sys.argv[3:]]
print(f'  phi {sys.argv[1]}, {sys.argv[2]} cells: node-centred {e[0]:+.2f} %, mean {sum(e) / len(e):+.2f} %, '
      f'spread {max(e) - min(e):.2f} %, largest {max(abs(x) for x in e):.2f} %')" "$phi" "$cells" \
      "${errors[@]}"
  done
done
