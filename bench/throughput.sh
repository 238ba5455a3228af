#!/usr/bin/env bash
# Throughput of parameter studies through the daemon (issue 6, point 4; docs/evidence/service.md,
# "Throughput"): velocity node updates per second of
#   (1) one job alone, on 2 threads   (dlmfdd --max-concurrent 1 --solver-threads 2), and
#   (2) two jobs at once, 1 thread each (dlmfdd --max-concurrent 2 --solver-threads 1, the thread
#       share the daemon picks by itself on 2 cores),
# each a real dlmfdd on loopback with a real SQLite queue running the real solver on the paper's
# 5.2 pair (h = 1/96, wave advection, STEPS steps, no field output). The rate is
#   sum over jobs of (velocity nodes x steps) / (wall time from submitting to the last job's end),
# so daemon, process start and output costs are included. Prints one CSV line per setting and the
# ratio (2) / (1); the issue asks for at least 0.9.
#
#   bench/throughput.sh                  # BUILD=build STEPS=1000 WORK=runs/throughput
set -euo pipefail
cd "$(dirname "$0")/.."

BUILD=${BUILD:-build}
STEPS=${STEPS:-1000}
WORK=${WORK:-runs/throughput}
DLMFD="$BUILD/client/dlmfd"
DLMFDD="$BUILD/server/dlmfdd"
SOLVER="$BUILD/solver/dlmfd-solve"
CASE=cases/paper/5.2_pair_oldroyd_b.toml
NODES=$((193 * 769))  # velocity nodes of the 2 x 8 box at h = 1/96
END=$(awk -v s="$STEPS" 'BEGIN { printf "%.10g", s * 0.0004 }')
SETS=(--set splitting.advection=wave --set time.end="$END" --set output.fields_every=0
      --set output.checkpoint_every=0)

# shellcheck source=scripts/dlmfdd_lib.sh
. scripts/dlmfdd_lib.sh
trap stop_dlmfdd EXIT

# run_jobs LABEL JOBS THREADS: JOBS jobs at once, THREADS each; prints
# "LABEL,jobs,threads_per_job,wall_s,node_updates_per_s".
run_jobs() {
  local label=$1 jobs=$2 threads=$3
  rm -rf "${WORK:?}/${label:?}"
  start_dlmfdd "$WORK/$label" "$WORK/$label.log" --max-concurrent "$jobs" --solver-threads "$threads" >/dev/null
  local start end k
  local -a ids=()
  start=$(date +%s.%N)
  for k in $(seq 1 "$jobs"); do
    ids+=("$("$DLMFD" submit "$CASE" "${SETS[@]}" --name "throughput-$label-$k" --tag throughput)")
  done
  for id in "${ids[@]}"; do
    if ! "$DLMFD" watch "$id" >/dev/null; then
      echo "throughput: job $id did not complete:" >&2
      "$DLMFD" show "$id" >&2
      exit 1
    fi
  done
  end=$(date +%s.%N)
  stop_dlmfdd
  awk -v l="$label" -v j="$jobs" -v t="$threads" -v s="$start" -v e="$end" -v n="$NODES" -v st="$STEPS" \
    'BEGIN { w = e - s; printf "%s,%d,%s,%.2f,%.0f\n", l, j, t, w, j * n * st / w }'
}

mkdir -p "$WORK"
echo "setting,jobs,threads_per_job,wall_s,node_updates_per_s"
one=$(run_jobs one_job 1 2)
echo "$one"
two=$(run_jobs two_jobs 2 1)
echo "$two"
awk -F, -v a="$one" -v b="$two" 'BEGIN { split(a, x, ","); split(b, y, ","); printf "ratio two_jobs / one_job = %.3f\n", y[5] / x[5] }'
