#!/usr/bin/env bash
# ThreadSanitizer run of the server tests (issue 5 point 7). Builds the daemon and the server tests
# with -fsanitize=thread in build-tsan and runs them (ctest -L server). The daemon's threads are
# what is checked; the solver is a separate process, so the tests run a dlmfd-solve built WITHOUT
# TSan (a TSan-built solver dies with SIGSEGV inside the uninstrumented libgomp):
# $DLMFD_SOLVER_BINARY when set, else build/solver/dlmfd-solve when present, else a Release one
# built here in build-tsan-solver.
# The tests pass that path to the daemon's --solver flag (tests/server/support/daemon_process.h).
# Debian's gRPC/abseil/protobuf are not instrumented. scripts/tsan_absl_sync.cc (preloaded) tells
# TSan about the hand-offs those libraries make where it cannot see them (absl::Mutex/CondVar,
# gRPC's batch start -> completion, the last reference of a callback call -> OnDone/OnCancel);
# scripts/tsan.supp ignores the libc accesses those libraries make themselves (justified there).
# Before the tests, scripts/tsan_canary.cc (a Watch reactor with a deliberate race in OnWriteDone,
# same compiler, flags, preload and options) must give exactly that one report, or the script fails.
# A report from the test process fails it (exit 66); a report the daemon writes to its log fails the
# test that ran it (daemon_process.cc). Results and the reasoning: docs/evidence/service.md, "ThreadSanitizer".
# Usage: scripts/tsan.sh [extra ctest arguments], e.g. scripts/tsan.sh -R Daemon
set -euo pipefail
root="$(cd "$(dirname "$0")/.." && pwd)"
build="$root/build-tsan"
supp="$root/scripts/tsan.supp"
jobs="${JOBS:-2}"

solver="${DLMFD_SOLVER_BINARY:-}"
if [[ -z "$solver" && -x "$root/build/solver/dlmfd-solve" ]]; then
  solver="$root/build/solver/dlmfd-solve"
fi
if [[ -z "$solver" ]]; then
  cmake -S "$root" -B "$root/build-tsan-solver" -DCMAKE_BUILD_TYPE=Release \
    -DDLMFD_BUILD_SERVICE=OFF \
    -DDLMFD_BUILD_TESTS=OFF -DDLMFD_BUILD_BENCH=OFF -DDLMFD_WERROR=ON
  cmake --build "$root/build-tsan-solver" --target dlmfd-solve -j "$jobs"
  solver="$root/build-tsan-solver/solver/dlmfd-solve"
fi
echo "tsan.sh: solver (not instrumented) = $solver"

cmake -S "$root" -B "$build" -DDLMFD_TSAN=ON -DCMAKE_BUILD_TYPE=RelWithDebInfo \
  -DDLMFD_BUILD_BENCH=OFF -DDLMFD_WERROR=ON
cmake --build "$build" --target dlmfdd server_tests -j "$jobs"

# absl::Mutex/CondVar of the uninstrumented gRPC made visible to TSan (scripts/tsan_absl_sync.cc).
absl_sync="$(ls /lib/*/libabsl_synchronization.so.* /usr/lib/*/libabsl_synchronization.so.* \
  2>/dev/null | head -n1 || true)"
absl_symbols="$( [[ -n "$absl_sync" ]] && nm -D "$absl_sync" 2>/dev/null || true)"
if [[ "$absl_symbols" != *_ZN4absl7debian35Mutex4LockEv* ]]; then
  echo "tsan.sh: warning: abseil's Mutex is not absl::debian3 here; the shim wraps nothing and" \
       "gRPC's hand-offs will be reported as races" >&2
fi
shim="$build/libtsan_absl_sync.so"
# Not instrumented itself: it calls the TSan runtime of the instrumented process through weak
# symbols, so the uninstrumented /bin/sh of the solver wrapper below can load it too.
c++ -std=c++17 -O1 -g -fPIC -shared -Wall -Wextra -Wpedantic -Werror \
  -o "$shim" "$root/scripts/tsan_absl_sync.cc" -ldl
# The canary (run below, before the tests): the same compiler and flags as the daemon
# (cmake/Sanitizers.cmake: headers read as in the uninstrumented libraries' build).
canary="$build/tsan_canary"
c++ -std=c++17 -O2 -g -fno-omit-frame-pointer -fsanitize=thread -U__SANITIZE_THREAD__ -D_GLIBCXX_TSAN=1 \
  -Wall -Wextra -Wpedantic -Werror -I"$build/proto/gen" \
  -o "$canary" "$root/scripts/tsan_canary.cc" "$build/proto/libdlmfd_api_proto.a" \
  "$build/proto/libdlmfd_events_proto.a" $(pkg-config --libs grpc++ protobuf)
# The solver is started by the daemon and inherits its environment: a wrapper drops the TSan
# preload and options before exec'ing the uninstrumented solver.
wrapper="$build/dlmfd-solve-without-tsan"
printf '#!/bin/sh\nunset LD_PRELOAD TSAN_OPTIONS\nexec "%s" "$@"\n' "$solver" > "$wrapper"
chmod +x "$wrapper"
export DLMFD_SOLVER_BINARY="$wrapper"
export LD_PRELOAD="$shim"

# The daemon inherits TSAN_OPTIONS from the test; its reports go to its log, which
# tests/server/support/daemon_process.cc searches after the daemon exits: a report fails the test.
default_options="second_deadlock_stack=1 history_size=7 suppressions=$supp"
export TSAN_OPTIONS="${TSAN_OPTIONS:-$default_options}"

# The canary: this setup must still report a race in our reactor code that gRPC calls.
canary_status=0
"$canary" > "$build/tsan_canary.log" 2>&1 || canary_status=$?
canary_reports="$(grep -c 'WARNING: ThreadSanitizer' "$build/tsan_canary.log" || true)"
if [[ "$canary_status" != 66 || "$canary_reports" != 1 ]] ||
   ! grep -Eq 'OnWriteDone.*tsan_canary\.cc' "$build/tsan_canary.log"; then
  echo "tsan.sh: the canary's deliberate race was not reported exactly once (exit $canary_status," \
       "$canary_reports reports; see $build/tsan_canary.log): this setup would hide races" >&2
  exit 1
fi
echo "tsan.sh: canary ok (its deliberate race in CanaryReactor::OnWriteDone was reported)"
cd "$build"
ctest -L server --output-on-failure "$@"
