#!/usr/bin/env bash
# ThreadSanitizer run of the server tests (issue 5 point 7). Builds the daemon and the server tests
# with TSan in build-tsan and runs them (ctest -L server). The daemon's threads are what is checked;
# the solver is a separate process, so the tests run a dlmfd-solve built WITHOUT TSan (a TSan-built
# solver dies with SIGSEGV inside the uninstrumented libgomp): $DLMFD_SOLVER_BINARY when set, else
# build/engine/dlmfd-solve when present, else a Release one built here in build-tsan-solver. The tests
# pass that path to the daemon's --solver flag (tests/server/support/daemon_process.h).
# Reports inside uninstrumented third-party libraries are suppressed by scripts/tsan.supp (each line
# justified there); any report with a frame in our code is kept and fails the test (halt_on_error).
# Usage: scripts/tsan.sh [extra ctest arguments], e.g. scripts/tsan.sh -R daemon_test
set -euo pipefail
root="$(cd "$(dirname "$0")/.." && pwd)"
build="$root/build-tsan"
jobs="${JOBS:-2}"

solver="${DLMFD_SOLVER_BINARY:-}"
if [[ -z "$solver" && -x "$root/build/engine/dlmfd-solve" ]]; then
  solver="$root/build/engine/dlmfd-solve"
fi
if [[ -z "$solver" ]]; then
  cmake -S "$root" -B "$root/build-tsan-solver" -DCMAKE_BUILD_TYPE=Release -DDLMFD_BUILD_SERVICE=OFF \
    -DDLMFD_BUILD_TESTS=OFF -DDLMFD_BUILD_BENCH=OFF -DDLMFD_WERROR=ON
  cmake --build "$root/build-tsan-solver" --target dlmfd-solve -j "$jobs"
  solver="$root/build-tsan-solver/engine/dlmfd-solve"
fi
export DLMFD_SOLVER_BINARY="$solver"
echo "tsan.sh: solver (not instrumented) = $DLMFD_SOLVER_BINARY"

cmake -S "$root" -B "$build" -DDLMFD_TSAN=ON -DCMAKE_BUILD_TYPE=RelWithDebInfo -DDLMFD_BUILD_BENCH=OFF -DDLMFD_WERROR=ON
cmake --build "$build" --target dlmfdd service_units_test daemon_test -j "$jobs"
# The daemon inherits TSAN_OPTIONS from the test; its reports go to its log, which the daemon tests
# print on failure. exitcode=66 makes a daemon that reported a race exit with a status the tests see.
export TSAN_OPTIONS="${TSAN_OPTIONS:-halt_on_error=1 second_deadlock_stack=1 exitcode=66 suppressions=$root/scripts/tsan.supp}"
cd "$build"
ctest -L server --output-on-failure "$@"
