#!/usr/bin/env bash
# Sets everything up, builds, and runs the whole test suite in the release build (warnings are
# errors), then the daemon's and the CLI's tests (labels server and e2e) in an ASan+UBSan build
# with clang, the same tree that builds the fuzz targets. This is the README's test command and what
# CI runs. SANITIZE_ALL=1 runs every label under the sanitizers (a longer run, for changes deep in
# the engine). Last, the fuzz targets run for DLMFD_FUZZ_SECONDS (20) each (scripts/fuzz.sh).
#
# The tests mostly wait (daemons, Slurm, browsers: the release tests took 248 s of CPU in 342 s on
# both cores): the ASan+UBSan build runs at nice 10 beside the Slurm tests, clang-tidy and the
# release tests, on the cores they leave idle (docs/evidence/service.md, "CI's time"). Each phase
# prints its wall and CPU time.
set -euo pipefail
cd "$(dirname "$0")/.."
timed() {  # timed NAME COMMAND...: runs it, then prints its wall time and CPU time (user + sys)
  local TIMEFORMAT="== $1: %0R s wall, %0U s user + %0S s sys"
  shift
  time "$@"
}
timed setup scripts/setup.sh
jobs=$(nproc)
# ctest runs the tests side by side on every core: one OpenMP thread each, and no spin-waiting.
export OMP_NUM_THREADS=1 OMP_WAIT_POLICY=passive

# Background steps (their pids): stopped when the script ends early.
background=()
slurm_started=0
# On a failure the controller's and the node's last lines go to the log before Slurm stops.
trap 'status=$?
  for pid in "${background[@]}"; do
    pkill -TERM -P "$pid" 2> /dev/null || true
    kill "$pid" 2> /dev/null || true
  done
  if [ "$status" != 0 ] && [ "$(id -u)" -eq 0 ]; then scripts/slurm-dev.sh logs || true; fi
  if [ "$slurm_started" = 1 ]; then scripts/slurm-dev.sh stop; fi' EXIT

# The tests labelled slurm run against a real single-node Slurm (scripts/slurm-dev.sh, as root):
# started here when it is not running, and then stopped on exit; without root they skip.
if [ "$(id -u)" -eq 0 ]; then
  if ! scripts/slurm-dev.sh status > /dev/null 2>&1; then
    scripts/slurm-dev.sh start
    slurm_started=1
  fi
  eval "$(scripts/slurm-dev.sh env)"
fi

# Runs a step in the background, its output and times kept in LOG: bg_start VAR LOG COMMAND...
# sets VAR to its pid. bg_end PID LOG NAME waits for it, prints the log and fails as it failed.
bg_start() {
  local var=$1 log=$2
  shift 2
  ( timed "$(basename "$log" .log)" "$@" ) > "$log" 2>&1 &
  printf -v "$var" '%s' "$!"
  background+=("$!")
}
bg_end() {
  local status=0
  wait "$1" || status=$?
  echo "== $3 (exit status $status; its output follows)"
  cat "$2"
  return "$status"
}

echo "== release build"
cmake -S . -B build -DCMAKE_BUILD_TYPE=Release -DDLMFD_WERROR=ON > /dev/null
timed "release build" cmake --build build -j"$jobs"

# The tests labelled slurm run one at a time (a resource lock) and mostly wait on Slurm's
# scheduling (about 5 minutes): they run from here on beside the other steps.
echo "== release tests labelled slurm, in the background (output follows the ASan+UBSan build)"
bg_start slurm_tests_pid build/slurm-tests.log ctest --test-dir build --output-on-failure \
  --timeout 900 -L slurm

# The ASan+UBSan tree, built at nice 10 from here on: the steps until its tests take precedence.
# It is clang's, and builds the libFuzzer targets (issue 38) too: DLMFD_FUZZ adds the fuzzer's
# coverage to the libraries they link (the scene files, the daemon's library, the protocol), which
# the sanitizer tests run as they are: one build instead of gcc's sanitizer tree and a fuzz tree
# of its own (docs/evidence/service.md, "One clang tree for the sanitizers and the fuzzers").
# -g1: line tables, so reports keep file and line. -O0 for the code that only waits on clients,
# gRPC and files (the CLI, the dashboard, the tests), -O1 for the computing targets
# (DLMFD_NUMERICS_FLAGS: the engine and dlmfd-solve, which the e2e tests run over the paper's
# cases) and for the fuzzed libraries (tests/fuzz/CMakeLists.txt).
cmake -S . -B build-asan -DCMAKE_C_COMPILER=clang -DCMAKE_CXX_COMPILER=clang++ \
  -DCMAKE_BUILD_TYPE=RelWithDebInfo "-DCMAKE_CXX_FLAGS_RELWITHDEBINFO=-O0 -g1 -DNDEBUG" \
  -DDLMFD_NUMERICS_FLAGS=-O1 -DDLMFD_SANITIZE=ON -DDLMFD_FUZZ=ON -DDLMFD_WERROR=ON \
  -DDLMFD_BUILD_BENCH=OFF > /dev/null
# The sanitizers guard the code that meets clients and jobs: the daemon, the CLI, the dashboard
# (dlmfd-web) and the solver they run (the e2e tests run every paper case's scene through the
# instrumented dlmfd-solve). The engine's unit and convergence tests run in the release build
# only: under ASan they doubled the sanitizer pass (build 17 minutes, tests 7, on 2 cores), which
# kept CI above its 30 minutes. The tests labelled slurm run once, in the release build: they wait
# on Slurm's scheduling (minutes), and the daemon's code they drive runs under the sanitizers in
# the server tests.
if [ "${SANITIZE_ALL:-0}" = 1 ]; then
  asan_targets=()
  asan_labels=(-LE slurm)
else
  # service_checks (CMakeLists.txt): dlmfdd, dlmfd, dlmfd-solve, dlmfd-web, server_tests,
  # e2e_tests and the fuzz targets, as one goal so that make builds them side by side.
  asan_targets=(--target service_checks)
  # The dashboard meets browsers: it is built under the sanitizers (123 s of CPU, 2026-12-04) and
  # its HTTP rules run there (7 s); the Chromium test, which drives the same code through a
  # browser for 37 s more and passes there too, runs in release only (docs/dashboard.md).
  asan_labels=(-L '^(server|e2e|browser)$' -E '^Dashboard\.InHeadlessChromium$')
fi
echo "== ASan+UBSan build, at nice 10 beside the next steps (output follows them)"
bg_start asan_build_pid build/asan-build.log nice -n 10 cmake --build build-asan -j"$jobs" "${asan_targets[@]}"

echo "== clang-tidy (.clang-tidy) on the C++ files the last commit changed (CONTRIBUTING.md)"
timed tidy scripts/tidy.py --build build --since HEAD~1 -j "$jobs"
echo "== release tests"
timed "release tests" ctest --test-dir build --output-on-failure -j"$jobs" --timeout 900 -LE slurm

bg_end "$asan_build_pid" build/asan-build.log "ASan+UBSan build"
bg_end "$slurm_tests_pid" build/slurm-tests.log "release tests labelled slurm"

echo "== ASan+UBSan tests"
ASAN_OPTIONS=detect_leaks=1:abort_on_error=1 UBSAN_OPTIONS=print_stacktrace=1:halt_on_error=1 \
  LSAN_OPTIONS=suppressions="$PWD/scripts/lsan.supp":print_suppressions=0 \
  timed "ASan+UBSan tests" ctest --test-dir build-asan --output-on-failure -j"$jobs" \
  --timeout 1800 "${asan_labels[@]}"

echo "== libFuzzer targets, ${DLMFD_FUZZ_SECONDS:-20} s each"
# The scene parser and every rpc's request body, from the sanitizer tree; the daemon's jobs run the
# release solver.
DLMFD_FUZZ_BUILD="$PWD/build-asan" DLMFD_SOLVER_BINARY="$PWD/build/solver/dlmfd-solve" \
  timed fuzz scripts/fuzz.sh "${DLMFD_FUZZ_SECONDS:-20}"
echo "== CI: ${SECONDS} s wall"
times
