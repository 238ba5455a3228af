#!/usr/bin/env python3
"""Every case file at the defaults (issue 32 point 3): each file of cases/ with its numerics keys
removed (numerics.preset, particle_mesh.kind, domain.diagonals, splitting.advection,
splitting.constraint, splitting.steady_correction, fluid.stress_splitting) runs through
dlmfd-solve; prints one markdown row per case: steps run against steps planned, the status and
its reason, ms a step, and what `auto` resolved.

  bench/cases_at_defaults.py --solve build/solver/dlmfd-solve              # every case, to its end
  bench/cases_at_defaults.py --fraction 0.1 cases/paper/5.2_pair_oldroyd_b.toml  # its first tenth
  bench/cases_at_defaults.py --steps 3        # each case's first 3 steps (the CI test CaseFiles)

The physical keys stay as the case file writes them; results go under --out (one folder per case).
A shortened run (--steps, --fraction) runs with what each "auto" becomes over the whole run
(dlmfd-solve --check), named: particle_mesh.kind = "auto" reads the run's length.
"""
import argparse
import glob
import json
import os
import pathlib
import re
import subprocess
import sys
import time
import tomllib

NUMERICS_KEYS = {
    "numerics": {"preset"},
    "particle_mesh": {"kind"},
    "domain": {"diagonals"},
    "splitting": {"advection", "constraint", "steady_correction"},
    "fluid": {"stress_splitting"},
}


def strip_numerics(text):
    """The scene text without its numerics keys (line-based: the case files write one key a line)."""
    table, kept, dropped = "", [], []
    for line in text.splitlines():
        header = re.match(r"\s*\[\s*([A-Za-z_.]+)\s*\]\s*(#.*)?$", line)
        if header:
            table = header.group(1)
        key = re.match(r"\s*([A-Za-z_]+)\s*=", line)
        if key and key.group(1) in NUMERICS_KEYS.get(table, ()):
            dropped.append(f"{table}.{key.group(1)}")
            continue
        kept.append(line)
    return "\n".join(kept) + "\n", dropped


def resolved_at_full_length(solve, scene, sets):
    """What each "auto" of the scene becomes over the run as written (dlmfd-solve --check): a
    shortened run must not resolve otherwise (particle_mesh.kind reads the run's length)."""
    command = [solve, str(scene), "--check"]
    for assignment in sets:
        command += ["--set", assignment]
    check = subprocess.run(command, capture_output=True, text=True)
    return re.findall(r'^numerics: ([a-z_.]+) = "([a-z_]+)"', check.stdout, re.M)


def run_case(solve, case, out, fraction, steps, threads, sets):
    text, dropped = strip_numerics(case.read_text())
    scene = tomllib.loads(text)
    end, dt = scene["time"]["end"], scene["time"]["dt"]
    planned = steps if steps else round(end * fraction / dt)
    folder = out / case.with_suffix("").as_posix().replace("/", "_")
    folder.mkdir(parents=True, exist_ok=True)
    (folder / "scene_at_defaults.toml").write_text(text)
    command = [solve, str(folder / "scene_at_defaults.toml"), "--out", str(folder / "results"),
               "--quiet", "--threads", str(threads)]
    for assignment in sets:
        command += ["--set", assignment]
    named = []
    if planned != round(end / dt):
        named = resolved_at_full_length(solve, folder / "scene_at_defaults.toml", sets)
        for key, value in named:
            command += ["--set", f'{key}="{value}"']
        command += ["--set", f"time.end={planned * dt!r}"]
    start = time.time()
    proc = subprocess.run(command, capture_output=True, text=True)
    wall = time.time() - start
    summary_path = folder / "results" / "summary.json"
    summary = json.loads(summary_path.read_text()) if summary_path.exists() else {}
    reason = summary.get("reason") or proc.stderr.strip().splitlines()[-1:] or [""]
    reason = reason if isinstance(reason, str) else reason[0]
    resolved = "; ".join(f"{n['key']} = {n['value']}" for n in summary.get("numerics", []))
    resolved = resolved or "; ".join(f"{key} = {value}" for key, value in named)
    return {
        "case": case.as_posix(), "dropped": dropped, "steps": summary.get("steps", 0),
        "planned": planned, "status": summary.get("status", f"exit {proc.returncode}"),
        "reason": reason, "ms": summary.get("ms_per_step"), "wall": wall, "resolved": resolved,
        "rc": proc.returncode,
    }


def main():
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("cases", nargs="*", help="case files (default: every file under cases/)")
    parser.add_argument("--solve", default="build/solver/dlmfd-solve")
    parser.add_argument("--out", default="/tmp/dlmfd-cases-at-defaults")
    parser.add_argument("--fraction", type=float, default=1.0, help="run this fraction of time.end")
    parser.add_argument("--steps", type=int, default=0, help="run only this many steps of each")
    parser.add_argument("--threads", type=int, default=1)
    parser.add_argument("--set", action="append", default=[], metavar="KEY=VALUE",
                        help="a key set on every case (as dlmfd-solve --set), e.g. to compare a scheme")
    args = parser.parse_args()
    cases = [pathlib.Path(c) for c in (args.cases or sorted(glob.glob("cases/**/*.toml", recursive=True)))]
    out = pathlib.Path(args.out)
    print("| case | numerics keys removed | steps / planned | status | ms a step | auto resolved |")
    print("|---|---|---|---|---|---|")
    failed = 0
    for case in cases:
        r = run_case(args.solve, case, out, args.fraction, args.steps, args.threads, args.set)
        ok = r["rc"] == 0 and r["status"] == "completed" and r["steps"] == r["planned"]
        failed += not ok
        status = r["status"] + ("" if ok else f": {r['reason']}")
        ms = f"{r['ms']:.1f}" if r["ms"] else "-"
        print(f"| {r['case']} | {', '.join(r['dropped']) or '-'} | {r['steps']} / {r['planned']} | "
              f"{status} | {ms} | {r['resolved'] or '-'} |", flush=True)
    span = f"the first {args.steps} steps" if args.steps else f"fraction {args.fraction}"
    print(f"\n{len(cases) - failed} of {len(cases)} cases ran at the defaults "
          f"({span} of each run, {args.threads} thread(s)).")
    return 1 if failed else 0


if __name__ == "__main__":
    sys.exit(main())
