#!/usr/bin/env bash
# The start-up channel (cases/verification/waters_king.toml, the family "wk" of
# bench/stability_map.sh, all the viscosity in step (33)) at E = lambda = 10, where the standard
# scheme fails, run in each representation of fluid.conformation (standard, log, sqrt) and, for
# comparison, with the Giesekus (alpha 0.1) and FENE-P (L^2 100) models (docs/evidence/stability.md,
# "Representations and models"). To t = 10, wave advection, one thread, JOBS at a time.
#   bench/representation_map.sh     # SOLVE=build/solver/dlmfd-solve WORK=runs/representation_map
# Output: docs/stability/representations.csv and a Markdown table on stdout.
set -euo pipefail
cd "$(dirname "$0")/.."
SOLVE=$(realpath "${SOLVE:-build/solver/dlmfd-solve}")
WORK=${WORK:-runs/representation_map}
JOBS=${JOBS:-2}
mkdir -p "$WORK" docs/stability

for h in 0.03125 0.015625; do
  for dt in 0.005 0.01 0.02 0.04; do
    for variant in standard log sqrt giesekus fene_p; do
      case $variant in
        standard | log | sqrt) model="--set fluid.conformation=$variant" ;;
        giesekus) model="--set fluid.model=giesekus --set fluid.mobility=0.1" ;;
        fene_p) model="--set fluid.model=fene_p --set fluid.extensibility=100" ;;
      esac
      size=$(awk -v h="$h" 'BEGIN { printf "%.10g", 4 * h }')
      cells=$(awk -v h="$h" 'BEGIN { printf "%d", 1 / h + 0.5 }')
      echo "wk_c${cells}_dt${dt}_${variant}|$h|$dt|$variant|--set splitting.advection=wave --set domain.h=$h --set domain.size=[$size,2.0] --set time.dt=$dt --set time.end=10 --set fluid.relaxation_time=10 --set output.fields_every=0 --set output.checkpoint_every=0 $model"
    done
  done
done > "$WORK/runs.txt"

run_one() {
  local name h dt variant sets
  IFS='|' read -r name h dt variant sets <<< "$1"
  [ -f "$WORK/$name/summary.json" ] && return 0
  rm -rf "${WORK:?}/${name:?}"
  # shellcheck disable=SC2086  # sets is a list of flags
  "$SOLVE" cases/verification/waters_king.toml --out "$WORK/$name" --threads 1 --quiet $sets \
    > "$WORK/$name.log" 2>&1 || true
}
export -f run_one
export SOLVE WORK
# shellcheck disable=SC2016  # $1 expands in the child bash
tr '\n' '\0' < "$WORK/runs.txt" | OMP_WAIT_POLICY=passive xargs -0 -P "$JOBS" -I{} bash -c 'run_one "$1"' _ {}

python3 - "$WORK" <<'PY'
import csv, json, sys
work = sys.argv[1]
rows = []
for line in open(f"{work}/runs.txt"):
    name, h, dt, variant, _ = line.rstrip("\n").split("|")
    try:
        s = json.load(open(f"{work}/{name}/summary.json"))
    except (OSError, ValueError):
        s = {"status": "missing", "reason": "", "time": float("nan"), "steps": 0}
    max_tr, min_eig = float("nan"), float("nan")
    try:
        with open(f"{work}/{name}/diagnostics.csv") as f:
            d = list(csv.DictReader(f))
        max_tr = max(float(r["max_trA"]) for r in d if r.get("max_trA"))
        min_eig = min(float(r["min_eig_A"]) for r in d if r.get("min_eig_A"))
    except (OSError, ValueError, KeyError):
        pass
    rows.append([name, h, dt, variant, s.get("status"), s.get("time"), max_tr, min_eig,
                 (s.get("reason") or "")[:120]])
with open("docs/stability/representations.csv", "w", newline="") as f:
    w = csv.writer(f)
    w.writerow(["run", "h", "dt", "variant", "status", "t_end", "max_trA", "min_eig_A", "reason"])
    w.writerows(rows)
print("| h | dt | " + " | ".join(["standard", "log", "sqrt", "giesekus 0.1", "fene_p 100"]) + " |")
print("|---|---|---|---|---|---|---|")
for h in ["0.03125", "0.015625"]:
    for dt in ["0.005", "0.01", "0.02", "0.04"]:
        cells = []
        for v in ["standard", "log", "sqrt", "giesekus", "fene_p"]:
            r = next(r for r in rows if r[1] == h and r[2] == dt and r[3] == v)
            cells.append(("ok" if r[4] == "completed" else f"failed t={r[5]:.3g}") +
                         f", max trA {r[6]:.3g}")
        print(f"| 1/{round(1/float(h))} | {dt} | " + " | ".join(cells) + " |")
PY
