#!/usr/bin/env bash
# The drag on the viscosity rule's channel (cases/verification/viscosity_rule_channel.toml) as
# lambda -> 0, under each fluid.stress_splitting: the relative gap |F(lambda) - F(0)| / F(0) against
# lambda, as a CSV and a log-log chart (docs/evidence/validation.md, "The viscosity rule"). About 15 s.
#   bench/viscosity_limit.sh            # SOLVE=build/solver/dlmfd-solve DLMFD=build/client/dlmfd
#                                       # WORK=runs/viscosity_limit OUT=docs/figures/viscosity_limit.png
#                                       # PYTHON=python3, with h5py (Debian's python3-h5py)
set -euo pipefail
cd "$(dirname "$0")/.."
SOLVE=${SOLVE:-build/solver/dlmfd-solve}
DLMFD=${DLMFD:-build/client/dlmfd}
WORK=${WORK:-runs/viscosity_limit}
OUT=${OUT:-docs/figures/viscosity_limit.png}
PYTHON=${PYTHON:-python3}
SCENE=cases/verification/viscosity_rule_channel.toml
mkdir -p "$WORK"

# The x-force on the disk at the last record of a run's particles.h5.
drag() { "$PYTHON" -c "import h5py, sys; print(repr(h5py.File(sys.argv[1])['force'][-1, 0, 0]))" "$1"; }

run() {  # name, then --set arguments
  local name=$1
  shift
  "$SOLVE" "$SCENE" --out "$WORK/$name" --threads 1 --quiet "$@" > "$WORK/$name.log" 2>&1
  drag "$WORK/$name/particles.h5"
}

newtonian=$(run newtonian --set fluid.relaxation_time=0)
echo "splitting,lambda,drag,gap" > "$WORK/viscosity_limit.csv"
for splitting in explicit devss; do
  for lambda in 1e-1 1e-2 1e-3 1e-4 1e-5 1e-6; do
    f=$(run "${splitting}_$lambda" --set "fluid.relaxation_time=$lambda" \
      --set "fluid.stress_splitting=\"$splitting\"")
    gap=$("$PYTHON" -c "import sys; f, n = map(float, sys.argv[1:]); print(abs(f - n) / n)" "$f" \
      "$newtonian")
    echo "$splitting,$lambda,$f,$gap" >> "$WORK/viscosity_limit.csv"
  done
done
column -s, -t < "$WORK/viscosity_limit.csv"
echo "lambda = 0: drag $newtonian"
"$DLMFD" chart --csv "$WORK/viscosity_limit.csv" --xcol lambda --ycol gap --group splitting \
  --logx --logy --markers --title "Drag on the viscosity rule's channel: |F(lambda) - F(0)| / F(0)" \
  -o "$OUT"
echo "chart $OUT"
