#!/usr/bin/env bash
# The README's main job: start dlmfdd on a free loopback port and the web dashboard (dlmfd-web) in
# front of it, submit a real case at a modest resolution, print the URL where the job can be
# watched in a browser, watch it to the end, fetch its results into runs/main-job/, draw a PNG,
# print the summary, stop both. Needs a build in build/ (scripts/build.sh).
#
#   CASE=cases/paper/...toml SETS="--set domain.h=0.02 --set time.end=1" scripts/main-job.sh
#   WEB_PORT=7480 KEEP_WEB=1 scripts/main-job.sh   # a fixed port; keep the dashboard up at the end
set -euo pipefail
cd "$(dirname "$0")/.."

BUILD=${BUILD:-build}
# The paper's 5.2 Oldroyd-B pair (eta 0.12, lambda 1.4) at half the paper's resolution, to t = 2.
CASE=${CASE:-cases/paper/5.2_pair_oldroyd_b.toml}
SETS=${SETS:---set domain.h=0.020833333333333332 --set particle_mesh.h=0.02857142857142857 --set time.dt=0.002 --set time.end=2 --set output.fields_every=0.5 --set output.particles_every=0.02}
RUNS=${RUNS:-runs}
DLMFD="$BUILD/client/dlmfd"
DLMFDD="$BUILD/server/dlmfdd"
SOLVER="$BUILD/solver/dlmfd-solve"
WEB="$BUILD/web/dlmfd-web"

for binary in "$DLMFD" "$DLMFDD" "$SOLVER" "$WEB"; do
  if [ ! -x "$binary" ]; then
    echo "main-job: $binary is missing; build first: scripts/build.sh" >&2
    exit 2
  fi
done
if [ ! -f "$CASE" ]; then
  echo "main-job: no scene file $CASE (set CASE=...)" >&2
  exit 2
fi

DATA="$RUNS/daemon"
OUT="$RUNS/main-job"
# shellcheck source=scripts/dlmfdd_lib.sh
. scripts/dlmfdd_lib.sh

echo "== starting dlmfdd (data in $DATA, log in $RUNS/dlmfdd.log)"
WEB_PID=""
stop_all() {
  if [ -n "$WEB_PID" ] && kill -0 "$WEB_PID" 2>/dev/null; then
    kill -TERM "$WEB_PID" 2>/dev/null || true
    wait "$WEB_PID" 2>/dev/null || true
  fi
  stop_dlmfdd
}
trap stop_all EXIT
start_dlmfdd "$DATA" "$RUNS/dlmfdd.log"

echo "== starting the dashboard dlmfd-web (log in $RUNS/dlmfd-web.log)"
rm -f "$DATA/web-port"
"$WEB" --listen "127.0.0.1:${WEB_PORT:-0}" --server "$DLMFD_SERVER" --port-file "$DATA/web-port" \
  >"$RUNS/dlmfd-web.log" 2>&1 &
WEB_PID=$!
for _ in $(seq 1 150); do
  [ -s "$DATA/web-port" ] && break
  if ! kill -0 "$WEB_PID" 2>/dev/null; then
    echo "dlmfd-web exited; its log:" >&2
    cat "$RUNS/dlmfd-web.log" >&2
    exit 5
  fi
  sleep 0.2
done
WEB_URL="http://127.0.0.1:$(tr -d '[:space:]' <"$DATA/web-port")"

echo "== submitting $CASE $SETS"
# shellcheck disable=SC2086  # SETS is a list of flags
JOB=$("$DLMFD" submit "$CASE" $SETS --name main-job --tag main-job)
echo "job $JOB"
echo "watch it in a browser: $WEB_URL/jobs/$JOB  (all studies and jobs: $WEB_URL/)"

echo "== watching"
outcome=0
"$DLMFD" watch "$JOB" || outcome=$?

echo "== fetching results to $OUT"
rm -rf "$OUT"
"$DLMFD" fetch "$JOB" --out "$OUT"

PICTURE=""
if ls "$OUT"/fields/snap_*.h5 >/dev/null 2>&1; then
  # trA for an Oldroyd-B run, the speed for a Newtonian one: $OUT/<quantity>_<step>.png
  PICTURE=$("$DLMFD" plot "$OUT")
fi

echo "== summary"
if command -v python3 >/dev/null 2>&1 && [ -f "$OUT/summary.json" ]; then
  python3 - "$OUT/summary.json" <<'PY'
import json, sys
s = json.load(open(sys.argv[1]))
particles = s.get("particles", [])
count = len(particles) if isinstance(particles, list) else len(particles.get("position", []))
print(f"status      {s.get('status')}" + (f" ({s['reason']})" if s.get("reason") else ""))
print(f"steps       {s.get('steps')}")
print(f"time        {s.get('time')}")
print(f"ms/step     {float(s.get('ms_per_step', 'nan')):.4g}")
print(f"wall        {float(s.get('wall_seconds', 'nan')):.4g} s")
print(f"particles   {count}")
PY
elif [ -f "$OUT/summary.json" ]; then
  cat "$OUT/summary.json"
else
  "$DLMFD" show "$JOB"
fi
echo "results     $OUT/"
[ -n "$PICTURE" ] && echo "picture     $PICTURE"
echo "daemon log  $RUNS/dlmfdd.log"
if [ "${KEEP_WEB:-0}" = 1 ]; then
  echo "== the daemon and the dashboard stay up until Ctrl-C: $WEB_URL/jobs/$JOB"
  wait "$WEB_PID" || true
fi
exit "$outcome"
