#!/usr/bin/env bash
# The figures of docs/gallery.md: the paper's figures (section 5) drawn with dlmfd plot, chart and
# movie from runs at the PAPER'S RESOLUTION: each case file's own h = 1/96, h_p = 1/70 and time
# step, to the times of the paper's figures. Two settings differ from the case files, and the
# captions say so: wave advection instead of least squares (3 times cheaper a step on the paper's
# grid, and the scheme of docs/evidence/validation_paper.md's long viscoelastic runs), and snapshots as often as
# the figures and the movie need. About an hour and a half on two cores (docs/gallery.md has each
# run's wall time); a run whose summary says completed is not run again, so a second call only
# redraws.
# Usage: bench/gallery.sh [BUILD_DIR]   (default build; THREADS=2). Runs go to runs/gallery/,
# pictures to docs/figures/gallery/.
set -euo pipefail
cd "$(dirname "$0")/.."
build=${1:-build}
threads=${THREADS:-2}
solve="$build/solver/dlmfd-solve"
dlmfd="$build/client/dlmfd"
runs=runs/gallery
out=docs/figures/gallery
mkdir -p "$runs" "$out"

run() {  # run NAME CASE [--set ...]: one run, skipped when its summary says completed
  local name=$1 case=$2
  shift 2
  if grep -q '"completed"' "$runs/$name/summary.json" 2>/dev/null; then return; fi
  local resume=()
  if [[ -f $runs/$name/checkpoint.h5 ]]; then resume=(--resume); fi
  echo "gallery: $(date -u +%T) running $name" >&2
  OMP_WAIT_POLICY=active "$solve" "cases/paper/$case.toml" --out "$runs/$name" --quiet \
    --threads "$threads" --set splitting.advection=wave "$@" "${resume[@]}"
  echo "gallery: $(date -u +%T) $name done" >&2
}
# The snapshot at time T of a run whose time step is DT.
step_of() { awk -v t="$1" -v dt="$2" 'BEGIN { printf "%d", t / dt + 0.5 }'; }
declare -A dt=([5.1a]=0.001 [5.1a_h128]=0.0004 [5.1a_dt4e-4]=0.0004 [5.1b]=0.0004
  [5.2_newtonian]=0.0004 [5.2_oldroyd_b]=0.0004 [5.3a]=0.0004 [5.3b]=0.0004 [5.3c]=0.0004
  [5.4]=0.0004)
mesh_of() {
  case $1 in
    5.1a_h128) echo "h = 1/128, h_p = 1/120" ;;
    5.3b) echo "h = 1/144, h_p = 1/120" ;;
    *) echo "h = 1/96, h_p = 1/70" ;;
  esac
}
caption_of() { echo "$1: $(mesh_of "$1"), dt = ${dt[$1]}, wave advection"; }
plot() {  # plot RUN T FILE [flags]: the snapshot at time T
  local run=$1 t=$2 file=$3
  shift 3
  "$dlmfd" plot "$runs/$run" --snapshot "$(step_of "$t" "${dt[$run]}")" --out "$out/$file" \
    --caption "$(caption_of "$run")" "$@" > /dev/null
}
chart() { "$dlmfd" chart --width 800 --height 500 "$@" 2> /dev/null > /dev/null; }

# 5.1a, figures 3-6: one disk (rho_p = 1.5) in an Oldroyd-B liquid (lambda = 0.01), on the three
# meshes and time steps of figure 3; figure 5 at t = 0.304, figure 6 at step 818 (t = 0.3272: the
# caption's 0.327 is not a multiple of dt = 0.0004).
run 5.1a 5.1a_disk_rho1.5_h96_dt1e-3 --set time.end=0.35
run 5.1a_h128 5.1a_disk_rho1.5_h128_dt4e-4 --set time.end=0.35 --set output.fields_every=0.152
run 5.1a_dt4e-4 5.1a_disk_rho1.5_h96_dt4e-4 --set time.end=0.35 --set output.fields_every=0.3272
for q in u v omega; do
  chart "$runs/5.1a" "$runs/5.1a_h128" "$runs/5.1a_dt4e-4" --label "+ h = 1/96, dt = 0.001" \
    --label "++ h = 1/128, dt = 0.0004" --label "+++ h = 1/96, dt = 0.0004" --y "$q" \
    --title "5.1a: $q (figure 3)" -o "$out/5.1a_$q.png"
done
near=(--window 0,1.8,1.5,4.8 --width 520 --height 900)
plot 5.1a 0.3 5.1a_velocity_t0.3.png --quantity speed --arrows 14 "${near[@]}"
plot 5.1a 0.3 5.1a_trA_t0.3.png --quantity trA-2 --log --isolines 10 "${near[@]}"
plot 5.1a_h128 0.304 5.1a_h128_velocity_t0.304.png --quantity speed --arrows 14 "${near[@]}"
plot 5.1a_h128 0.304 5.1a_h128_trA_t0.304.png --quantity trA-2 --log --isolines 10 "${near[@]}"
plot 5.1a_dt4e-4 0.3272 5.1a_dt4e-4_velocity_t0.327.png --quantity speed --arrows 14 "${near[@]}"
plot 5.1a_dt4e-4 0.3272 5.1a_dt4e-4_trA_t0.327.png --quantity trA-2 --log --isolines 10 \
  "${near[@]}"

# 5.1b, figure 7: rho_p = 1.02, lambda = 0.3, trA at t = 3.1.
run 5.1b 5.1b_disk_rho1.02_lambda0.3 --set time.end=3.1
plot 5.1b 3.1 5.1b_velocity_t3.1.png --quantity speed --arrows 12 --width 420 --height 1000
plot 5.1b 3.1 5.1b_trA_t3.1.png --quantity trA-2 --log --isolines 10 --width 420 --height 1000
chart "$runs/5.1b" --label "h = 1/96, dt = 0.0004" --y v --title "5.1b: v" -o "$out/5.1b_v.png"

# 5.2, figure 8: the Newtonian pair (drafting, kissing, tumbling) to t = 25.
run 5.2_newtonian 5.2_pair_newtonian --set time.end=25 --set output.fields_every=0.5
for t in 0.5 1.5 2.5 9.5 25; do
  plot 5.2_newtonian "$t" "5.2_newtonian_velocity_t$t.png" --quantity speed --arrows 12 \
    --width 420 --height 1000
done
plot 5.2_newtonian 2.5 5.2_newtonian_vorticity_t2.5.png --quantity vorticity --arrows 12 \
  --width 420 --height 1000
chart "$runs/5.2_newtonian" --label "Newtonian pair" --y y \
  --title "5.2 Newtonian: y of the centres" \
  -o "$out/5.2_newtonian_y.png"
chart "$runs/5.2_newtonian" --label "Newtonian pair" --x x --y y --equal \
  --title "5.2 Newtonian: trajectories (equal scales)" -o "$out/5.2_newtonian_trajectory.png"

# 5.2, figure 9: the Oldroyd-B pair dropped at y = 7.7 and 6.6, to t = 25; and its movie.
run 5.2_oldroyd_b 5.2_pair_oldroyd_b_caption_start --set time.end=25 \
  --set output.fields_every=0.25
plot 5.2_oldroyd_b 0.5 5.2_oldroyd_b_velocity_t0.5.png --quantity speed --arrows 12 \
  --width 420 --height 1000
for t in 0.5 9.5 25; do
  plot 5.2_oldroyd_b "$t" "5.2_oldroyd_b_trA_t$t.png" --isolines 12 --lines-only --width 420 \
    --height 1000
  plot 5.2_oldroyd_b "$t" "5.2_oldroyd_b_trA_log_t$t.png" --quantity trA-2 --log \
    --range 1e-4,10 --isolines 10 --width 420 --height 1000
done
chart "$runs/5.2_oldroyd_b" --label "Oldroyd-B pair" --y gap --logy \
  --title "5.2 Oldroyd-B: gap between the disks" -o "$out/5.2_oldroyd_b_gap.png"
chart "$runs/5.2_oldroyd_b" --label "Oldroyd-B pair" --y y \
  --title "5.2 Oldroyd-B: y of the centres" -o "$out/5.2_oldroyd_b_y.png"
"$dlmfd" movie "$runs/5.2_oldroyd_b" --quantity trA-2 --log --range 1e-4,10 --isolines 8 \
  --width 360 --height 960 --fps 10 --out "$out/5.2_oldroyd_b_trA.mp4" \
  --caption "$(caption_of 5.2_oldroyd_b)" > /dev/null

# 5.3a, figure 10: eleven disks in a wide channel (eta 0.13, lambda 1.3), to t = 18.3.
run 5.3a 5.3a_eleven_disks --set time.end=18.3 --set output.fields_every=0.1
for t in 1 15.6 18.3; do
  plot 5.3a "$t" "5.3a_trA_t$t.png" --quantity trA-2 --log --range 1e-4,10 --isolines 10 \
    --width 420 --height 1000
done
chart "$runs/5.3a" --label "5.3a" --x x --y y --equal --title "5.3a: trajectories to t = 18.3" \
  -o "$out/5.3a_trajectory.png"

# 5.3b, figure 10(c): the 5.3a lattice in a liquid of eta 0.3, lambda 3.5 (rho_p 1.02), on the
# paper's finer mesh h = 1/144, h_p = 1/120, t = 18.3.
run 5.3b 5.3b_eleven_disks_lambda3.5 --set output.fields_every=0.3
plot 5.3b 18.3 5.3b_trA_t18.3.png --quantity trA-2 --log --range 1e-4,1e3 --isolines 10 \
  --width 420 --height 1000
chart "$runs/5.3b" --label "5.3b" --x x --y y --equal --title "5.3b: trajectories to t = 18.3" \
  -o "$out/5.3b_trajectory.png"

# 5.3c, figure 11: eleven disks in a narrow channel (width 1, eta 0.1, lambda 3), t = 21.1; trA
# reaches 2500 there, so its colours go to 1e3.
run 5.3c 5.3c_eleven_disks_narrow --set output.fields_every=0.1
plot 5.3c 21.1 5.3c_trA_t21.1.png --quantity trA-2 --log --range 1e-4,1e3 --isolines 10 \
  --width 300 --height 1000
chart "$runs/5.3c" --label "5.3c" --x x --y y --equal --title "5.3c: trajectories to t = 21.1" \
  -o "$out/5.3c_trajectory.png"

# 5.4, figure 12: fluidization of 102 disks (eta 0.02, lambda 0.5), t = 2 (trA up to 340).
run 5.4 5.4_fluidized_bed_102
for t in 1 2; do
  plot 5.4 "$t" "5.4_trA_t$t.png" --quantity trA-2 --log --range 1e-4,1e3 --isolines 10 \
    --width 420 --height 1000
done

# Series named by the parameter in which runs differ: three relaxation times of the 5.1a disk.
for lambda in 0.01 0.05 0.2; do
  run "5.1a_lambda$lambda" 5.1a_disk_rho1.5_h96_dt1e-3 --set time.end=0.3 \
    --set output.fields_every=0 --set "fluid.relaxation_time=$lambda"
done
chart "$runs"/5.1a_lambda* --y v --title "5.1a: v for three relaxation times" \
  -o "$out/5.1a_relaxation_sweep_v.png"
ls -la "$out"

# Figures 9 and 10 as (a)-(d) panels, one `dlmfd figure` each.
bench/gallery_figures.sh "$runs" "$out" "$build" 0.0004
