#!/usr/bin/env bash
# Cost of step (35) by representation (issue 17, point 6; docs/evidence/performance.md, "Conformation step
# (35)"): bench/conformation_step_bench's variants 0 (Oldroyd-B standard), 1 (log) and 2 (sqrt) on
# THREADS threads, ROUNDS invocations of 5 repetitions each in random interleaving (so that a change
# of the machine's load falls on all three alike), then per variant the median over all repetitions
# of the wall and CPU time per step and the ratios to the standard step.
#   bench/conformation_cost.sh     # BENCH=build/bench/conformation_step_bench ROUNDS=8 THREADS=1
set -euo pipefail
cd "$(dirname "$0")/.."
BENCH=${BENCH:-build/bench/conformation_step_bench}
ROUNDS=${ROUNDS:-8}
THREADS=${THREADS:-1}
out=$(mktemp -d)
trap 'rm -rf "$out"' EXIT
for r in $(seq "$ROUNDS"); do
  OMP_WAIT_POLICY=active "$BENCH" --benchmark_filter="BM_ConformationStep/$THREADS/[012]/" \
    --benchmark_repetitions=5 --benchmark_enable_random_interleaving=true \
    --benchmark_min_time=0.2 --benchmark_out="$out/$r.json" --benchmark_out_format=json \
    > /dev/null 2> "$out/$r.err" || { cat "$out/$r.err" >&2; exit 1; }
done
python3 - "$out" "$ROUNDS" <<'PY'
import json, statistics, sys
out, rounds = sys.argv[1], int(sys.argv[2])
wall, cpu = {}, {}
for r in range(1, rounds + 1):
    for b in json.load(open(f"{out}/{r}.json"))["benchmarks"]:
        if b.get("run_type") != "iteration":
            continue
        v = b["run_name"].split("/")[2]
        wall.setdefault(v, []).append(b["real_time"])
        cpu.setdefault(v, []).append(b["cpu_time"])
names = {"0": "Oldroyd-B, standard", "1": "Oldroyd-B, log", "2": "Oldroyd-B, sqrt"}
w0, c0 = statistics.median(wall["0"]), statistics.median(cpu["0"])
print("| variant | repetitions | wall, median | CPU, median | wall / standard | CPU / standard |")
print("|---|---|---|---|---|---|")
for v in ("0", "1", "2"):
    w, c = statistics.median(wall[v]), statistics.median(cpu[v])
    print(f"| {names[v]} | {len(wall[v])} | {w:.2f} ms | {c:.2f} ms | {w / w0:.2f} | {c / c0:.2f} |")
PY
