#!/usr/bin/env bash
# The commit-message rule (scripts/commit_message.sh, CONTRIBUTING.md) on messages that follow it
# and on each way to break it: the hook accepts the first and refuses the others, naming the fault.
set -uo pipefail
check="$(dirname "$0")/../../scripts/commit_message.sh"
dir=$(mktemp -d)
trap 'rm -rf "$dir"' EXIT
failures=0
expect() {  # expect STATUS FAULT_TEXT MESSAGE
  printf '%b' "$3" > "$dir/msg"
  out=$("$check" "$dir/msg" 2>&1)
  status=$?
  if [ "$status" != "$1" ] || ! grep -q -- "$2" <<< "$out"; then
    echo "FAIL: message $(printf '%q' "$3"): status $status (expected $1), output: $out"
    failures=$((failures + 1))
  fi
}
subject72=$(printf 'a%.0s' $(seq 72))
subject73=$(printf 'a%.0s' $(seq 73))
expect 0 "" "Stokes solve: u and v side by side\n\nms/step 12.8 -> 9.1 (bench/x.sh)\n"
expect 0 "" "$subject72\n"
expect 0 "" "$subject72\n\n# a comment line git strips: $subject73$subject73\n"
expect 1 "73 characters" "$subject73\n\nbody\n"
expect 1 "blank" "A subject\nthe body on the second line\n"
expect 1 "empty" "\n\nbody only\n"
expect 1 "empty" ""
out=$("$check" 2>&1); [ $? = 2 ] && grep -q usage <<< "$out" || { echo "FAIL: no argument is not a usage error"; failures=$((failures + 1)); }
rm -f "$dir/msg"
out=$("$check" "$dir/msg" 2>&1); [ $? = 2 ] || { echo "FAIL: a missing file is not a usage error"; failures=$((failures + 1)); }
if [ "$failures" != 0 ]; then exit 1; fi
echo "commit message rule: 9 cases as expected"
