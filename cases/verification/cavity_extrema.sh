#!/bin/bash
# Centre-line extrema of a lid-driven cavity results directory (unit square, even cell count, lid
# moving in +x at y = 1) from its last field snapshot: u_min on x = 0.5, v_max and v_min on y = 0.5,
# each the vertex of the parabola through the extreme node and its two neighbours, with the
# deviation from an accurate reference (docs/sources/peers.md, copied into docs/evidence/validation.md):
#   Re 100:  Marchi, Suero & Araki, J. Braz. Soc. Mech. Sci. Eng. 31 (2009) 186-198 (1024^2 finite
#            volumes with Richardson extrapolation): -0.2140424, 0.1795728, -0.2538030;
#   Re 1000: Botella & Peyret, Comput. Fluids 27 (1998) 421-433 (Chebyshev spectral):
#            -0.3885698, 0.3769447, -0.5270771.
# Also prints the largest change of u, v between the last two snapshots (a steady-state check).
# Usage: cavity_extrema.sh RESULTS_DIR [RE]   (RE = 100, the default, or 1000)
set -euo pipefail
dir=$1
re=${2:-100}
case $re in
  100) ref="-0.2140424 0.1795728 -0.2538030" ;;
  1000) ref="-0.3885698 0.3769447 -0.5270771" ;;
  *) echo "cavity_extrema.sh: RE must be 100 or 1000, not $re" >&2; exit 2 ;;
esac
snaps=($(ls "$dir"/fields/snap_*.h5 | sort))
last=${snaps[-1]}
prev=${snaps[-2]}
tmp=$(mktemp -d)
trap 'rm -rf "$tmp"' EXIT
for f in u v; do
  h5dump -d /$f -y -w 0 -m '%.15g' -o "$tmp/$f.txt" "$last" > /dev/null
  h5dump -d /$f -y -w 0 -m '%.15g' -o "$tmp/${f}_prev.txt" "$prev" > /dev/null
done
awk -v tmp="$tmp" -v re="$re" -v ref="$ref" '
function load(file, arr,   line, n, k, parts, m) {
  n = 0
  while ((getline line < file) > 0) {
    gsub(/[ \t]/, "", line)
    m = split(line, parts, ",")
    for (k = 1; k <= m; ++k) if (parts[k] != "") arr[n++] = parts[k] + 0
  }
  close(file)
  return n
}
function abs(x) { return x < 0 ? -x : x }
# Extremum (sign 1: max, -1: min) of f[0..n] (spacing h): the parabola through the extreme interior
# node and its neighbours; sets EXT_AT.
function extremum(f, n, h, sign,   k, best, a, b, c, d2) {
  best = 1
  for (k = 1; k < n; ++k) if (sign * f[k] > sign * f[best]) best = k
  a = f[best - 1]; b = f[best]; c = f[best + 1]; d2 = a - 2 * b + c
  EXT_AT = (best + 0.5 * (a - c) / d2) * h
  return b - (c - a) * (c - a) / (8 * d2)
}
BEGIN {
  split(ref, R, " ")
  nn = load(tmp "/u.txt", U); load(tmp "/v.txt", V)
  load(tmp "/u_prev.txt", UP); load(tmp "/v_prev.txt", VP)
  m = int(sqrt(nn) + 0.5); n = m - 1; h = 1.0 / n; c = n / 2
  for (j = 0; j <= n; ++j) ul[j] = U[j * m + c]
  for (i = 0; i <= n; ++i) vl[i] = V[c * m + i]
  umin = extremum(ul, n, h, -1); yu = EXT_AT
  vmax = extremum(vl, n, h, 1); xmax = EXT_AT
  vmin = extremum(vl, n, h, -1); xmin = EXT_AT
  d = 0
  for (k = 0; k < nn; ++k) { if (abs(U[k] - UP[k]) > d) d = abs(U[k] - UP[k]); if (abs(V[k] - VP[k]) > d) d = abs(V[k] - VP[k]) }
  printf "Re %d  cells %d  u_min %.7f (y = %.4f)  v_max %.7f (x = %.4f)  v_min %.7f (x = %.4f)  minus reference %+.6f %+.6f %+.6f  steady change %.2e\n", re, n, umin, yu, vmax, xmax, vmin, xmin, umin - R[1], vmax - R[2], vmin - R[3], d
}'
