#!/usr/bin/env bash
# The figures of docs/gallery.md: the paper's figures (section 5) drawn with dlmfd plot, chart and
# movie from SHORT, COARSE runs (h = 1/48 or 1/32 instead of 1/96, wave advection, dt = 0.001,
# end times cut), so the whole gallery is made in minutes on two cores. The full runs of
# bench/paper_cases.sh with bench/paper_figures.sh give the same figures at the paper's resolution.
# Usage: bench/gallery.sh [BUILD_DIR]   (default build). Runs go to runs/gallery/, pictures to
# docs/figures/gallery/.
set -euo pipefail
cd "$(dirname "$0")/.."
build=${1:-build}
solve="$build/solver/dlmfd-solve"
dlmfd="$build/client/dlmfd"
runs=runs/gallery
out=docs/figures/gallery
mkdir -p "$runs" "$out"

coarse32=(--set domain.h=0.03125 --set particle_mesh.h=0.04285714285714286)
coarse48=(--set domain.h=0.020833333333333332 --set particle_mesh.h=0.02857142857142857)
quick=(--set splitting.advection=wave --set time.dt=0.001 --set output.checkpoint_every=0)

run() {  # run NAME CASE [--set ...]: one short run, skipped when its summary says completed
  local name=$1 case=$2
  shift 2
  if grep -q '"completed"' "$runs/$name/summary.json" 2>/dev/null; then return; fi
  echo "gallery: running $name" >&2
  OMP_NUM_THREADS=1 nice -n 5 "$solve" "cases/paper/$case.toml" --out "$runs/$name" --quiet \
    --threads 1 "${quick[@]}" "$@"
}
step_of() { awk -v t="$1" 'BEGIN { printf "%d", t / 0.001 + 0.5 }'; }
# The settings the figures were made with, in their captions (the scene titles give the paper's).
declare -A mesh=([5.1a]="h = 1/48, h_p = 1/35" [5.2_newtonian]="h = 1/32, h_p = 1/23.3"
  [5.2_oldroyd_b]="h = 1/32, h_p = 1/23.3" [5.3a]="h = 1/32, h_p = 1/23.3")
plot() {  # plot RUN T FILE [flags]: the snapshot at time T
  local run=$1 t=$2 file=$3
  shift 3
  "$dlmfd" plot "$runs/$run" --snapshot "$(step_of "$t")" --out "$out/$file" \
    --caption "$run, short coarse run: ${mesh[$run]}, dt = 0.001, wave advection" "$@" > /dev/null
}
chart() { "$dlmfd" chart --width 800 --height 500 "$@" 2> /dev/null > /dev/null; }

# 5.1a, figures 3 and 4: one disk (rho_p = 1.5) in an Oldroyd-B liquid (lambda = 0.01), h = 1/48.
run 5.1a 5.1a_disk_rho1.5_h96_dt1e-3 "${coarse48[@]}" --set time.end=0.35 \
  --set output.fields_every=0.05
for q in u v omega; do
  chart "$runs/5.1a" --label "h = 1/48, dt = 0.001" --y "$q" --title "5.1a: $q (figure 3)" \
    -o "$out/5.1a_$q.png"
done
plot 5.1a 0.3 5.1a_velocity_t0.3.png --quantity speed --arrows 14 --window 0,2.5,1.5,5.5 \
  --width 520 --height 900
plot 5.1a 0.3 5.1a_trA_t0.3.png --quantity trA-2 --log --isolines 10 --window 0,2.5,1.5,5.5 \
  --width 520 --height 900

# 5.2, figure 8: the Newtonian pair (drafting, kissing, tumbling), h = 1/32, to t = 3.
run 5.2_newtonian 5.2_pair_newtonian "${coarse32[@]}" --set time.end=3 --set output.fields_every=0.5
plot 5.2_newtonian 0.5 5.2_newtonian_velocity_t0.5.png --quantity speed --arrows 12 \
  --width 420 --height 1000
plot 5.2_newtonian 2.5 5.2_newtonian_vorticity_t2.5.png --quantity vorticity --arrows 12 \
  --width 420 --height 1000
chart "$runs/5.2_newtonian" --label "Newtonian pair" --y y --title "5.2 Newtonian: y of the centres" \
  -o "$out/5.2_newtonian_y.png"
chart "$runs/5.2_newtonian" --label "Newtonian pair" --x x --y y --equal \
  --title "5.2 Newtonian: trajectories (equal scales)" -o "$out/5.2_newtonian_trajectory.png"

# 5.2, figure 9: the Oldroyd-B pair dropped at y = 7.7 and 6.6, h = 1/32, to t = 2.5; and its movie.
run 5.2_oldroyd_b 5.2_pair_oldroyd_b_caption_start "${coarse32[@]}" --set time.end=2.5 \
  --set output.fields_every=0.05
plot 5.2_oldroyd_b 0.5 5.2_oldroyd_b_velocity_t0.5.png --quantity speed --arrows 12 \
  --width 420 --height 1000
plot 5.2_oldroyd_b 0.5 5.2_oldroyd_b_trA_t0.5.png --isolines 12 --lines-only --width 420 \
  --height 1000
plot 5.2_oldroyd_b 2.5 5.2_oldroyd_b_trA_t2.5.png --quantity trA-2 --log --range 1e-4,10 --isolines 10 \
  --width 420 --height 1000
chart "$runs/5.2_oldroyd_b" --label "Oldroyd-B pair" --y gap --logy \
  --title "5.2 Oldroyd-B: gap between the disks" -o "$out/5.2_oldroyd_b_gap.png"
"$dlmfd" movie "$runs/5.2_oldroyd_b" --quantity trA-2 --log --range 1e-4,10 --isolines 8 \
  --window 0,4.5,2,8 \
  --width 480 --height 720 --fps 10 --out "$out/5.2_oldroyd_b_trA.mp4" \
  --caption "5.2 Oldroyd-B pair, short coarse run: ${mesh[5.2_oldroyd_b]}, dt = 0.001" > /dev/null

# 5.3a, figure 10(a): eleven disks in a wide channel (eta 0.13, lambda 1.3), h = 1/32, to t = 1.
run 5.3a 5.3a_eleven_disks "${coarse32[@]}" --set time.end=1 --set output.fields_every=0.5
plot 5.3a 1 5.3a_trA_t1.png --quantity trA-2 --log --range 1e-4,10 --isolines 10 --width 420 \
  --height 1000
chart "$runs/5.3a" --label "5.3a" --x x --y y --equal --title "5.3a: trajectories to t = 1" \
  -o "$out/5.3a_trajectory.png"

# Series named by the parameter in which runs differ: three relaxation times of the 5.1a disk.
for lambda in 0.01 0.05 0.2; do
  run "5.1a_lambda$lambda" 5.1a_disk_rho1.5_h96_dt1e-3 "${coarse48[@]}" --set time.end=0.3 \
    --set output.fields_every=0 --set "fluid.relaxation_time=$lambda"
done
chart "$runs"/5.1a_lambda* --y v --title "5.1a: v for three relaxation times" \
  -o "$out/5.1a_relaxation_sweep_v.png"
ls -la "$out"
