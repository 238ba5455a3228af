#!/usr/bin/env bash
# The chain statistics of the paper's 5.3a in a channel periodic along the fall (issue 37 point 3):
# bench/chain_statistics.py's tables for near pairs of surface gap below GAP radii, and three charts
# drawn by `dlmfd chart` into docs/figures: 5.3a_periodic_pair_angles.png (the pair angles to
# gravity per window of the fall distance), 5.3a_periodic_chain_lengths.png (the fraction of disks
# in chains of each length) and 5.3a_periodic_fall.png (the mean drop against time).
# docs/evidence/validation_particles.md, "The paper's eleven disks over ten fall distances".
#   bench/chain_statistics.sh RESULTS_DIR   # GAP=0.5 WINDOWS=5 DLMFD=build/client/dlmfd
# The run (about 9 ms a step on one thread of this machine, 62,500 steps):
#   build/solver/dlmfd-solve cases/periodic/5.3a_eleven_disks_periodic.toml --out runs/p53 --threads 1
set -euo pipefail
cd "$(dirname "$0")/.."
RUN=${1:?results directory}
GAP=${GAP:-0.5}
WINDOWS=${WINDOWS:-5}
DLMFD=${DLMFD:-build/client/dlmfd}
CSV=$(mktemp -d)
trap 'rm -rf "$CSV"' EXIT
/usr/bin/python3 bench/chain_statistics.py "$RUN" --gap "$GAP" --windows "$WINDOWS" --csv "$CSV"
title="5.3a in a channel periodic along the fall (h = 1/48); near: gap < $GAP radii"
"$DLMFD" chart --csv "$CSV/pair_angles.csv" --xcol angle --ycol fraction --group window --markers \
  --xtitle "angle of a near pair's line of centres to gravity (degrees; 0: one above the other)" \
  --ytitle "fraction of near pairs (15-degree bins)" --ylim 0,0.4 --title "$title" \
  -o docs/figures/5.3a_periodic_pair_angles.png
"$DLMFD" chart --csv "$CSV/chain_lengths.csv" --xcol length --ycol fraction --group window \
  --markers --xtitle "chain length (disks connected by near pairs; 5: five or more)" \
  --ytitle "fraction of the disks" --ylim 0,1 --title "$title" \
  -o docs/figures/5.3a_periodic_chain_lengths.png
"$DLMFD" chart --csv "$CSV/fall.csv" --xcol t --ycol drop --csv-label "mean drop of the 11 disks" \
  --ytitle "mean drop (the paper's run: 3.1)" --title "$title" -o docs/figures/5.3a_periodic_fall.png
