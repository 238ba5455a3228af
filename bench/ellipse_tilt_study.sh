#!/usr/bin/env bash
# The ellipse's tilt against the elasticity number, as one study through the daemon (issue 37,
# point 5; docs/studies.md, "A longer study: the ellipse's tilt against the elasticity number").
# Starts dlmfdd on a free loopback port, submits cases/shapes/ellipse_oldroyd_b.toml with one point
# per relaxation time (E = lambda eta / (rho D^2) = 1.6 lambda, D = 2 sqrt(a b) as summary.json),
# watches it to the end, writes the study's table, folds each final orientation into the tilt of
# the long axis from the horizontal (0 broadside-on, 90 long axis vertical), charts the tilt
# against E and stops the daemon.
#
#   bench/ellipse_tilt_study.sh                       # into runs/ellipse-tilt/
#   LAMBDAS=0,0.1,1 OUT=runs/tilt FIGURE=docs/figures/ellipse_tilt_E.png bench/ellipse_tilt_study.sh
#
# Cost: about 11,700 steps a point; the 6 points took 17 minutes on 2 shared cores.
set -euo pipefail
cd "$(dirname "$0")/.."

BUILD=${BUILD:-build}
LAMBDAS=${LAMBDAS:-0,0.01,0.03,0.1,0.375,1}
OUT=${OUT:-runs/ellipse-tilt}
FIGURE=${FIGURE:-$OUT/tilt_E.png}
DLMFD="$BUILD/client/dlmfd"
DLMFDD="$BUILD/server/dlmfdd"
SOLVER="$BUILD/solver/dlmfd-solve"
for binary in "$DLMFD" "$DLMFDD" "$SOLVER"; do
  [ -x "$binary" ] || { echo "ellipse_tilt_study: $binary is missing; build first" >&2; exit 2; }
done

# shellcheck source=scripts/dlmfdd_lib.sh
. scripts/dlmfdd_lib.sh
mkdir -p "$OUT"
trap stop_dlmfdd EXIT
start_dlmfdd "$OUT/daemon" "$OUT/dlmfdd.log"

STUDY=$("$DLMFD" study cases/shapes/ellipse_oldroyd_b.toml --grid "fluid.relaxation_time=$LAMBDAS" \
  --name ellipse-tilt -q)
echo "study $STUDY"
"$DLMFD" watch --study "$STUDY" || echo "watch: exit $? (a point failed; the table says which)"
"$DLMFD" table --study "$STUDY" \
  --columns fluid.relaxation_time,status,reason,E,M,Re,fall_speed,p0.x,p0.angle >"$OUT/table.csv"

/usr/bin/python3 - "$OUT/table.csv" "$OUT/tilt.csv" <<'PY'
"""Adds tilt_deg: the long axis' angle from the horizontal, folded into [0, 90] degrees."""
import csv
import math
import sys

rows = list(csv.DictReader(open(sys.argv[1])))
with open(sys.argv[2], "w", newline="") as out:
    writer = csv.writer(out)
    writer.writerow(["lambda", "E", "M", "Re", "x", "tilt_deg", "status"])
    for r in rows:
        if not r["p0.angle"]:
            continue
        theta = math.degrees(float(r["p0.angle"])) % 180.0  # the long axis is the body's x axis
        tilt = min(theta, 180.0 - theta)
        writer.writerow([r["fluid.relaxation_time"], r["E"], r["M"], r["Re"], r["p0.x"],
                         f"{tilt:.2f}", r["status"]])
        print(f"lambda {r['fluid.relaxation_time']:>6}  E {float(r['E']):7.4f}  "
              f"M {float(r['M']):6.3f}  Re {float(r['Re']):6.3f}  x {float(r['p0.x']):.4f}  "
              f"tilt {tilt:6.2f} deg  {r['status']}")
PY
"$DLMFD" chart --csv "$OUT/tilt.csv" --xcol E --ycol tilt_deg --markers --csv-label "final tilt" \
  --xtitle "elasticity number E = lambda eta / (rho D^2), D = 2 sqrt(ab)" \
  --ytitle "tilt of the long axis from the horizontal (degrees)" \
  --title "Ellipse a/b = 2 settling in an Oldroyd-B liquid, blockage 1/4" --out "$FIGURE"
echo "table $OUT/table.csv, tilt $OUT/tilt.csv, chart $FIGURE"
