#!/usr/bin/env bash
# The serial fraction of each sub-step measured in wall time from 1 and 2 threads (issue 34,
# points 1-2; docs/evidence/performance.md, "Threads"). bench/oldroyd_b_step_bench's full Oldroyd-B step
# (the 5.2 pair, wave advection, the engine's default coupling, devss and both diagonals) on 1 and
# 2 threads, the repetitions of the two interleaved in random order (a shared machine's load then
# falls on both alike), the minimum over the repetitions of each sub-step's ms. With the speed-up
# S = t1 / t2, Amdahl's law t_T = t1 (s + (1 - s) / T) gives the serial fraction s = 2 / S - 1
# and the efficiency it implies at 16 threads, E16 = 1 / (16 s + 1 - s). The instruction-count
# measure of the same fraction (load-independent) is bench/serial_fraction.sh's.
#
#   bench/thread_scaling.sh            # BUILD=build REPS=6 (repetitions of each thread count)
set -euo pipefail
cd "$(dirname "$0")/.."

BUILD=${BUILD:-build}
REPS=${REPS:-6}
json=$(mktemp /tmp/thread_scaling.XXXXXX.json)
trap 'rm -f "$json"' EXIT

echo "load before: $(cut -d' ' -f1-3 /proc/loadavg)" >&2
"$BUILD/bench/oldroyd_b_step_bench" \
  --benchmark_filter='BM_OldroydBStep/threads:[12]/coupling:2/stress:1/diagonals:1' \
  --benchmark_repetitions="$REPS" --benchmark_enable_random_interleaving=true \
  --benchmark_format=json --benchmark_out="$json" --benchmark_out_format=json >/dev/null
echo "load after: $(cut -d' ' -f1-3 /proc/loadavg)" >&2

python3 - "$json" <<'EOF'
import json, sys
runs = [b for b in json.load(open(sys.argv[1]))["benchmarks"] if b.get("run_type") == "iteration"]
keys = {"step": "real_time", "stokes": "ms_stokes", "advection": "ms_advection",
        "conformation": "ms_conformation", "particles": "ms_particles"}
best = {}
for b in runs:
    threads = int(b["name"].split("threads:")[1].split("/")[0])
    for name, key in keys.items():
        value = b[key]
        best[(name, threads)] = min(best.get((name, threads), value), value)
print("substep,ms_1_thread,ms_2_threads,speedup_2,serial_fraction,amdahl_efficiency_16")
for name in keys:
    t1, t2 = best[(name, 1)], best[(name, 2)]
    speedup = t1 / t2
    s = 2.0 / speedup - 1.0
    e16 = 1.0 / (16.0 * s + 1.0 - s) if s > -1.0 / 15.0 else float("nan")
    print(f"{name},{t1:.3f},{t2:.3f},{speedup:.3f},{s:.4f},{e16:.3f}")
EOF
