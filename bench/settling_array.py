#!/usr/bin/python3
"""A square array of disks settling at zero mean flux against the fixed array's drag (issue 37
point 3; cases/periodic/settling_square_array.toml; docs/evidence/validation_particles.md,
"Sedimentation without end walls").

    bench/settling_array.py [--phi 0.1 0.2 0.3] [--cells 32 64 128] [--dt 1e-3] [--window 0.5:1.5]
                            [--solve build/solver/dlmfd-solve] [--work runs/settling_array]

One disk in a unit box periodic in both directions falls under its excess weight W = 1; in its
frame the liquid streams through a fixed square array with superficial velocity V (zero mixture
flux), so V = W / (mu K(Phi)), K from Sangani & Acrivos (1982)
(cases/verification/sangani_acrivos_reference.csv). For each area fraction and mesh: the disk's
mean fall speed over the window (particles.h5, every record), K_settling = W / (mu |V|) and its
error against the reference, the cells the disk crossed in the window, and the mean pressure
gradient's G_y |Omega| / W (diagnostics.csv: the liquid carries the whole excess weight). With
--csv, the hindered settling speed V mu / W against Phi beside the reference's 1 / K, for
`dlmfd chart` (docs/figures/settling_array_speed.png).
Run the meshes one after another on one thread (about 1 / 3 / 20 s a run at 32 / 64 / 128 cells).
"""
import argparse
import csv
import itertools
import math
import os
import subprocess

import h5py
import numpy as np

SCENE = "cases/periodic/settling_square_array.toml"
REFERENCE = "cases/verification/sangani_acrivos_reference.csv"


def reference():
    with open(REFERENCE) as f:
        rows = csv.DictReader(line for line in f if not line.startswith("#"))
        return {float(r["phi"]): float(r["k"]) for r in rows}


def run(solve, work, phi, cells, dt):
    d = 2.0 * math.sqrt(phi / math.pi)
    # rho_p - rho = 1, so |g| = W / (pi a^2) = 1 / phi makes W = 1.
    out = os.path.join(work, f"phi{phi}_n{cells}_dt{dt}")
    subprocess.run([solve, SCENE, "--out", out, "--threads", "1", "--quiet", "--set", f"time.dt={dt!r}",
                    "--set", f"domain.h={1.0 / cells!r}", "--set", f"particles.0.diameter={d!r}",
                    "--set", f"gravity=[0.0, {-1.0 / phi!r}]", "--set", "output.fields_every=0"],
                   check=True)
    return out


def measure(out, window):
    a, b = window
    with h5py.File(os.path.join(out, "particles.h5"), "r") as f:
        t = f["time"][:]
        v = f["velocity"][:, 0, 1]
        y = f["position"][:, 0, 1]
    sel = (t >= a - 1e-9) & (t <= b + 1e-9)
    with open(os.path.join(out, "diagnostics.csv"), newline="") as f:
        rows = [r for r in csv.DictReader(f) if a - 1e-9 <= float(r["time"]) <= b + 1e-9]
    g = np.mean([float(r["mean_pressure_gradient_y"]) for r in rows])
    rate = max(max(abs(float(r["flow_rate_x"])), abs(float(r["flow_rate_y"]))) for r in rows)
    return float(np.mean(v[sel])), float(np.std(v[sel])), float(y[sel][0] - y[sel][-1]), g, rate


def main():
    parser = argparse.ArgumentParser()
    parser.add_argument("--phi", nargs="+", type=float, default=[0.1, 0.2, 0.3])
    parser.add_argument("--cells", nargs="+", type=int, default=[32, 64, 128])
    parser.add_argument("--window", default="0.5:1.5")
    parser.add_argument("--dt", nargs="+", type=float, default=[1e-3])
    parser.add_argument("--solve", default="build/solver/dlmfd-solve")
    parser.add_argument("--work", default="runs/settling_array")
    parser.add_argument("--no-run", action="store_true", help="measure existing runs only")
    parser.add_argument("--csv", help="write series,phi,speed (V mu / W, ours per mesh and the "
                        "reference 1 / K) for `dlmfd chart --csv FILE --group series`")
    args = parser.parse_args()
    window = tuple(float(x) for x in args.window.split(":"))
    ref = reference()
    os.makedirs(args.work, exist_ok=True)
    print("| Phi (K ref) | h | dt | mean V | std V | K = W / (mu V) | error % | cells crossed "
          "| G_y A / W | max end-of-step rate |")
    print("|---|---|---|---|---|---|---|---|---|---|")
    points = [("Sangani & Acrivos (1 / K)", phi, 1.0 / ref[phi]) for phi in args.phi]
    for phi, cells, dt in itertools.product(args.phi, args.cells, args.dt):
        out = os.path.join(args.work, f"phi{phi}_n{cells}_dt{dt}")
        if not args.no_run:
            out = run(args.solve, args.work, phi, cells, dt)
        v, sd, drop, g, rate = measure(out, window)
        k = 1.0 / abs(v)
        print(f"| {phi} ({ref[phi]}) | 1/{cells} | {dt:g} | {v:.6f} | {sd:.1e} | {k:.4f} "
              f"| {100 * (k / ref[phi] - 1):+.3f} | {drop * cells:.2f} | {g:.6f} | {rate:.1e} |",
              flush=True)
        points.append((f"settling array h = 1/{cells} dt = {dt:g}", phi, abs(v)))
    if args.csv:
        with open(args.csv, "w") as f:
            f.write("series,phi,speed\n")
            for series, phi, speed in sorted(points):
                f.write(f"{series},{phi},{speed:.8g}\n")

if __name__ == "__main__":
    main()
