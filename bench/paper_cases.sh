#!/usr/bin/env bash
# Runs paper cases (cases/paper/*.toml) one after another into runs/paper/<case>/,
# THREADS solver threads (default 1). On the 2-core machine one lane with THREADS=2 beats two
# lanes: two solvers side by side each run 2.4 times slower (memory bandwidth, docs/evidence/performance.md).
# Usage: bench/paper_cases.sh CASE[@advection] ...
#   CASE is a file name in cases/paper without .toml; @wave or @least_squares overrides
#   splitting.advection (the long viscoelastic runs use @wave, see docs/evidence/validation_paper.md).
# A case whose directory holds checkpoint.h5 and no summary.json resumes from it.
set -uo pipefail
cd "$(dirname "$0")/.."
solver=${SOLVER:-build/solver/dlmfd-solve}
threads=${THREADS:-1}
mkdir -p runs/paper
for spec in "$@"; do
  name=${spec%@*}
  args=()
  out=runs/paper/$name
  if [[ $spec == *@* ]]; then
    args+=(--set "splitting.advection=${spec#*@}")
    out=runs/paper/${name}@${spec#*@}
  fi
  if [[ -f $out/summary.json ]] && grep -q '"completed"' "$out/summary.json"; then
    echo "$(date -u +%T) $spec: already completed"; continue
  fi
  if [[ -f $out/checkpoint.h5 ]]; then args+=(--resume); fi
  echo "$(date -u +%T) $spec: start"
  "$solver" "cases/paper/$name.toml" --out "$out" --threads "$threads" "${args[@]}" > "$out.log" 2>&1
  echo "$(date -u +%T) $spec: exit $?"
done
