#!/usr/bin/env bash
# The paper's figures 9 and 10 as (a)-(d) panels, each one `dlmfd figure` command (docs/gallery.md,
# "Multi-panel figures"), from the runs of bench/gallery.sh (the paper's resolution) or any runs of
# the same cases and times (docs/gallery.md's are at half the paper's resolution).
# Usage: bench/gallery_figures.sh RUNS_DIR OUT_DIR [BUILD_DIR] [DT]
#   RUNS_DIR holds 5.2_oldroyd_b (5.2_pair_oldroyd_b_caption_start to t = 25, snapshots every
#   0.5) and 5.3a (5.3a_eleven_disks to t = 18.3, every 0.1); DT their time step (default 0.0004,
#   the paper's).
set -euo pipefail
cd "$(dirname "$0")/.."
runs=$1
out=$2
build=${3:-build}
dt=${4:-0.0004}
dlmfd=${DLMFD:-$build/client/dlmfd}
mkdir -p "$out"
step_of() { awk -v t="$1" -v dt="$dt" 'BEGIN { printf "%d", t / dt + 0.5 }'; }
pair="$runs/5.2_oldroyd_b"
iso=(--isolines 12 --lines-only --no-caption --units cgs)

# Figure 9: (a) the velocity field at t = 0.5, (b) isovalues of trA at t = 0.5, (c) at t = 9.5,
# (d) at t = 25.
"$dlmfd" figure --columns 4 --size 7.5,4.2 --dpi 200 --font-size 7 --out "$out/figure9.png" \
  --panel "plot $pair --snapshot $(step_of 0.5) --quantity speed --arrows 8 --units cgs --no-caption" \
  --panel "plot $pair --snapshot $(step_of 0.5) ${iso[*]}" \
  --panel "plot $pair --snapshot $(step_of 9.5) ${iso[*]}" \
  --panel "plot $pair --snapshot $(step_of 25) ${iso[*]}" > /dev/null

# Figure 10, as its caption reads (one run): (a) isovalues of trA at t = 1, (b) at t = 15.6, (c) at
# t = 18.3; and (d) the trajectories to t = 18.3.
log=(--quantity trA-2 --log --range 1e-4,10 --isolines 10 --no-caption --units cgs)
"$dlmfd" figure --columns 4 --size 7.5,4.2 --dpi 200 --font-size 7 --out "$out/figure10.png" \
  --panel "plot $runs/5.3a --snapshot $(step_of 1) ${log[*]}" \
  --panel "plot $runs/5.3a --snapshot $(step_of 15.6) ${log[*]}" \
  --panel "plot $runs/5.3a --snapshot $(step_of 18.3) ${log[*]}" \
  --panel "chart $runs/5.3a --x x --y y --equal --title '' --units cgs --legend-title '' --label 5.3a" > /dev/null
ls -la "$out/figure9.png" "$out/figure10.png"
