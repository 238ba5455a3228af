#!/bin/bash
# Max |u - u_ref| on x = 0.5 and max |v - v_ref| on y = 0.5 between two lid-driven cavity results
# directories (unit square), from their last field snapshots, at the nodes of the coarser run RUN;
# REFERENCE is a finer run of the same scene whose cell count is a multiple of RUN's (the engine's
# own fine-grid solution: the mesh error of RUN when both use the same dt, since the splitting's
# first-order error in dt is then the same in both). docs/evidence/validation.md, lid-driven cavity.
# Usage: cavity_self_errors.sh RUN REFERENCE
set -euo pipefail
a=$1; b=$2
la=$(ls "$a"/fields/snap_*.h5 | sort | tail -1); lb=$(ls "$b"/fields/snap_*.h5 | sort | tail -1)
tmp=$(mktemp -d); trap 'rm -rf "$tmp"' EXIT
for f in u v; do
  h5dump -d /$f -y -w 0 -m '%.15g' -o "$tmp/a$f.txt" "$la" > /dev/null
  h5dump -d /$f -y -w 0 -m '%.15g' -o "$tmp/b$f.txt" "$lb" > /dev/null
done
awk -v tmp="$tmp" '
function load(file, arr,   line, n, k, parts, m) { n = 0
  while ((getline line < file) > 0) { gsub(/[ \t]/, "", line); m = split(line, parts, ",")
    for (k = 1; k <= m; ++k) if (parts[k] != "") arr[n++] = parts[k] + 0 }
  close(file); return n }
function abs(x) { return x < 0 ? -x : x }
BEGIN { na = load(tmp "/au.txt", AU); load(tmp "/av.txt", AV); nb = load(tmp "/bu.txt", BU); load(tmp "/bv.txt", BV)
  ma = int(sqrt(na) + 0.5); mb = int(sqrt(nb) + 0.5); n = ma - 1; nr = mb - 1; r = nr / n; ca = n / 2; cb = nr / 2
  if (nr % n != 0) { printf "cavity_self_errors.sh: the reference has %d cells, not a multiple of %d\n", nr, n > "/dev/stderr"; exit 2 }
  eu = 0; ev = 0; su = 0; sv = 0
  for (k = 0; k <= n; ++k) { du = abs(AU[k * ma + ca] - BU[k * r * mb + cb]); dv = abs(AV[ca * ma + k] - BV[cb * mb + k * r])
    if (du > eu) { eu = du; yu = k / n } if (dv > ev) { ev = dv; xv = k / n } }
  printf "cells %d vs %d  max|u-uref| %.6f (y = %.4f)  max|v-vref| %.6f (x = %.4f)\n", n, nr, eu, yu, ev, xv }'
