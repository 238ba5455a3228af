#!/usr/bin/env bash
# The multiplier CG of step (37) against the ratio of the particle mesh to the fluid mesh (issue 13
# point 8; docs/evidence/work_precision.md, "The particle mesh against the fluid mesh"): the scene
# cases/verification/periodic_box_large_disk.toml (a fixed disk D = 0.62 in a unit periodic box,
# h = 1/64) with particle_mesh.h = RATIO * domain.h, under each coupling of the constraint; prints
# the CG's iterations in each of the first five steps, or the solver's error when it fails.
#   bench/multiplier_conditioning.sh    # SOLVER=build/solver/dlmfd-solve RATIOS="0.5 ... 2"
set -euo pipefail
cd "$(dirname "$0")/.."
SOLVER=${SOLVER:-build/solver/dlmfd-solve}
RATIOS=${RATIOS:-"0.5 0.75 1.0 1.1 1.2 1.3 1.37 1.5 2.0"}
SCENE=cases/verification/periodic_box_large_disk.toml
out=$(mktemp -d)
trap 'rm -rf "$out"' EXIT
h=$(awk '/^h = / { print $3; exit }' "$SCENE")
printf '%-12s %-6s %s\n' coupling 'hp/h' 'CG iterations, steps 1-5'
for coupling in incremental paper; do
  for ratio in $RATIOS; do
    hp=$(python3 -c "print($ratio * $h)")
    dir="$out/$coupling-$ratio"
    if OMP_NUM_THREADS=1 "$SOLVER" "$SCENE" --out "$dir" --set "particle_mesh.h=$hp" \
      --set "splitting.constraint=\"$coupling\"" > "$dir.log" 2>&1; then
      its=$(python3 -c "
import csv, sys
rows = list(csv.DictReader(open(sys.argv[1])))
print(' '.join(r['multiplier_iterations'] for r in rows[:5]))" "$dir/diagnostics.csv")
    else
      its=$(grep -o 'did not converge.*residual [0-9.e+-]* > [0-9.e+-]*' "$dir.log" | head -1)
      its=${its:-"failed: $(tail -1 "$dir.log")"}
    fi
    printf '%-12s %-6s %s\n' "$coupling" "$ratio" "$its"
  done
done
