#!/usr/bin/env python3
"""clang-tidy's checks (.clang-tidy: the function-size limit and the checks the code passes) on the
C++ files a change touches, or on every file (--all). CONTRIBUTING.md, "Code".

    scripts/tidy.py [--build DIR] [--since REV | --all]      (defaults: build, HEAD~1)

It reads DIR/compile_commands.json (the build exports it). A unity build compiles several sources
in one translation unit: each changed source is checked in the unit that includes it, and
clang-tidy reports only in the changed files (its header filter), so an unchanged neighbour in the
same unit is not held against the change. Exit status 1 when clang-tidy finds anything.
"""

import argparse
import concurrent.futures
import json
import os
import re
import subprocess
import sys

ROOT = os.path.dirname(os.path.dirname(os.path.abspath(__file__)))
SOURCES = (".cc", ".h", ".cpp", ".hpp")


def changed_files(since):
    out = subprocess.run(["git", "-C", ROOT, "diff", "--name-only", "--diff-filter=d", since, "--"],
                         check=True, capture_output=True, text=True).stdout
    return [os.path.join(ROOT, f) for f in out.split() if f.endswith(SOURCES)]


def units_including(entries):
    """Each translation unit of the compile database with the sources it compiles."""
    units = {}
    for e in entries:
        path = os.path.join(e["directory"], e["file"])
        sources = [path]
        if "/Unity/" in path:
            with open(path) as f:
                sources = re.findall(r'#include "([^"]+)"', f.read())
        units[path] = sources
    return units


def main():
    parser = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    parser.add_argument("--build", default=os.path.join(ROOT, "build"))
    which = parser.add_mutually_exclusive_group()
    which.add_argument("--since", default="HEAD~1")
    which.add_argument("--all", action="store_true")
    parser.add_argument("-j", type=int, default=os.cpu_count())
    args = parser.parse_args()

    database = os.path.join(args.build, "compile_commands.json")
    if not os.path.exists(database):
        sys.exit(f"tidy: {database} is missing (configure the build first)")
    with open(database) as f:
        units = units_including(json.load(f))
    # Generated code (protobuf) is not ours to tidy.
    units = {u: [s for s in srcs if s.startswith(ROOT) and not s.startswith(args.build)]
             for u, srcs in units.items()}

    if args.all:
        targets = sorted({s for srcs in units.values() for s in srcs})
    elif subprocess.run(["git", "-C", ROOT, "rev-parse", "--verify", "-q", args.since + "^{commit}"],
                        capture_output=True).returncode != 0:
        # A shallow clone has no parent to compare with: every file is checked.
        print(f"tidy: {args.since} is not in this clone's history: checking every file")
        targets = sorted({s for srcs in units.values() for s in srcs})
    else:
        targets = changed_files(args.since)
    if not targets:
        print("tidy: no C++ file to check")
        return 0
    # A changed source is checked in the unit that compiles it; a changed header in the units of
    # the sources with its name (include/dlmfd/particles/shape.h through src/particles/shape.cc),
    # else in the units of the sources beside it.
    def stem(path):
        return os.path.splitext(os.path.basename(path))[0]

    stems = {stem(t) for t in targets}
    dirs = {os.path.dirname(t) for t in targets if t.endswith((".h", ".hpp"))}
    chosen = [u for u, srcs in units.items()
              if any(stem(s) in stems or os.path.dirname(s) in dirs for s in srcs)]
    header_filter = "^(" + "|".join(re.escape(t) for t in targets) + ")$"
    print(f"tidy: {len(targets)} files through {len(chosen)} translation units")

    def tidy(unit):
        return subprocess.run(
            ["clang-tidy", "-p", args.build, "--quiet", "--extra-arg=-Wno-unknown-warning-option",
             f"--header-filter={header_filter}", unit],
            capture_output=True, text=True)

    failed = False
    with concurrent.futures.ThreadPoolExecutor(max_workers=args.j) as pool:
        for result in pool.map(tidy, chosen):
            out = result.stdout + result.stderr
            findings = [line for line in out.splitlines()
                        if re.search(r"(warning|error):", line) and line.startswith(tuple(targets))]
            # A unit that does not compile under clang is a finding too, wherever the error is.
            if findings or (result.returncode != 0 and "error:" in out):
                failed = True
                print(out.strip())
    print("tidy: " + ("findings above" if failed else "clean"))
    return 1 if failed else 0


if __name__ == "__main__":
    sys.exit(main())
