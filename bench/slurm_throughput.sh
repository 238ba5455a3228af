#!/usr/bin/env bash
# 200 queued jobs through a real Slurm (issue 15, point 7; docs/evidence/service.md, "Slurm"): the
# daemon's submission rate, the delay from a job's end to COMPLETED in the daemon, and the
# daemon's CPU while it follows its jobs and polls Slurm.
#
# A real dlmfdd with the slurm executor on loopback (its defaults: slurm_poll_seconds = 10,
# slurm_max_submitted = 100) and the single-node Slurm of scripts/slurm-dev.sh (start it first).
# To queue JOBS jobs before the daemon starts submitting them, a first daemon with
# --slurm-max-submitted 1 takes a blocker job (it runs until cancelled) and queues the others,
# then stops (it leaves the blocker in Slurm); the blocker is cancelled in Slurm; a second daemon
# with the defaults adopts the blocker and submits the queued jobs, at most 100 at once. Each job
# is the cavity case on 16 x 16 cells for one step (the solver's start and end, no output):
# Slurm's own cost dominates. Measured on the second daemon:
#   submission rate   jobs handed to Slurm per second over the first burst (the daemon's log
#                     lines "Slurm job N started": one sbatch each)
#   end -> COMPLETED  per job, the store's finished_time minus the mtime of DIR/solver.exit
#                     (written by the batch script when the solver has ended)
#   daemon CPU        utime + stime of dlmfdd (/proc/PID/stat) over its wall time, and of the
#                     commands it ran (sbatch, squeue, scancel: cutime + cstime)
#
#   bench/slurm_throughput.sh           # BUILD=build JOBS=200 WORK=runs/slurm_throughput
set -euo pipefail
cd "$(dirname "$0")/.."

BUILD=${BUILD:-build}
JOBS=${JOBS:-200}
WORK=${WORK:-runs/slurm_throughput}
DLMFD="$BUILD/client/dlmfd"
DLMFDD="$BUILD/server/dlmfdd"
SOLVER="$(realpath "$BUILD/solver/dlmfd-solve")"

scripts/slurm-dev.sh status >/dev/null || {
  echo "slurm_throughput: no Slurm: start it with scripts/slurm-dev.sh start (as root)" >&2
  exit 2
}
eval "$(scripts/slurm-dev.sh env)"
JOBCOMP="${DLMFD_SLURM_DIR:-/tmp/dlmfd-slurm}/log/jobcomp.txt"

# shellcheck source=scripts/dlmfdd_lib.sh
. scripts/dlmfdd_lib.sh
trap stop_dlmfdd EXIT

rm -rf "${WORK:?}"
mkdir -p "$WORK"
WORK="$(realpath "$WORK")"
SHARED="$WORK/shared"
# The repository's cavity case on 16 x 16 cells, one step, no output.
SCENE=cases/lid_driven_cavity.toml
TINY=(--set domain.h=0.0625 --set time.end=0.01 --set output.fields_every=0
      --set output.checkpoint_every=0)
SLURM_FLAGS=(--executor slurm --slurm-shared-dir "$SHARED" --slurm-jobcomp-file "$JOBCOMP")

# 1. Queue the jobs behind a blocker.
start_dlmfdd "$WORK/data" "$WORK/queue.log" "${SLURM_FLAGS[@]}" --slurm-max-submitted 1 >/dev/null
# `dlmfd submit` prints "submitted NAME as job ID (queued)".
blocker=$("$DLMFD" submit "$SCENE" "${TINY[@]}" --set time.end=1e4 --name blocker |
  grep -o 'j-[0-9a-f]*')
for _ in $(seq 1 300); do [ -s "$SHARED/$blocker/slurm.id" ] && break; sleep 0.2; done
queue_start=$(date +%s.%N)
for k in $(seq 1 "$JOBS"); do
  "$DLMFD" submit "$SCENE" "${TINY[@]}" --name "tiny-$k" --tag slurm-bench >/dev/null
done
queue_end=$(date +%s.%N)
stop_dlmfdd
scancel "$(cat "$SHARED/$blocker/slurm.id")"

# 2. The measured daemon: the defaults.
start=$(date +%s.%N)
start_dlmfdd "$WORK/data" "$WORK/run.log" "${SLURM_FLAGS[@]}" >/dev/null
pid=$DLMFDD_PID
read -r utime0 stime0 < <(awk '{ print $14, $15 }' "/proc/$pid/stat")
while [ "$(sqlite3 "$WORK/data/jobs.db" "SELECT COUNT(*) FROM jobs WHERE state IN (1, 2)")" != 0 ]; do
  sleep 1
done
end=$(date +%s.%N)
read -r utime1 stime1 cutime1 cstime1 < <(awk '{ print $14, $15, $16, $17 }' "/proc/$pid/stat")
stop_dlmfdd

tick=$(getconf CLK_TCK)
completed=$(sqlite3 "$WORK/data/jobs.db" \
  "SELECT COUNT(*) FROM jobs WHERE state = 3 AND name LIKE 'tiny-%'")
echo "jobs: $JOBS queued in $(awk -v a="$queue_start" -v b="$queue_end" 'BEGIN { printf "%.1f", b - a }') s by the CLI, $completed COMPLETED"
echo "wall: $(awk -v a="$start" -v b="$end" 'BEGIN { printf "%.1f", b - a }') s from the daemon's start to the last end"
# Submission rate over the first burst (at most slurm_max_submitted = 100 jobs).
grep -E ' Slurm job [0-9]+ started' "$WORK/run.log" | awk '
  NR <= 100 { split($1, t, "T"); split(t[2], h, ":"); s = h[1] * 3600 + h[2] * 60 + h[3];
    if (NR == 1) first = s; last = s; n = NR }
  END { printf "submission: %d sbatch in %.2f s: %.1f jobs/s\n", n, last - first, (n - 1) / (last - first) }'
# End -> COMPLETED, per job.
sqlite3 -separator ' ' "$WORK/data/jobs.db" \
  "SELECT id, printf('%.6f', finished_time) FROM jobs WHERE state = 3 AND name LIKE 'tiny-%'" |
  while read -r id finished; do
    ended=$(stat -c %.6Y "$SHARED/$id/solver.exit")
    awk -v f="$finished" -v e="$ended" 'BEGIN { printf "%.3f\n", f - e }'
  done | sort -n | awk '
  { d[NR] = $1; sum += $1 }
  END { printf "end -> COMPLETED: mean %.2f s, median %.2f s, p95 %.2f s, max %.2f s (%d jobs)\n",
        sum / NR, d[int((NR + 1) / 2)], d[int(NR * 0.95)], d[NR], NR }'
awk -v u0="$utime0" -v s0="$stime0" -v u1="$utime1" -v s1="$stime1" -v cu="$cutime1" -v cs="$cstime1" \
  -v t="$tick" -v a="$start" -v b="$end" 'BEGIN {
    own = (u1 + s1 - u0 - s0) / t; kids = (cu + cs) / t; w = b - a;
    printf "daemon CPU: %.1f s over %.1f s (%.1f %% of one core); its sbatch/squeue/scancel: %.1f s (%.1f %%)\n",
           own, w, 100 * own / w, kids, 100 * kids / w }'
