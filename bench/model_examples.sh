#!/usr/bin/env bash
# The examples of issue 17, point 5 (docs/evidence/validation.md, "Examples: the paper's 5.2 pair with each
# model"), at the PAPER'S RESOLUTION (each case file's h = 1/96, h_p = 1/70, dt = 4e-4):
#   - the 5.2 pair (dropped at y = 7.7 and 7.3) with Oldroyd-B in the standard and the log
#     representation, with Giesekus (alpha 0.1) and with FENE-P (L^2 100), to t = 9.5 (figure 9c's
#     time; the chain has formed by then);
#   - 5.3a (eleven disks) with Giesekus and FENE-P to t = 15.6 (figure 10b's time; about 40 min a
#     run on one core), beside bench/gallery.sh's Oldroyd-B run of the same scene
#     (runs/gallery/5.3a: run bench/gallery.sh first).
# One setting differs from the case files, as in bench/gallery.sh: wave advection (a third of the
# cost of least squares a step). One thread a run, JOBS runs at a time; a run whose summary says
# completed is not run again, an interrupted one resumes from its checkpoint, so a second call only
# tabulates and redraws.
# Usage: bench/model_examples.sh [BUILD_DIR]   (default build; JOBS=2; PYTHON=python3, with h5py).
# Runs go to runs/model_examples/, pictures to docs/figures/models/, the numbers to stdout.
set -euo pipefail
cd "$(dirname "$0")/.."
build=${1:-build}
export SOLVE=$build/solver/dlmfd-solve
dlmfd=$build/client/dlmfd
python=${PYTHON:-python3}  # with h5py (Debian's python3-h5py, scripts/setup.sh)
export PYTHONPATH=$build/python${PYTHONPATH:+:$PYTHONPATH}  # dlmfd.results, for fall_numbers.py
export RUNS=runs/model_examples
out=docs/figures/models
mkdir -p "$RUNS" "$out"

# name|scene|end time|snapshot interval
cat > "$RUNS/runs.txt" << 'EOF'
5.2_oldroyd_b|cases/paper/5.2_pair_oldroyd_b.toml|9.5|0.5
5.2_oldroyd_b_log|cases/models/5.2_pair_oldroyd_b_log.toml|9.5|0.5
5.2_giesekus|cases/models/5.2_pair_giesekus.toml|9.5|0.5
5.2_fene_p|cases/models/5.2_pair_fene_p.toml|9.5|0.5
5.3a_giesekus|cases/models/5.3a_eleven_disks_giesekus.toml|15.6|0.2
5.3a_fene_p|cases/models/5.3a_eleven_disks_fene_p.toml|15.6|0.2
EOF

run_one() {
  local name scene end every resume=()
  IFS='|' read -r name scene end every <<< "$1"
  if grep -q '"completed"' "$RUNS/$name/summary.json" 2> /dev/null; then return 0; fi
  if [[ -f $RUNS/$name/checkpoint.h5 ]]; then resume=(--resume); fi
  echo "model_examples: $(date -u +%T) running $name" >&2
  OMP_WAIT_POLICY=passive "$SOLVE" "$scene" --out "$RUNS/$name" --quiet --threads 1 \
    --set splitting.advection=wave --set time.end="$end" --set output.fields_every="$every" \
    "${resume[@]}" > "$RUNS/$name.log" 2>&1 || true
  echo "model_examples: $(date -u +%T) $name: $(grep -o '"status": *"[a-z]*"' \
    "$RUNS/$name/summary.json" 2> /dev/null || echo no summary)" >&2
}
export -f run_one
# shellcheck disable=SC2016  # $1 expands in the child bash
tr '\n' '\0' < "$RUNS/runs.txt" | xargs -0 -P "${JOBS:-2}" -I{} bash -c 'run_one "$1"' _ {}

# The numbers of docs/evidence/validation.md's tables (bench/fall_numbers.py: fall speeds, gaps, the kiss,
# trA).
for name in 5.2_oldroyd_b 5.2_oldroyd_b_log 5.2_giesekus 5.2_fene_p; do
  "$python" bench/fall_numbers.py "$RUNS/$name" --window 0,1 --window 5,9.5 --gap-at 1 --gap-at 3 \
    --gap-at 6 --gap-at 9.5
done
# shellcheck disable=SC2054  # the commas are inside each window a,b
windows=(--window 0,8 --window 0,15.6 --window 0.5,2 --window 2,5 --window 5,8 --window 5,10
  --window 10,15.6)
"$python" bench/fall_numbers.py runs/gallery/5.3a "${windows[@]}"
for name in 5.3a_giesekus 5.3a_fene_p; do
  "$python" bench/fall_numbers.py "$RUNS/$name" "${windows[@]}"
done

# Pictures: trA - 2 (log colours, the gallery's range) of the pair at t = 9.5 and of 5.3a at t = 8
# and 15.6, the pair's gap and velocity against time (one curve a disk and model), and 5.3a's
# trajectories.
picture() {  # picture RUN STEP FILE CAPTION
  "$dlmfd" plot "$1" --snapshot "$2" --quantity trA-2 --log --range 1e-4,10 --isolines 10 \
    --width 420 --height 1000 --caption "$4" --out "$out/$3" > /dev/null
}
declare -A label=([5.2_oldroyd_b]="Oldroyd-B" [5.2_oldroyd_b_log]="Oldroyd-B, log-conformation"
  [5.2_giesekus]="Giesekus, alpha = 0.1" [5.2_fene_p]="FENE-P, L^2 = 100")
for name in 5.2_oldroyd_b 5.2_oldroyd_b_log 5.2_giesekus 5.2_fene_p; do
  picture "$RUNS/$name" 23750 "${name}_trA_t9.5.png" \
    "5.2 pair, ${label[$name]}: t = 9.5, h = 1/96, h_p = 1/70, dt = 0.0004, wave advection"
done
pairs=("$RUNS/5.2_oldroyd_b" "$RUNS/5.2_oldroyd_b_log" "$RUNS/5.2_giesekus" "$RUNS/5.2_fene_p")
labels=(--label "Oldroyd-B" --label "Oldroyd-B, log" --label "Giesekus 0.1" --label "FENE-P 100")
"$dlmfd" chart "${pairs[@]}" "${labels[@]}" --y gap --logy --width 800 --height 500 \
  --title "5.2 pair by model: gap between the disks" -o "$out/5.2_models_gap.png" > /dev/null
"$dlmfd" chart "${pairs[@]}" "${labels[@]}" --y v --width 800 --height 500 \
  --title "5.2 pair by model: vertical velocity of the disks" -o "$out/5.2_models_v.png" > /dev/null
label+=([5.3a_giesekus]="Giesekus, alpha = 0.1" [5.3a_fene_p]="FENE-P, L^2 = 100")
for t in 8 15.6; do
  step=$(awk -v t="$t" 'BEGIN { printf "%d", t / 0.0004 + 0.5 }')
  picture runs/gallery/5.3a "$step" "5.3a_oldroyd_b_trA_t$t.png" \
    "5.3a, Oldroyd-B: t = $t, h = 1/96, h_p = 1/70, dt = 0.0004, wave advection"
  for name in 5.3a_giesekus 5.3a_fene_p; do
    picture "$RUNS/$name" "$step" "${name}_trA_t$t.png" \
      "5.3a, ${label[$name]}: t = $t, h = 1/96, h_p = 1/70, dt = 0.0004, wave advection"
  done
done
"$dlmfd" chart runs/gallery/5.3a "$RUNS/5.3a_giesekus" "$RUNS/5.3a_fene_p" --label "Oldroyd-B" \
  --label "Giesekus 0.1" --label "FENE-P 100" --x x --y y --equal --width 700 --height 900 \
  --title "5.3a by model: trajectories" -o "$out/5.3a_models_trajectory.png" > /dev/null
echo "model_examples: pictures in $out" >&2
