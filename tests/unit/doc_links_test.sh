#!/usr/bin/env bash
# The docs link checker (scripts/check_doc_links.py, CONTRIBUTING.md) on a small checkout: silent
# and 0 on citations that resolve, 1 naming each broken one, of every kind it checks.
set -uo pipefail
check="$(cd "$(dirname "$0")/../.." && pwd)/scripts/check_doc_links.py"
dir=$(mktemp -d)
trap 'rm -rf "$dir"' EXIT
failures=0
fail() { echo "FAIL: $*"; failures=$((failures + 1)); }
mkdir -p "$dir/docs/evidence" "$dir/src"
cat > "$dir/docs/design.md" << 'MD'
# Design
## 1. What it is
### 1.1 Scenes
MD
cat > "$dir/docs/evidence/drag.md" << 'MD'
# Drag
## The drag at the defaults: within 1 %
**The dt ladder** runs four steps.
MD
mkdir -p "$dir/docs/method"
cat > "$dir/docs/method/fluid.md" << 'MD'
# Method notes 1
## 1. Operators
MD
cat > "$dir/docs/README.md" << 'MD'
# Map
[drag](evidence/drag.md#the-drag-at-the-defaults-within-1-) and [design](design.md).
MD
cat > "$dir/src/a.h" << 'MD'
// design.md 1.1; method notes 1, section 1; docs/evidence/drag.md, "The drag at the defaults";
// docs/evidence/drag.md, "The dt
// ladder"; docs/evidence/ holds the evidence.
MD
git -C "$dir" init -q && git -C "$dir" add -A
out=$("$check" --root "$dir" 2>&1)
[ $? = 0 ] || fail "a clean checkout: $out"
cat > "$dir/src/b.h" << 'MD'
// docs/evidence/lift.md; docs/evidence/drag.md#nowhere; docs/evidence/drag.md, "The lift";
// design.md 7; drag.md, "The lift"; nowhere.md; ../shared/reference/peers.md
// docs/work_precision.md; method notes 1, section 7
MD
cat > "$dir/docs/broken.md" << 'MD'
[a](evidence/none.md) [b](#none) [c](evidence/drag.md#none)
MD
git -C "$dir" add -A
out=$("$check" --root "$dir" 2>&1)
[ $? = 1 ] || fail "a broken checkout passed: $out"
for fault in "src/b.h:1: cites docs/evidence/lift.md: docs/evidence/lift.md does not exist" \
  "src/b.h:1: cites docs/evidence/drag.md#nowhere: docs/evidence/drag.md has no heading #nowhere" \
  'src/b.h:1: cites docs/evidence/drag.md, "The lift": no heading' \
  "src/b.h:2: cites design.md 7, not a section" 'src/b.h:2: cites docs/evidence/drag.md, "The lift"' \
  "src/b.h:2: names nowhere.md, which is no tracked file" "src/b.h:2: cites ../shared/reference/peers.md" \
  "src/b.h:3: cites docs/work_precision.md: docs/work_precision.md does not exist (moved: docs/evidence/" \
  "src/b.h:3: cites method notes 1, section 7, not a section of docs/method/fluid.md" \
  "docs/broken.md:1: link evidence/none.md: docs/evidence/none.md does not exist" \
  "docs/broken.md:1: link #none: docs/broken.md has no heading #none" \
  "docs/broken.md:1: link evidence/drag.md#none: docs/evidence/drag.md has no heading #none"; do
  grep -qF -- "$fault" <<< "$out" || fail "not reported: $fault (output: $out)"
done
out=$("$check" --root 2>&1); [ $? = 2 ] || fail "a bad argument is not a usage error"
if [ "$failures" != 0 ]; then exit 1; fi
