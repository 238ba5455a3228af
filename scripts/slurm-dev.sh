#!/usr/bin/env bash
# A real single-node Slurm for development and the tests labelled `slurm`
# (docs/sources/slurm_single_node.md: Debian 12, slurm 22.05, as root, no systemd, no cgroups).
#
#   scripts/slurm-dev.sh start    installs slurmctld, slurmd, slurm-client, munge (scripts/setup.sh),
#                                 writes the configuration, starts munged, slurmctld, slurmd and
#                                 waits until the node is idle; does nothing when already running
#   scripts/slurm-dev.sh stop     stops slurmd, slurmctld and munged by their pid files
#   scripts/slurm-dev.sh status   exit 0 and `sinfo` when running, exit 1 otherwise
#   scripts/slurm-dev.sh stop-slurmctld | start-slurmctld
#                                 stops or starts slurmctld alone (jobs run on under slurmd;
#                                 the tests of a controller restart during runs use them)
#   scripts/slurm-dev.sh logs     the last lines of slurmctld's and slurmd's logs, and squeue
#   scripts/slurm-dev.sh env      prints `export SLURM_CONF=...` for a shell (eval "$(... env)")
#
# Everything lives under DLMFD_SLURM_DIR (default /tmp/dlmfd-slurm), which this script owns:
# slurm.conf, the pid files, the state and spool directories, the logs and the jobcomp file
# (jobcomp.txt: one line per finished job). The system's /etc/slurm is not touched; the commands
# find the configuration through SLURM_CONF. Plugins: proctrack/linuxproc and task/none (cgroup
# plugins fail in containers), jobcomp/filetxt, no accounting daemon. linuxproc enforces no memory
# limit: fine for tests, not for a site (docs/cluster.md).
set -euo pipefail
cd "$(dirname "$0")/.."
dir="${DLMFD_SLURM_DIR:-/tmp/dlmfd-slurm}"
conf="$dir/slurm.conf"
export SLURM_CONF="$conf"

die() {
  echo "slurm-dev: $*" >&2
  exit 1
}

# True when the process named by the pid file is alive.
alive() { [ -s "$1" ] && kill -0 "$(cat "$1")" 2>/dev/null; }

running() { alive "$dir/run/slurmctld.pid" && alive "$dir/run/slurmd.pid"; }

write_config() {
  local host cpus memory_mb
  host="$(hostname -s)"
  # The machine's processors, not OpenMP's thread count: GNU nproc honours OMP_NUM_THREADS, which
  # scripts/test.sh sets to 1 (a one-CPU node runs one job at a time and a long job blocks the rest).
  cpus="$(env -u OMP_NUM_THREADS -u OMP_THREAD_LIMIT nproc)"
  # Without RealMemory a node offers 1 MB and every --mem fails; 95 % of the machine's memory stays
  # below what slurmd measures (a node that reports less than configured would be drained).
  memory_mb=$(awk '/^MemTotal:/ { print int($2 / 1024 * 0.95) }' /proc/meminfo)
  mkdir -p "$dir/run" "$dir/state" "$dir/spool" "$dir/log" "$dir/munge"
  chown slurm:slurm "$dir/state" "$dir/spool" "$dir/log"
  cat > "$conf.tmp" << EOF
# Written by scripts/slurm-dev.sh: a single-node Slurm for development and tests.
ClusterName=dlmfd-dev
SlurmctldHost=$host
SlurmUser=slurm
AuthType=auth/munge
ProctrackType=proctrack/linuxproc
TaskPlugin=task/none
MpiDefault=none
ReturnToService=2
SlurmctldPidFile=$dir/run/slurmctld.pid
SlurmdPidFile=$dir/run/slurmd.pid
SlurmdSpoolDir=$dir/spool
StateSaveLocation=$dir/state
SchedulerType=sched/backfill
SelectType=select/cons_tres
SelectTypeParameters=CR_Core
AccountingStorageType=accounting_storage/none
JobCompType=jobcomp/filetxt
JobCompLoc=$dir/log/jobcomp.txt
JobAcctGatherType=jobacct_gather/none
SlurmctldLogFile=$dir/log/slurmctld.log
SlurmdLogFile=$dir/log/slurmd.log
SlurmctldPort=6817
SlurmdPort=6818
NodeName=$host CPUs=$cpus RealMemory=$memory_mb State=UNKNOWN
PartitionName=debug Nodes=ALL Default=YES MaxTime=INFINITE State=UP
EOF
  mv "$conf.tmp" "$conf"
}

start_munge() {
  local pidfile="$dir/munge/munged.pid"
  if alive "$pidfile"; then return; fi
  [ -s /etc/munge/munge.key ] || die "/etc/munge/munge.key is missing (Debian's munge creates it)"
  install -d -o munge -g munge -m 0755 /run/munge
  install -d -o munge -g munge -m 0700 "$dir/munge"
  runuser -u munge -- munged --socket=/run/munge/munge.socket.2 --pid-file="$pidfile" \
    --log-file="$dir/munge/munged.log" --seed-file="$dir/munge/munged.seed"
}

wait_idle() {
  local i
  for i in $(seq 1 60); do
    if sinfo -h -o '%t' 2> /dev/null | grep -Eq '^(idle|mix|alloc)'; then return 0; fi
    sleep 1
  done
  die "the node did not become idle within 60 s; see $dir/log/slurmctld.log and slurmd.log"
}

start() {
  [ "$(id -u)" -eq 0 ] || die "start needs root (it installs packages and starts munged as munge)"
  if running; then
    echo "slurm-dev: already running (SLURM_CONF=$conf)"
    return
  fi
  scripts/setup.sh
  write_config
  start_munge
  alive "$dir/run/slurmctld.pid" || slurmctld -f "$conf"
  alive "$dir/run/slurmd.pid" || slurmd -f "$conf"
  wait_idle
  echo "slurm-dev: running (SLURM_CONF=$conf)"
}

stop_one() {
  local pidfile="$1" pid i
  alive "$pidfile" || return 0
  pid="$(cat "$pidfile")"
  kill "$pid"
  for i in $(seq 1 50); do
    kill -0 "$pid" 2> /dev/null || return 0
    sleep 0.2
  done
  echo "slurm-dev: pid $pid ($pidfile) did not stop in 10 s, SIGKILL" >&2
  kill -9 "$pid" 2> /dev/null || true
}

stop() {
  stop_one "$dir/run/slurmd.pid"
  stop_one "$dir/run/slurmctld.pid"
  stop_one "$dir/munge/munged.pid"
  rm -f "$dir/run/"*.pid "$dir/munge/munged.pid"
  echo "slurm-dev: stopped"
}

start_slurmctld() {
  alive "$dir/run/slurmctld.pid" || slurmctld -f "$conf"
  wait_idle
  echo "slurm-dev: slurmctld running"
}

case "${1:-}" in
  start) start ;;
  stop) stop ;;
  stop-slurmctld)
    stop_one "$dir/run/slurmctld.pid"
    rm -f "$dir/run/slurmctld.pid"
    echo "slurm-dev: slurmctld stopped"
    ;;
  start-slurmctld) start_slurmctld ;;
  logs)
    for log in slurmctld.log slurmd.log; do
      echo "== $dir/log/$log (last 40 lines)"
      tail -n 40 "$dir/log/$log" 2> /dev/null || true
    done
    echo "== squeue"
    squeue 2> /dev/null || true
    ;;
  status)
    if running; then
      sinfo
    else
      echo "slurm-dev: not running (start it with scripts/slurm-dev.sh start)"
      exit 1
    fi
    ;;
  env) echo "export SLURM_CONF=$conf" ;;
  *) die "usage: scripts/slurm-dev.sh start|stop|status|logs|env|stop-slurmctld|start-slurmctld" ;;
esac
