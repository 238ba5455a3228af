#!/usr/bin/env bash
# The layout rule (CONTRIBUTING.md): every tracked C++ file is as clang-format (.clang-format)
# writes it. Prints the files that differ and how to fix them; exit status 1 when any does.
# Run from anywhere: scripts/check_format.sh
set -euo pipefail
cd "$(dirname "$0")/.."
if ! git rev-parse --git-dir > /dev/null 2>&1; then
  echo "check_format: not a git checkout (the tracked files are unknown)" >&2
  exit 77
fi
mapfile -t files < <(git ls-files '*.cc' '*.h' '*.cpp' '*.hpp')
# clang-format names each file that differs in its warnings ("FILE:LINE:COL: error: ...").
mapfile -t differing < <(printf '%s\0' "${files[@]}" |
  xargs -0 -P "$(nproc)" -n 25 clang-format --dry-run -Werror 2>&1 |
  sed -n 's/^\([^:]*\):[0-9]*:[0-9]*: error: .*/\1/p' | sort -u)
if [ ${#differing[@]} -gt 0 ]; then
  echo "check_format: ${#differing[@]} of ${#files[@]} files differ from clang-format's layout:" >&2
  printf '  %s\n' "${differing[@]}" >&2
  echo "fix with: clang-format -i ${differing[*]}" >&2
  exit 1
fi
echo "check_format: ${#files[@]} files as clang-format writes them"
