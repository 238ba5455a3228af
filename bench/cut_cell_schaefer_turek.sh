#!/usr/bin/env bash
# Schaefer-Turek 2D-1 through the time loop with the cut-cell boundary (particle_mesh.kind =
# "cut_cell"; docs/evidence/cut_cell_boundary.md, "A second-order boundary: the time loop"): the disk's centre
# moved along x by SHIFTS (in units of h) from (0.2, 0.2), at each D/h of D_OVER_H, the scene
# otherwise as shipped (cases/verification/schaefer_turek_2d1.toml: dt = 0.005, both diagonals,
# wave advection), to t = END. Prints one CSV line a run: D/h, shift, C_D and C_L at t = END
# (C_D = 500 F_x, C_L = 500 F_y), C_D at t = END - 1, the GMRES iterations a step (mean) and the
# CPU ms a step (user + system over the run, set-up included; the machine may be shared).
# Then, per D/h with a shift of 2 among SHIFTS, each C_D moved back to x = 0.2 with the slope of the
# 2h shift (the same discrete geometry: the physical effect of the inflow's distance), their mean,
# spread and worst error against 5.57953523384 (John & Matthies 2001). The lines go to
# $WORK/cut_cell_st.csv too.
#   bench/cut_cell_schaefer_turek.sh     # D_OVER_H="20" SHIFTS="0 0.25 0.5 0.75 1 1.25 1.5 1.75 2"
#                                        # END=5 SOLVE=build/solver/dlmfd-solve WORK=runs/cut_cell_st
#                                        # SETS="--set k=v ..." (more overrides)
set -euo pipefail
cd "$(dirname "$0")/.."
SOLVE=${SOLVE:-build/solver/dlmfd-solve}
WORK=${WORK:-runs/cut_cell_st}
D_OVER_H=${D_OVER_H:-20}
SHIFTS=${SHIFTS:-0 0.25 0.5 0.75 1 1.25 1.5 1.75 2}
END=${END:-5}
PYTHON=${PYTHON:-/usr/bin/python3}
read -r -a EXTRA <<< "${SETS:-}"
SCENE=cases/verification/schaefer_turek_2d1.toml
mkdir -p "$WORK"

CSV="$WORK/cut_cell_st.csv"
echo "d_over_h,shift,cd,cl,cd_one_before,gmres_per_step,cpu_ms_per_step" | tee "$CSV"
for d in $D_OVER_H; do
  h=$(awk -v d="$d" 'BEGIN { printf "%.17g", 0.1 / d }')
  for s in $SHIFTS; do
    x=$(awk -v h="$h" -v s="$s" 'BEGIN { printf "%.17g", 0.2 + s * h }')
    out="$WORK/st_${d}_${s}"
    rm -rf "$out"
    /usr/bin/time -f "%U %S" -o "$WORK/time" "$SOLVE" "$SCENE" --out "$out" --threads 1 \
      --set particle_mesh.kind=cut_cell --set "domain.h=$h" --set "particles.0.center=[$x, 0.2]" \
      --set "time.end=$END" --set output.fields_every=0 --set output.checkpoint_every=0 \
      "${EXTRA[@]}" > "$out.log" 2>&1
    read -r user system < "$WORK/time"
    "$PYTHON" - "$out" "$d" "$s" "$user" "$system" << 'EOF'
import csv, sys
import h5py
run, d, s, user, system = sys.argv[1], sys.argv[2], sys.argv[3], float(sys.argv[4]), float(sys.argv[5])
with h5py.File(run + "/particles.h5", "r") as f:
    t, force = f["time"][:], f["force"][:, 0, :]
before = max(k for k in range(len(t)) if t[k] <= t[-1] - 1.0 + 1e-9)
with open(run + "/diagnostics.csv") as f:
    rows = list(csv.DictReader(f))
gmres = sum(float(r["stokes_iterations"]) for r in rows) / len(rows)
print("%s,%s,%.6f,%.6f,%.6f,%.1f,%.1f" % (d, s, 500 * force[-1, 0], 500 * force[-1, 1],
      500 * force[before, 0], gmres, 1000 * (user + system) / len(rows)))
EOF
  done
done | tee -a "$CSV"

"$PYTHON" - "$CSV" << 'EOF'
import csv, sys
reference = 5.57953523384
runs = {}
for r in csv.DictReader(open(sys.argv[1])):
    runs.setdefault(float(r["d_over_h"]), {})[float(r["shift"])] = float(r["cd"])
for d, cd in sorted(runs.items()):
    if 0.0 not in cd or 2.0 not in cd:
        continue
    slope = (cd[2.0] - cd[0.0]) / 2.0  # per h
    moved = {s: c - slope * s for s, c in sorted(cd.items()) if s < 2.0}
    mean = sum(moved.values()) / len(moved)
    spread = (max(moved.values()) - min(moved.values())) / mean
    worst = max(abs(c / reference - 1.0) for c in moved.values())
    print("D/h %g: moved back %s; mean %.5f (%+.3f %%), spread %.3f %%, worst %.3f %%" % (
        d, " ".join("%.5f" % c for c in moved.values()), mean, 100 * (mean / reference - 1),
        100 * spread, 100 * worst))
EOF
