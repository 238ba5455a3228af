#!/usr/bin/env bash
# A fixed ellipse's drag, lift and torque over sub-grid positions (issue 37 point 4: the
# orientation noise a free ellipse would feel). Schaefer-Turek 2D-1's channel and inflow
# (cases/verification/schaefer_turek_2d1.toml, Re = 20 on the disk's diameter) with the disk
# replaced by a fixed ellipse of the same area (a / b = 2, a = 0.0707107, b = 0.0353553) at
# ANGLE degrees, its centre shifted by s = k h / 4 along x (k = 0..7, so s covers [0, 2h)),
# run to steady state (t = END). Prints a row per shift and the mean and spread of
# Cd = 2 Fx / (rho U^2 D), Cl = 2 Fy / (rho U^2 D), Cm = 2 T / (rho U^2 D^2), with U = 0.2 the
# mean inflow and D = 0.1 the equal-area diameter. With k = 8 among SHIFTS (s = 2h: the same
# discrete geometry as k = 0), each value is also moved back to x = 0.2 with the slope of the 2h
# shift, as bench/cut_cell_schaefer_turek.sh does for the disk: what is left over the shifts is the
# grid's, not the inflow's distance (the forces fall as the body moves downstream, about 0.5 % of
# Cd per cell at D/h = 20). SETS: more overrides (e.g. --set particle_mesh.kind=\"cut_cell\").
#
#   bench/fixed_ellipse_positions.sh                   # h = 0.005 (D/h = 20), ANGLE=30, END=8
#   H=0.0025 DT=0.0025 END=4 SHIFTS="0 2 4 6" bench/fixed_ellipse_positions.sh   # D/h = 40
#   SHIFTS="0 1 2 3 4 5 6 7 8" SETS='--set particle_mesh.kind="cut_cell"' bench/fixed_ellipse_positions.sh
set -euo pipefail
cd "$(dirname "$0")/.."
SOLVER=${SOLVER:-build/solver/dlmfd-solve}
H=${H:-0.005}
DT=${DT:-0.005}
END=${END:-8}
ANGLE=${ANGLE:-30}
SHIFTS=${SHIFTS:-0 1 2 3 4 5 6 7}  # k of s = k h / 4
OUT=${OUT:-runs/fixed_ellipse_positions}
read -r -a EXTRA <<< "${SETS:-}"  # more overrides, as words
mkdir -p "$OUT"
theta=$(/usr/bin/python3 -c "import math; print(math.radians($ANGLE))")
# The case's disk (diameter 0.1) as the ellipse of the same area.
scene="$OUT/schaefer_turek_ellipse.toml"
sed -e 's/^diameter = 0.1$/shape = "ellipse"\nsemi_axes = [0.07071067811865475, 0.035355339059327376]/' \
  -e 's/^title = .*/title = "Schaefer-Turek 2D-1 with a fixed ellipse of the disk'"'"'s area, a \/ b = 2"/' \
  cases/verification/schaefer_turek_2d1.toml >"$scene"
grep -q '^shape = "ellipse"' "$scene" || { echo "the case's disk was not found" >&2; exit 2; }
for k in $SHIFTS; do
  x=$(/usr/bin/python3 -c "print(0.2 + $k * $H / 4)")
  dir="$OUT/h${H}_a${ANGLE}_k$k"
  [ -f "$dir/summary.json" ] || nice -n 10 "$SOLVER" "$scene" "${EXTRA[@]}" \
    --out "$dir" --threads 1 --quiet --set domain.h="$H" --set time.dt="$DT" --set time.end="$END" \
    --set "particles.0.angle=$theta" --set "particles.0.center=[$x, 0.2]" \
    --set output.fields_every=0 --set output.particles_every=0.5
done
# shellcheck disable=SC2086  # SHIFTS is a list
/usr/bin/python3 - "$OUT" "$H" "$ANGLE" $SHIFTS <<'PY'
"""The table and the spreads over the shifts."""
import json
import statistics
import sys

out, h, angle = sys.argv[1], float(sys.argv[2]), sys.argv[3]
scale_f, scale_t = 0.5 * 0.2 ** 2 * 0.1, 0.5 * 0.2 ** 2 * 0.1 ** 2
rows = []
for k in (int(k) for k in sys.argv[4:]):
    s = json.load(open(f"{out}/h{sys.argv[2]}_a{angle}_k{k}/summary.json"))
    p = s["particles"][0]
    rows.append((k, p["force"][0] / scale_f, p["force"][1] / scale_f, p["torque"] / scale_t,
                 s["status"]))
    print(f"shift {k}h/4  Cd {rows[-1][1]:.5f}  Cl {rows[-1][2]:+.5f}  Cm {rows[-1][3]:+.5f}  "
          f"{rows[-1][4]}")
shifted = {r[0]: r for r in rows}
for name, i in (("Cd", 1), ("Cl", 2), ("Cm", 3)):
    v = [r[i] for r in rows if r[0] < 8]
    m = statistics.mean(v)
    print(f"{name}: mean {m:+.5f}  spread (max - min) {max(v) - min(v):.5f}  "
          f"= {100 * (max(v) - min(v)) / abs(m):.2f} % of the mean  (h = {h}, angle {angle} deg)")
    if 0 in shifted and 8 in shifted:  # back to x = 0.2 with the slope of the 2h shift
        slope = (shifted[8][i] - shifted[0][i]) / 8
        c = [r[i] - slope * r[0] for r in rows if r[0] < 8]
        mc = statistics.mean(c)
        print(f"{name} at x = 0.2: mean {mc:+.5f}  spread {max(c) - min(c):.5f}  "
              f"= {100 * (max(c) - min(c)) / abs(mc):.3f} % of the mean  (slope {slope:+.6f} a "
              f"quarter cell)")
PY
