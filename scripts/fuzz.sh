#!/usr/bin/env bash
# The libFuzzer targets of tests/fuzz (issue 38 point 1), built with clang (the fuzzer's coverage +
# ASan + UBSan) and run side by side, each for a bounded time: the scene parser
# (scene_text_fuzz, seeded with the scenes of cases/) and every rpc of dlmfd.v1.Jobs against the
# real daemon in the process
# (rpc_request_fuzz, seeded with one readable request per rpc). A crash, a sanitizer report, an
# answer jobs.proto does not promise, or a stuck input (-timeout) fails the run; libFuzzer leaves
# the input that did it as TREE/fuzz-artifacts/crash-* (reproduce: TARGET FILE).
# Usage: scripts/fuzz.sh [seconds per target, default 30]
#        scripts/fuzz.sh --build-only     (builds the targets and stops)
# The tree: build-fuzz, configured here at -O1 (the fuzzers' usual optimisation); or
# $DLMFD_FUZZ_BUILD, a tree configured already with DLMFD_FUZZ, used as it is (CI's sanitizer
# tree build-asan: clang, DLMFD_SANITIZE and DLMFD_FUZZ; scripts/test.sh).
# The rpc target runs the daemon's jobs with $DLMFD_SOLVER_BINARY, else build/solver/dlmfd-solve
# (the release build's), else a Release one built in build-fuzz-solver.
set -euo pipefail
root="$(cd "$(dirname "$0")/.." && pwd)"
seconds="${1:-30}"
build_only=0
if [[ "$seconds" == --build-only ]]; then build_only=1; fi
build="${DLMFD_FUZZ_BUILD:-$root/build-fuzz}"
jobs="${JOBS:-$(nproc)}"

solver="${DLMFD_SOLVER_BINARY:-}"
if [[ -z "$solver" && -x "$root/build/solver/dlmfd-solve" ]]; then
  solver="$root/build/solver/dlmfd-solve"
fi
if [[ -z "$solver" && "$build_only" == 0 ]]; then
  cmake -S "$root" -B "$root/build-fuzz-solver" -DCMAKE_BUILD_TYPE=Release \
    -DDLMFD_BUILD_SERVICE=OFF -DDLMFD_BUILD_TESTS=OFF -DDLMFD_BUILD_BENCH=OFF > /dev/null
  cmake --build "$root/build-fuzz-solver" --target dlmfd-solve -j "$jobs"
  solver="$root/build-fuzz-solver/solver/dlmfd-solve"
fi

# -O1 -g1: the fuzzers' usual optimisation, with line numbers in the reports.
if [[ -z "${DLMFD_FUZZ_BUILD:-}" ]]; then
  cmake -S "$root" -B "$build" -DCMAKE_C_COMPILER=clang -DCMAKE_CXX_COMPILER=clang++ \
    -DCMAKE_BUILD_TYPE=RelWithDebInfo "-DCMAKE_CXX_FLAGS_RELWITHDEBINFO=-O1 -g1 -DNDEBUG" \
    -DDLMFD_SANITIZE=ON -DDLMFD_FUZZ=ON -DDLMFD_BUILD_TESTS=OFF -DDLMFD_BUILD_BENCH=OFF > /dev/null
elif ! grep -qs '^DLMFD_FUZZ:BOOL=ON$' "$build/CMakeCache.txt"; then
  echo "fuzz.sh: DLMFD_FUZZ_BUILD=$build is not a tree configured with -DDLMFD_FUZZ=ON" >&2
  exit 2
fi
cmake --build "$build" -j "$jobs" --target scene_text_fuzz rpc_request_fuzz
if [[ "$build_only" == 1 ]]; then exit 0; fi

# Seeds: every scene of cases/; one request per rpc (its first byte picks the rpc, in the order of
# jobs.proto's service), built with the Python stubs' wire format by hand: field 1 as a string.
seeds="$build/fuzz-seeds"
rm -rf "$seeds" && mkdir -p "$seeds/scene" "$seeds/rpc" "$build/fuzz-artifacts"
find "$root/cases" -name '*.toml' -exec cp {} "$seeds/scene/" \;
python3 - "$seeds/rpc" "$root/cases/lid_driven_cavity.toml" "$root/proto/dlmfd/v1/jobs.proto" <<'EOF'
import pathlib, re, sys
out, scene_path = pathlib.Path(sys.argv[1]), pathlib.Path(sys.argv[2])
# One seed pair per rpc of the service, as many as jobs.proto declares.
rpcs = len(re.findall(r"^\s*rpc \w+\(", pathlib.Path(sys.argv[3]).read_text(), re.M))
# The cavity, shortened to 5 steps (the daemon here allows 20).
scene = scene_path.read_bytes().replace(b"end = 15.0", b"end = 0.05")
def varint(n):
    b = bytearray()
    while True:
        byte, n = n & 0x7F, n >> 7
        b.append(byte | (0x80 if n else 0))
        if not n:
            return bytes(b)
def text(field, value):
    return varint(field << 3 | 2) + varint(len(value)) + value
for rpc in range(rpcs):
    (out / f"rpc-{rpc}-empty").write_bytes(bytes([rpc]))
    (out / f"rpc-{rpc}-id").write_bytes(bytes([rpc]) + text(1, b"j-0000000000000001"))
(out / "submit-scene").write_bytes(bytes([0]) + text(1, scene))
EOF

# Each target in its own corpus directory (new inputs land there), seeds read alongside. The two
# targets run side by side, one core each (CI has two): the step takes one run's time, not two.
export ASAN_OPTIONS="abort_on_error=1:detect_leaks=0" UBSAN_OPTIONS="print_stacktrace=1:halt_on_error=1"
export DLMFD_SOLVER_BINARY="$solver"
targets=(scene_text_fuzz rpc_request_fuzz)
declare -A pids
for target in "${targets[@]}"; do
  corpus="$build/fuzz-corpus/$target"
  mkdir -p "$corpus"
  seed_dir="$seeds/scene"
  [[ "$target" == rpc_request_fuzz ]] && seed_dir="$seeds/rpc"
  echo "== $target for $seconds s"
  "$build/tests/fuzz/$target" -max_total_time="$seconds" -timeout=60 -rss_limit_mb=4096 \
    -max_len=65536 -print_final_stats=1 -artifact_prefix="$build/fuzz-artifacts/$target-" \
    "$corpus" "$seed_dir" > "$build/$target.log" 2>&1 &
  pids[$target]=$!
done
status=0
for target in "${targets[@]}"; do
  if ! wait "${pids[$target]}"; then
    status=1
    echo "fuzz.sh: $target found a failure:" >&2
    tail -n 60 "$build/$target.log" >&2
  else
    echo "== $target"
    grep -E '^stat::(number_of_executed_units|new_units_added|peak_rss_mb)' "$build/$target.log" || true
  fi
done
exit "$status"
