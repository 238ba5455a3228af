#!/usr/bin/python3
"""The ripple of a settling particle's fall speed as it crosses the grid (issue 33 point 2;
docs/evidence/cut_cell_boundary.md, "The polymer around a free body", "Over dt, and where the
disk sits on the grid").

    bench/fall_speed_ripple.py RESULTS_DIR... [--from 0.5] [--to 1.0]

For each results directory (particles.h5 written often: a few records a cell crossed), over the
records with FROM < t <= TO: the mean fall speed -v of particle 0, and its ripple relative to that
mean once a quadratic trend in t is removed: peak to peak, RMS, and the part periodic in the
centre's place in a pressure cell (y mod 2h: the P1-iso-P2 pattern repeats every 2h), the peak to
peak of the residual's means over 20 bins of that place. The cells crossed say how well the bins
are filled.
"""
import argparse
import os
import tomllib

import h5py
import numpy as np


def ripple(directory, start, end, bins=20):
    with open(os.path.join(directory, "scene.toml"), "rb") as f:
        h = tomllib.load(f)["domain"]["h"]
    with h5py.File(os.path.join(directory, "particles.h5"), "r") as f:
        t = f["time"][:]
        v = -f["velocity"][:, 0, 1]
        y = f["position"][:, 0, 1]
    keep = (t > start + 1e-12) & (t <= end + 1e-12)
    t, v, y = t[keep], v[keep], y[keep]
    mean = v.mean()
    residual = v - np.polyval(np.polyfit(t, v, 2), t)
    place = np.floor((y / (2 * h)) % 1.0 * bins).astype(int)
    binned = [residual[place == k].mean() for k in range(bins) if (place == k).any()]
    return {
        "h": h, "mean": mean, "records": len(t),
        "peak_to_peak": (residual.max() - residual.min()) / mean,
        "rms": residual.std() / mean,
        "periodic": (max(binned) - min(binned)) / mean,
        "cells": (y.max() - y.min()) / h,
    }


def main():
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("runs", nargs="+")
    parser.add_argument("--from", dest="start", type=float, default=0.5)
    parser.add_argument("--to", dest="end", type=float, default=1.0)
    args = parser.parse_args()
    print("| run | h | mean fall speed | peak to peak | RMS | periodic in y mod 2h | cells crossed |")
    print("|---|---|---|---|---|---|---|")
    for run in args.runs:
        r = ripple(run, args.start, args.end)
        print(f"| {run} | {r['h']:g} | {r['mean']:.7f} | {r['peak_to_peak']:.2e} | {r['rms']:.2e} | "
              f"{r['periodic']:.2e} | {r['cells']:.1f} |")


if __name__ == "__main__":
    main()
