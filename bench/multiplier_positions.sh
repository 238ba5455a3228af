#!/usr/bin/env bash
# The multiplier CG of (37) against sub-grid position and particle count, under each
# solvers.multiplier_preconditioner (issue 37 point 4, issue 34 point 4;
# docs/evidence/validation_particles.md, "A multiplier solve whose cost does not depend on sub-grid
# position"): Jeffery's scene (cases/shapes/jeffery_orbit.toml, Couette flow, Re = 0.01) with its
# ellipse (r = 2) or the disk of the same area, centred (f h, f h) off the node (1, 1), f = 0, 1/4,
# 1/2, at h = 1/32 and 1/48 (dt from nu dt / h^2 = 2.048, as bench/jeffery_orbit.sh), to t = END;
# the paper's 5.2 pair, the 102-disk bed of 5.4 and the 1,000-disk bed (cases/fluidized_bed_1000.toml)
# over STEPS steps. Prints per run the CG iterations a step (mean / largest, diagnostics.csv) and,
# with CALLGRIND=1, callgrind's instructions a step inside the particle sub-step
# (Simulation::Impl::MoveParticles, which holds the DLM step) over CG_STEPS steps (BED_CG_STEPS for
# the 1,000-disk bed), on one thread.
#   bench/multiplier_positions.sh   # SOLVE=build/solver/dlmfd-solve PRECONDITIONERS="gram blocks"
#                                   # CASES="disk ellipse pair bed102 bed1000" CELLS="32 48"
#                                   # END=3 STEPS=100 CALLGRIND=1 CG_STEPS=10 BED_CG_STEPS=2
#                                   # WORK=runs/multiplier_positions
set -euo pipefail
cd "$(dirname "$0")/.."
SOLVE=${SOLVE:-build/solver/dlmfd-solve}
PRECONDITIONERS=${PRECONDITIONERS:-gram blocks}
CASES=${CASES:-disk ellipse pair bed102 bed1000}
CELLS=${CELLS:-32 48}
END=${END:-3}
STEPS=${STEPS:-100}
CALLGRIND=${CALLGRIND:-1}
CG_STEPS=${CG_STEPS:-10}
BED_CG_STEPS=${BED_CG_STEPS:-2}
WORK=${WORK:-runs/multiplier_positions}
mkdir -p "$WORK"
QUIET=(--quiet --threads 1 --set output.fields_every=0 --set output.particles_every=0
  --set output.checkpoint_every=0)

# iterations RUN: "mean largest" of the multiplier CG's iterations a step.
iterations() {
  awk -F, 'NR == 1 { for (i = 1; i <= NF; ++i) if ($i == "multiplier_iterations") c = i; next }
    { s += $c; n++; if ($c > m) m = $c } END { printf "%.1f %d", s / n, m }' "$1/diagnostics.csv"
}

# time_step SCENE: its time.dt.
time_step() {
  python3 -c "import sys, tomllib; print(tomllib.load(open(sys.argv[1], 'rb'))['time']['dt'])" "$1"
}

# instructions NAME STEPS DT SCENE ARGS...: callgrind's instructions a step in MoveParticles.
instructions() {
  local name=$1 steps=$2 dt=$3 scene=$4
  shift 4
  if [ "$CALLGRIND" != 1 ]; then echo "-"; return; fi
  local end
  end=$(awk -v d="$dt" -v n="$steps" 'BEGIN { printf "%.17g", (n + 0.5) * d }')
  OMP_NUM_THREADS=1 valgrind --tool=callgrind --callgrind-out-file="$WORK/$name.callgrind" \
    --toggle-collect='dlmfd::Simulation::Impl::MoveParticles*' \
    "$SOLVE" "$scene" "$@" --out "$WORK/$name.cg" "${QUIET[@]}" --set time.end="$end" \
    > "$WORK/$name.cg.log" 2>&1
  callgrind_annotate "$WORK/$name.callgrind" 2>/dev/null |
    awk -v n="$steps" '/PROGRAM TOTALS/ { gsub(",", "", $1); printf "%.3g", $1 / n }'
}

# run NAME ITERATION_END DT SCENE ARGS...: one row (DT: the run's time step).
run() {
  local name=$1 end=$2 dt=$3 scene=$4 steps=$CG_STEPS
  shift 4
  [[ $name == bed1000* ]] && steps=$BED_CG_STEPS
  OMP_NUM_THREADS=1 "$SOLVE" "$scene" "$@" --out "$WORK/$name" "${QUIET[@]}" \
    --set time.end="$end" > "$WORK/$name.log" 2>&1 || { echo "$name failed: $(tail -1 "$WORK/$name.log")"; return; }
  printf '%-34s %-12s %s\n' "$name" "$(iterations "$WORK/$name")" \
    "$(instructions "$name" "$steps" "$dt" "$scene" "$@")"
}

disk_scene="$WORK/disk_couette.toml"
sed -e 's/^shape = "ellipse"/diameter = 0.28284271247461906/' -e '/^semi_axes/d' \
  cases/shapes/jeffery_orbit.toml > "$disk_scene"

printf '%-34s %-12s %s\n' run 'its mean max' 'instructions/step (MoveParticles)'
for pre in $PRECONDITIONERS; do
  set_pre=(--set "solvers.multiplier_preconditioner=\"$pre\"")
  for shape in disk ellipse; do
    [[ " $CASES " == *" $shape "* ]] || continue
    scene=cases/shapes/jeffery_orbit.toml
    [ "$shape" = disk ] && scene=$disk_scene
    for n in $CELLS; do
      h=$(awk -v n="$n" 'BEGIN { printf "%.17g", 1 / n }')
      dt=$(awk -v n="$n" 'BEGIN { printf "%.17g", 2.048 / (4 * n * n) }')
      for f in 0 0.25 0.5; do
        c=$(awk -v f="$f" -v n="$n" 'BEGIN { printf "%.17g", 1 + f / n }')
        run "${shape}_h1_${n}_f${f}_$pre" "$END" "$dt" "$scene" "${set_pre[@]}" --set domain.h="$h" \
          --set time.dt="$dt" --set particles.0.center="[$c, $c]"
      done
    done
  done
  for c in pair bed102 bed1000; do
    [[ " $CASES " == *" $c "* ]] || continue
    case $c in
      pair) scene=cases/paper/5.2_pair_oldroyd_b.toml ;;
      bed102) scene=cases/paper/5.4_fluidized_bed_102.toml ;;
      bed1000) scene=cases/fluidized_bed_1000.toml ;;
    esac
    dt=$(time_step "$scene")
    run "${c}_$pre" "$(awk -v d="$dt" -v n="$STEPS" 'BEGIN { printf "%.17g", (n + 0.5) * d }')" \
      "$dt" "$scene" "${set_pre[@]}"
  done
done
