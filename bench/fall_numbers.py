#!/usr/bin/env python3
"""The numbers docs/evidence/validation_paper.md quotes for a falling-disk run of the paper's section 5, read from
its results directory (particles.h5 through the Python client's dlmfd.results, diagnostics.csv,
summary.json), so that a rerun under other settings is compared by the same definitions:

  - mean fall speed of the disks over [a, b]: the mean over disks of (y(a) - y(b)) / (b - a), at the
    recorded times nearest a and b;
  - for two disks, the gap between their surfaces at given times, and the first time it is within
    the collision range (diagnostics' particle_pair_gap below 1.5 h);
  - the first time the lowest disk's surface comes within --floor (default 0.05, a quarter of the
    paper's D = 0.2) of the floor y = 0;
  - closest approach between disks and to a wall, most contacts at once, max trA and the smallest
    eigenvalue of A over the run.

Usage: PYTHONPATH=build/python bench/fall_numbers.py RUN [--window a,b ...] [--gap-at t ...] [--h H]
       [--floor F]
"""
import argparse
import csv
import json
import math
import os
import sys

import numpy as np

try:
    from dlmfd.results import read_particles  # the Python client's reader of particles.h5
except ImportError as e:
    sys.exit(f"fall_numbers.py: {e}; run with PYTHONPATH=<build>/python (docs/python.md)")


def nearest(times, t):
    return int(np.argmin(np.abs(times - t)))


def main():
    ap = argparse.ArgumentParser(description=__doc__,
                                 formatter_class=argparse.RawDescriptionHelpFormatter)
    ap.add_argument("run")
    ap.add_argument("--window", action="append", default=[],
                    help="a,b: mean fall speed over [a, b]")
    ap.add_argument("--gap-at", action="append", type=float, default=[], help="gap of a pair at t")
    ap.add_argument("--h", type=float, default=1 / 96,
                    help="mesh size, for the collision range 1.5 h")
    ap.add_argument("--floor", type=float, default=0.05,
                    help="distance from the floor that counts as on it")
    args = ap.parse_args()

    particles = read_particles(args.run)
    t, y, r = particles.time, particles.position[:, :, 1], particles.radius
    summary = json.load(open(os.path.join(args.run, "summary.json")))
    print(f"{args.run}: {summary['status']} at t = {summary['time']:.4g} "
          f"({summary['steps']} steps, "
          f"{summary['wall_seconds']:.0f} s, {summary['ms_per_step']:.1f} ms/step)")
    for w in args.window:
        a, b = (float(x) for x in w.split(","))
        ia, ib = nearest(t, a), nearest(t, b)
        speed = float(np.mean(y[ia] - y[ib]) / (t[ib] - t[ia]))
        print(f"  mean fall speed over [{t[ia]:.4g}, {t[ib]:.4g}]: {speed:.3f}")
    if y.shape[1] == 2:
        for ta in args.gap_at:
            i = nearest(t, ta)
            gap = abs(y[i, 0] - y[i, 1]) - r[0] - r[1]  # centre-line pairs: the vertical distance
            print(f"  gap (vertical) at t = {t[i]:.4g}: {gap:.4f}")
    floor = np.where((y - r[None, :]).min(axis=1) < args.floor)[0]
    print(f"  lowest disk within {args.floor:g} of the floor: " +
          (f"t = {t[floor[0]]:.4g}" if floor.size else "never"))

    pair_gap, wall_gap, contacts, kiss = math.inf, math.inf, 0, None
    with open(os.path.join(args.run, "diagnostics.csv")) as f:
        for row in csv.DictReader(f):
            if row.get("particle_pair_gap"):
                g = float(row["particle_pair_gap"])
                pair_gap = min(pair_gap, g)
                if kiss is None and g < 1.5 * args.h:
                    kiss = float(row["time"])
            if row.get("particle_wall_gap"):
                wall_gap = min(wall_gap, float(row["particle_wall_gap"]))
            if row.get("collision_contacts"):
                contacts = max(contacts, int(float(row["collision_contacts"])))
    print(f"  closest approach between disks {pair_gap:.4g} ({pair_gap / args.h:.2f} h), to a wall "
          f"{wall_gap:.4g}; up to {contacts} contacts at once; first within 1.5 h: "
          + (f"t = {kiss:.4g}" if kiss is not None else "never"))
    if summary.get('max_trA') is not None:  # null in a Newtonian liquid (no polymer modelled)
        print(f"  max trA {summary['max_trA']:.4g}, "
              f"smallest eigenvalue of A {summary['min_eig_A']:.3g}")


if __name__ == "__main__":
    main()
