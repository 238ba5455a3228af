# shellcheck shell=bash
# Sourced by scripts that drive a real dlmfdd on loopback (scripts/main-job.sh, bench/throughput.sh).
#   start_dlmfdd DATA_DIR LOG_FILE [dlmfdd options...]
# starts "$DLMFDD" (with --solver "$SOLVER") on a free loopback port, waits until it serves, exports
# DLMFD_SERVER and sets DLMFDD_PID; stop_dlmfdd stops it (SIGTERM, then waits). Needs DLMFD, DLMFDD
# and SOLVER (paths of the built binaries). Exit 5 when the daemon does not come up.

start_dlmfdd() {
  local data=$1 log=$2
  shift 2
  mkdir -p "$data"
  rm -f "$data/port"
  "$DLMFDD" --listen 127.0.0.1:0 --port-file "$data/port" --data-dir "$data" --solver "$SOLVER" "$@" \
    >"$log" 2>&1 &
  DLMFDD_PID=$!
  for _ in $(seq 1 150); do
    [ -s "$data/port" ] && break
    if ! kill -0 "$DLMFDD_PID" 2>/dev/null; then
      echo "dlmfdd exited; its log:" >&2
      cat "$log" >&2
      exit 5
    fi
    sleep 0.2
  done
  if [ ! -s "$data/port" ]; then
    echo "dlmfdd wrote no port file within 30 s" >&2
    exit 5
  fi
  DLMFD_SERVER="127.0.0.1:$(tr -d '[:space:]' <"$data/port")"
  export DLMFD_SERVER
  unset DLMFD_TOKEN
  "$DLMFD" health --wait 30
}

stop_dlmfdd() {
  if [ -n "${DLMFDD_PID:-}" ] && kill -0 "$DLMFDD_PID" 2>/dev/null; then
    kill -TERM "$DLMFDD_PID" 2>/dev/null || true
    wait "$DLMFDD_PID" 2>/dev/null || true
  fi
}
