#!/usr/bin/env bash
# Builds the daemon, the solver and the server tests with ThreadSanitizer in build-tsan and runs the
# server tests (ctest -L server). Usage: scripts/tsan.sh [extra ctest arguments]
set -euo pipefail
root="$(cd "$(dirname "$0")/.." && pwd)"
build="$root/build-tsan"
cmake -S "$root" -B "$build" -DDLMFD_TSAN=ON -DCMAKE_BUILD_TYPE=RelWithDebInfo -DDLMFD_BUILD_BENCH=OFF
cmake --build "$build" --target dlmfdd dlmfd-solve service_units_test daemon_test -j "${JOBS:-2}"
export TSAN_OPTIONS="${TSAN_OPTIONS:-halt_on_error=1 second_deadlock_stack=1}"
cd "$build"
ctest -L server --output-on-failure "$@"
