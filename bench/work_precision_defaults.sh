#!/bin/bash
# Work precision at the defaults against the peer (issue 32 point 5; docs/evidence/work_precision.md, "At the
# defaults, against the peer"). Each scene names no numerics key and keeps the default tolerances:
# what a user who writes only the physics gets. Two problems, each a mesh ladder with dt set by the
# flow (dt proportional to h):
#   dfg     Schaefer-Turek 2D-1 to its steady drag (the channel 2.255 long, t = 5, dt = DFG_DT h,
#           2 by default: the Courant number max|u| dt / h is then 0.83, the peer's 0.8, as
#           bench/work_precision.sh's problem e at dt = h): |Cd - 5.57953523384| / 5.57953523384,
#           against the CPU seconds of the whole run to t = 5; with the peer's three points
#           (Basilisk's embedded boundaries, peers.md).
#   cavity  the lid-driven cavity at Re 100 (cases/lid_driven_cavity.toml's physics, its [splitting]
#           table dropped), lid Courant number 0.64 (dt = 0.64 h), t = 30: the max deviation from
#           Ghia's points (the measure of the peer's two points in peers.md, problem b), and from the
#           centre-line extrema of Marchi, Suero & Araki (2009; cases/verification/cavity_extrema.sh),
#           against the CPU seconds to t = 30.
# The peer's cost to the same time: peers.md gives its one-thread wall ms a step at CFL 0.8, not its
# step count; its step is taken as 0.8 h / U, U our run's largest speed on the same grid (the
# cavity: the lid's, 1). Basilisk's Courant number is per face and component, at most the speed's,
# so its steps are at least this long and its estimated cost an upper bound.
# Writes docs/work_precision/defaults_<problem>.csv and docs/figures/wp_defaults_<problem>.png and
# prints the CSVs. Runs one thread each at nice 19; our cost is CPU time (user + system over the
# run, set-up included), which a shared machine perturbs least; the peer's ms are its one-thread
# wall ms on an idle machine of this type.
#   bench/work_precision_defaults.sh [DLMFD_SOLVE]   ONLY=dfg|cavity  WORK=runs/work_precision_defaults
#                                                    DFG_H="0.01025 ..." DFG_DT=2 CAVITY_CELLS="32 64 128 256"
# A run whose summary.json is in WORK already is not run again.
set -euo pipefail
root=$(cd "$(dirname "$0")/.." && pwd)
solve=$(realpath "${1:-$root/build/solver/dlmfd-solve}")
build=$(dirname "$(dirname "$solve")")
wp_error=${WP_ERROR:-$build/bench/wp_error}
dlmfd=${DLMFD:-$build/client/dlmfd}
work=${WORK:-$root/runs/work_precision_defaults}
only=${ONLY:-dfg cavity}
data=$root/docs/work_precision
figures=$root/docs/figures
mkdir -p "$work" "$data" "$figures"

run() {  # dir scene --set ...
  local dir=$1 scene=$2
  shift 2
  [[ -f $dir/summary.json && -f $dir.cpu ]] && return 0
  rm -rf "$dir"
  echo "run $dir" >&2
  { time nice -n 19 "$solve" "$scene" --out "$dir" "$@" --threads 1 --quiet 2> "$dir.log" || true; } 2> "$dir.time"
  awk '/^user|^sys/ { split($2, a, "m"); s += a[1] * 60 + a[2] } END { printf "%.3f\n", s }' "$dir.time" > "$dir.cpu"
  rm -f "$dir.time"
}
json_number() { grep -o "\"$2\": *[-0-9.eE+]*" "$1/summary.json" | head -1 | sed 's/.*: *//'; }
cpu_ms() { awk -v c="$(cat "$1.cpu")" -v n="$(json_number "$1" steps)" 'BEGIN { printf "%.4g", 1e3 * c / n }'; }
cpu_s() { awk -v c="$(cat "$1.cpu")" 'BEGIN { printf "%.4g", c }'; }
# The run's largest speed at its end, max|u| = cfl h / dt (diagnostics.csv's last row).
max_speed() {
  awk -F, -v h="$2" -v dt="$3" 'NR == 1 { for (i = 1; i <= NF; ++i) if ($i == "cfl") c = i; next }
    { v = $c } END { printf "%.6g", v * h / dt }' "$1/diagnostics.csv"
}
# The peer's CPU seconds to time T at CFL 0.8 on cell size h with largest speed U: ms a step times
# T / (0.8 h / U) steps.
peer_s() { awk -v ms="$1" -v t="$2" -v h="$3" -v u="$4" 'BEGIN { printf "%.4g", ms / 1e3 * t * u / (0.8 * h) }'; }
relative() { awk -v v="$1" -v r="$2" 'BEGIN { e = (v - r) / r; if (e < 0) e = -e; printf "%.6e", e }'; }

if [[ $only == *dfg* ]]; then
  csv=$data/defaults_dfg.csv
  factor=${DFG_DT:-2}
  echo "series,h,d_over_h,dt,steps,max_speed,courant,cpu_ms_per_step,cpu_s_to_t5,cd,cl,error" > "$csv"
  declare -A speed
  for h in ${DFG_H:-0.01025 0.00854166666667 0.00732142857143 0.005125 0.0025625 0.00128125}; do
    dt=$(awk -v h="$h" -v f="$factor" 'BEGIN { printf "%.10g", f * h }')
    dir=$work/dfg_h${h}_dt$factor
    run "$dir" "$root/cases/verification/schaefer_turek_2d1.toml" --set domain.h="$h" \
      --set particle_mesh.h="$(awk -v h="$h" 'BEGIN { printf "%.12g", h * 96 / 70 }')" \
      --set 'domain.size=[2.255,0.41]' --set time.end=5 --set time.dt="$dt" \
      --set output.fields_every=0 --set output.particles_every=0.1 --set output.checkpoint_every=0
    read -r cd cl < <("$wp_error" particle "$dir" | awk '{ printf "%.10g %.6g\n", 2 * $7 / (0.2 * 0.2 * 0.1), 2 * $8 / (0.2 * 0.2 * 0.1) }')
    speed[$h]=$(max_speed "$dir" "$h" "$dt")
    echo "dlmfd at the defaults,$h,$(awk -v h="$h" 'BEGIN { printf "%.4g", 0.1 / h }'),$dt,$(json_number "$dir" steps),${speed[$h]},$(awk -v u="${speed[$h]}" -v h="$h" -v dt="$dt" 'BEGIN { printf "%.3g", u * dt / h }'),$(cpu_ms "$dir"),$(cpu_s "$dir"),$cd,$cl,$(relative "$cd" 5.57953523384)" >> "$csv"
  done
  # The peer (docs/sources/peers.md, DFG 2D-1): h, C_D, one-thread ms a step; its steps to t = 5
  # at CFL 0.8 with our largest speed on its grid (nan where we did not run that grid).
  while read -r h cd ms; do
    u=${speed[$h]:-nan}
    echo "Basilisk (peers.md),$h,$(awk -v h="$h" 'BEGIN { printf "%.4g", 0.1 / h }'),$(awk -v h="$h" -v u="$u" 'BEGIN { printf "%.4g", 0.8 * h / u }'),$(awk -v h="$h" -v u="$u" 'BEGIN { printf "%.0f", 5 * u / (0.8 * h) }'),$u,0.8,$ms,$(peer_s "$ms" 5 "$h" "$u"),$cd,nan,$(relative "$cd" 5.57953523384)" >> "$csv"
  done <<'PEER'
0.01025 5.5815 5.85
0.005125 5.5613 21.1
0.0025625 5.5698 62.1
PEER
  "$dlmfd" chart --csv "$csv" --xcol cpu_s_to_t5 --ycol error --group series --logx --logy --markers \
    --title "Schaefer-Turek 2D-1 at the defaults: |Cd - 5.5795| / 5.5795 against CPU s to t = 5" \
    --out "$figures/wp_defaults_dfg.png" > /dev/null
  cat "$csv"
fi

if [[ $only == *cavity* ]]; then
  scene=$work/cavity_re100_physics.toml
  awk '/^\[splitting\]/ { skip = 1; next } /^\[/ { skip = 0 } !skip' "$root/cases/lid_driven_cavity.toml" > "$scene"
  csv=$data/defaults_cavity.csv
  echo "series,cells,h,dt,steps,cpu_ms_per_step,cpu_s_to_t30,ghia_error,marchi_u_min,marchi_v_max,marchi_v_min,error" > "$csv"
  for n in ${CAVITY_CELLS:-32 64 128 256}; do
    h=$(awk -v n="$n" 'BEGIN { printf "%.10g", 1 / n }')
    dt=$(awk -v h="$h" 'BEGIN { printf "%.10g", 0.64 * h }')
    dir=$work/cavity_$n
    run "$dir" "$scene" --set domain.h="$h" --set time.dt="$dt" --set time.end=30 \
      --set output.fields_every=1 --set output.checkpoint_every=0
    ghia=$(bash "$root/cases/verification/cavity_ghia_errors.sh" "$dir" |
      sed 's/.*max|u-Ghia| \([0-9.]*\).*max|v-Ghia| \([0-9.]*\).*/\1 \2/' | awk '{ print ($1 > $2 ? $1 : $2) }')
    read -r du dv dw < <(bash "$root/cases/verification/cavity_extrema.sh" "$dir" 100 |
      sed 's/.*minus reference \([-+0-9.e]*\) \([-+0-9.e]*\) \([-+0-9.e]*\).*/\1 \2 \3/')
    echo "dlmfd at the defaults,$n,$h,$dt,$(json_number "$dir" steps),$(cpu_ms "$dir"),$(cpu_s "$dir"),$ghia,$du,$dv,$dw,$ghia" >> "$csv"
  done
  # The peer (docs/sources/peers.md): cells, one-thread ms a step (64: 1.71; 128: wall 18.2 s
  # over steps not recorded, so not drawn), max |u - Ghia|, max |v - Ghia|; its steps to t = 30 at
  # CFL 0.8 with the lid's speed 1.
  echo "Basilisk (peers.md),64,0.015625,0.0125,2400,1.71,$(peer_s 1.71 30 0.015625 1),0.0091,nan,nan,nan,0.0091" >> "$csv"
  "$dlmfd" chart --csv "$csv" --xcol cpu_s_to_t30 --ycol error --group series --logx --logy --markers \
    --title "Lid-driven cavity Re 100 at the defaults: max deviation from Ghia against CPU s to t = 30" \
    --out "$figures/wp_defaults_cavity.png" > /dev/null
  cat "$csv"
fi
