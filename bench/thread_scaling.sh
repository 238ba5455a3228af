#!/usr/bin/env bash
# The serial fraction of each sub-step measured in wall time from 1 and 2 threads (issue 34,
# points 1-2; docs/evidence/performance.md, "Threads"). bench/oldroyd_b_step_bench's full Oldroyd-B step
# (the 5.2 pair, wave advection, the engine's default coupling, devss and both diagonals) on 1 and
# 2 threads, the repetitions of the two interleaved in random order (a shared machine's load then
# falls on both alike), the minimum over the repetitions of each sub-step's ms. With the speed-up
# S = t1 / t2, Amdahl's law t_T = t1 (s + (1 - s) / T) gives the serial fraction s = 2 / S - 1
# and the efficiency it implies at 16 threads, E16 = 1 / (16 s + 1 - s). The instruction-count
# measure of the same fraction (load-independent) is bench/serial_fraction.sh's.
# In the same run, bench/machine_ceiling_bench's arithmetic (registers only) and streaming (STREAM's
# triad over arrays the size of the pair's velocity arrays) kernels on 1 and 2 threads: the rows
# ceiling_arithmetic and ceiling_stream are what this machine gives a second thread for work
# with no shared resource but the cores, and for work that streams the grid as a sub-step does.
# The host's steal share (time a virtual machine's cores waited for the host, from /proc/stat)
# goes to stderr: where it is not near 0 the ratios measure the host's other tenants.
#
#   bench/thread_scaling.sh            # BUILD=build REPS=6 (repetitions of each thread count)
set -euo pipefail
cd "$(dirname "$0")/.."

BUILD=${BUILD:-build}
REPS=${REPS:-6}
json=$(mktemp /tmp/thread_scaling.XXXXXX.json)
ceiling=$(mktemp /tmp/thread_scaling.XXXXXX.json)
trap 'rm -f "$json" "$ceiling"' EXIT
cpu_times() { head -1 /proc/stat; }

echo "load before: $(cut -d' ' -f1-3 /proc/loadavg)" >&2
before=$(cpu_times)
"$BUILD/bench/oldroyd_b_step_bench" \
  --benchmark_filter='BM_OldroydBStep/threads:[12]/coupling:2/stress:1/diagonals:1' \
  --benchmark_repetitions="$REPS" --benchmark_enable_random_interleaving=true \
  --benchmark_format=json --benchmark_out="$json" --benchmark_out_format=json >/dev/null
"$BUILD/bench/machine_ceiling_bench" \
  --benchmark_filter='BM_Throughput|BM_Triad/threads:[12]/kib:1160/' \
  --benchmark_repetitions="$REPS" --benchmark_enable_random_interleaving=true \
  --benchmark_format=json --benchmark_out="$ceiling" --benchmark_out_format=json >/dev/null
after=$(cpu_times)
echo "load after: $(cut -d' ' -f1-3 /proc/loadavg)" >&2
# /proc/stat's cpu line: user nice system idle iowait irq softirq steal ...
echo "$before" "$after" | awk '{ n = (NF - 2) / 2; total = 0
  for (k = 2; k <= n + 1; ++k) total += $(k + n + 1) - $k
  printf "host steal share during the run: %.2f %%\n", 100 * ($(n + 10) - $9) / total }' >&2

python3 - "$json" "$ceiling" <<'EOF'
import json, sys
runs = [b for b in json.load(open(sys.argv[1]))["benchmarks"] if b.get("run_type") == "iteration"]
ceilings = [b for b in json.load(open(sys.argv[2]))["benchmarks"] if b.get("run_type") == "iteration"]
for b in ceilings:  # one more pseudo sub-step per ceiling kernel, its time in ms
    b["name"] = b["name"].replace("BM_Throughput/", "ceiling_arithmetic/").replace(
        "BM_Triad/", "ceiling_stream/")
    b["ms"] = b["real_time"] * {"ns": 1e-6, "us": 1e-3, "ms": 1.0}[b["time_unit"]]
runs += ceilings
keys = {"step": "real_time", "stokes": "ms_stokes", "advection": "ms_advection",
        "conformation": "ms_conformation", "particles": "ms_particles",
        "ceiling_arithmetic": "ms", "ceiling_stream": "ms"}
best = {}
for b in runs:
    threads = int(b["name"].split("threads:")[1].split("/")[0])
    for name, key in keys.items():
        if name.startswith("ceiling") != b["name"].startswith("ceiling"):
            continue
        if name.startswith("ceiling") and not b["name"].startswith(name):
            continue
        value = b[key]
        best[(name, threads)] = min(best.get((name, threads), value), value)
print("substep,ms_1_thread,ms_2_threads,speedup_2,serial_fraction,amdahl_efficiency_16")
for name in keys:
    t1, t2 = best[(name, 1)], best[(name, 2)]
    speedup = t1 / t2
    s = 2.0 / speedup - 1.0
    e16 = 1.0 / (16.0 * s + 1.0 - s) if s > -1.0 / 15.0 else float("nan")
    print(f"{name},{t1:.4f},{t2:.4f},{speedup:.3f},{s:.4f},{e16:.3f}")
EOF
