#!/usr/bin/python3
"""The mean fall speed of particle 0 (with --all: of every particle) over windows of time, from results directories (issue 37,
point 3: the periodic channel at zero net flux against the closed one; docs/evidence/validation_particles.md,
"Sedimentation without end walls").

    bench/fall_speed_windows.py RESULTS_DIR... [--windows 0.5:1.5 1:2 1.5:2.5] [--all]

For each directory and window: the mean and standard deviation of the vertical velocity over the
particle records (particles.h5) with a <= t <= b, and the mean pressure gradient and end-of-step
flow rate of diagnostics.csv over the same window when the scene held a flow rate.
"""
import argparse
import csv
import os

import h5py
import numpy as np


def diagnostics(directory):
    path = os.path.join(directory, "diagnostics.csv")
    with open(path, newline="") as f:
        rows = list(csv.DictReader(f))
    if not rows or "mean_pressure_gradient" not in rows[0]:
        return None
    t = np.array([float(r["time"]) for r in rows])
    g = np.array([float(r["mean_pressure_gradient"]) for r in rows])
    q = np.array([float(r["flow_rate"]) for r in rows])
    return t, g, q


def main():
    parser = argparse.ArgumentParser()
    parser.add_argument("directories", nargs="+")
    parser.add_argument("--windows", nargs="+", default=["0.5:1.5", "1:2", "1.5:2.5"])
    parser.add_argument("--all", action="store_true", help="the mean over every particle")
    args = parser.parse_args()
    windows = [tuple(float(x) for x in w.split(":")) for w in args.windows]
    for d in args.directories:
        with h5py.File(os.path.join(d, "particles.h5"), "r") as f:
            t = f["time"][:]
            v = f["velocity"][:].reshape(len(t), -1, 2)[:, :, 1]
        v = v.mean(axis=1) if args.all else v[:, 0]
        diag = diagnostics(d)
        for a, b in windows:
            if t[-1] < b - 1e-9:
                print(f"{d} [{a:g}, {b:g}]: the run ends at t = {t[-1]:g}")
                continue
            m = (t >= a - 1e-9) & (t <= b + 1e-9)
            line = f"{d} [{a:g}, {b:g}]: mean v = {v[m].mean():.4f}, std {v[m].std():.4f}"
            if diag is not None:
                dt, g, q = diag
                k = (dt >= a - 1e-9) & (dt <= b + 1e-9)
                line += f", mean G = {g[k].mean():.4f}, max |flow_rate| = {abs(q[k]).max():.2e}"
            print(line)


if __name__ == "__main__":
    main()
