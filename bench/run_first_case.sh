#!/usr/bin/env bash
# Runs a benchmark executable's first case once (one iteration unless the case fixes its own
# minimum time or iteration count), so that a bench that no longer runs fails ctest (label bench;
# bench/CMakeLists.txt). It checks that the case runs to its end, not how fast: the timings of
# docs/evidence/performance.md come from the commands there, on a quiet machine.
#
#   bench/run_first_case.sh build/bench/particle_step_bench
set -euo pipefail
binary=$1
first=$("$binary" --benchmark_list_tests | head -1)
[ -n "$first" ] || { echo "run_first_case: $binary lists no case" >&2; exit 1; }
echo "run_first_case: $first"
# The case's name as an anchored regex: its '/' and ':' are literal there already.
exec "$binary" --benchmark_filter="^${first}\$" --benchmark_min_time=0
