#!/usr/bin/env bash
# ThreadSanitizer run of the server tests (issue 5 point 7). Builds the daemon and the server tests
# with TSan in build-tsan and runs them (ctest -L server). The daemon's threads are what is checked;
# the solver is a separate process, so the tests run a dlmfd-solve built WITHOUT TSan (a TSan-built
# solver dies with SIGSEGV inside the uninstrumented libgomp): $DLMFD_SOLVER_BINARY when set, else
# build/engine/dlmfd-solve when present, else a Release one built here in build-tsan-solver.
# The tests pass that path to the daemon's --solver flag (tests/server/support/daemon_process.h).
# Debian's gRPC/abseil/protobuf are not instrumented: scripts/tsan_absl_sync.cc (preloaded) makes
# their absl::Mutex/CondVar hand-offs visible, and scripts/tsan.supp ignores the libc accesses those
# libraries make themselves (each line justified there). A report from the test process fails it
# (exit 66); a report the daemon writes to its log fails the test that ran it (daemon_process.cc).
# Results and the reasoning: docs/api.md, section "ThreadSanitizer".
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
  cmake -S "$root" -B "$root/build-tsan-solver" -DCMAKE_BUILD_TYPE=Release \
    -DDLMFD_BUILD_SERVICE=OFF \
    -DDLMFD_BUILD_TESTS=OFF -DDLMFD_BUILD_BENCH=OFF -DDLMFD_WERROR=ON
  cmake --build "$root/build-tsan-solver" --target dlmfd-solve -j "$jobs"
  solver="$root/build-tsan-solver/engine/dlmfd-solve"
fi
echo "tsan.sh: solver (not instrumented) = $solver"

cmake -S "$root" -B "$build" -DDLMFD_TSAN=ON -DCMAKE_BUILD_TYPE=RelWithDebInfo \
  -DDLMFD_BUILD_BENCH=OFF -DDLMFD_WERROR=ON
cmake --build "$build" --target dlmfdd service_units_test daemon_test -j "$jobs"

# absl::Mutex/CondVar of the uninstrumented gRPC made visible to TSan (scripts/tsan_absl_sync.cc).
absl_sync="$(ls /lib/*/libabsl_synchronization.so.* /usr/lib/*/libabsl_synchronization.so.* \
  2>/dev/null | head -n1 || true)"
absl_symbols="$( [[ -n "$absl_sync" ]] && nm -D "$absl_sync" 2>/dev/null || true)"
if [[ "$absl_symbols" != *_ZN4absl7debian35Mutex4LockEv* ]]; then
  echo "tsan.sh: warning: abseil's Mutex is not absl::debian3 here; the shim wraps nothing and" \
       "gRPC's hand-offs will be reported as races" >&2
fi
shim="$build/libtsan_absl_sync.so"
c++ -std=c++17 -O1 -g -fPIC -shared -fsanitize=thread -Wall -Wextra -Wpedantic -Werror \
  -o "$shim" "$root/scripts/tsan_absl_sync.cc" -ldl
# The solver is started by the daemon and inherits its environment: a wrapper drops the TSan
# preload and options before exec'ing the uninstrumented solver.
wrapper="$build/dlmfd-solve-without-tsan"
printf '#!/bin/sh\nunset LD_PRELOAD TSAN_OPTIONS\nexec "%s" "$@"\n' "$solver" > "$wrapper"
chmod +x "$wrapper"
export DLMFD_SOLVER_BINARY="$wrapper"
export LD_PRELOAD="$shim"

# The daemon inherits TSAN_OPTIONS from the test; its reports go to its log, which
# tests/server/support/daemon_process.cc searches after the daemon exits: a report fails the test.
default_options="second_deadlock_stack=1 history_size=7 suppressions=$root/scripts/tsan.supp"
export TSAN_OPTIONS="${TSAN_OPTIONS:-$default_options}"
cd "$build"
ctest -L server --output-on-failure "$@"
