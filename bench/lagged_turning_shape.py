#!/usr/bin/python3
"""When the lagged multiplier (splitting.constraint = "incremental") blows up on a particle that
turns (issue 37; docs/evidence/validation_particles.md, "The lagged multiplier on a turning shape").

    bench/lagged_turning_shape.py [--solver build/solver/dlmfd-solve] [--out runs/lagged_turning]
                                  [--coupling incremental] [--end 0.1] [--jobs 2]

Runs cases/shapes/settling_ellipse.toml (released at 45 degrees, h = 1/64, dt = 5e-4) with the
coupling named, over the density ratio rho_p / rho (1.1, 1.5, 3) and the aspect ratio a / b at the
area of the case's ellipse (1 is the disk of that area, the control), then the case's ellipse
(a / b = 2, rho_p / rho = 1.1) at other time steps, grids and the mirror-symmetric mesh. Prints
one line a run: its status, the time it reached, the largest |omega| and the last fall speed.
"""
import argparse
import json
import math
import os
import subprocess
from concurrent.futures import ThreadPoolExecutor

import h5py
import numpy as np

ROOT = os.path.dirname(os.path.dirname(os.path.abspath(__file__)))
CASE = os.path.join(ROOT, "cases/shapes/settling_ellipse.toml")
AREA = 0.125 * 0.0625  # a b of the case's ellipse


def scene_for(ratio, out):
    """The case with the shape of aspect ratio `ratio` (1: a disk) at the case's area."""
    text = open(CASE).read()
    if ratio == 1.0:
        text = text.replace('shape = "ellipse"\n', "")
        text = text.replace("semi_axes = [0.125, 0.0625]\n",
                            f"diameter = {2.0 * math.sqrt(AREA)!r}\n")
    else:
        b = math.sqrt(AREA / ratio)
        text = text.replace("semi_axes = [0.125, 0.0625]", f"semi_axes = [{ratio * b!r}, {b!r}]")
    path = out + ".toml"
    with open(path, "w") as f:
        f.write(text)
    return path


def run(args, rho, ratio, dt=5e-4, h=1.0 / 64, diagonals="sw_ne"):
    name = f"rho{rho}_r{ratio}_dt{dt}_h{h:.6f}_{diagonals}_{args.coupling}"
    out = os.path.join(args.out, name)
    os.makedirs(args.out, exist_ok=True)
    sets = {"particles.0.density": rho, "time.dt": dt, "domain.h": h,
            "domain.diagonals": f'"{diagonals}"', "splitting.constraint": f'"{args.coupling}"',
            "time.end": args.end, "output.particles_every": dt, "output.fields_every": 100}
    cmd = ["nice", "-n", "10", args.solver, scene_for(ratio, out), "--out", out, "--threads", "1",
           "--quiet"]
    for key, value in sets.items():
        cmd += ["--set", f"{key}={value}"]
    subprocess.run(cmd, capture_output=True, text=True, check=False)
    with open(out + "/summary.json") as f:
        summary = json.load(f)
    with h5py.File(out + "/particles.h5", "r") as f:
        omega = f["angular_velocity"][:, 0]
        v = f["velocity"][:, 0, 1]
    return (f"rho_p/rho {rho:4} a/b {ratio:6} dt {dt:.2e} h 1/{1 / h:.0f} {diagonals:5}: "
            f"{summary['status']:9} t = {summary['time']:.4f}, max |omega| = "
            f"{np.max(np.abs(omega)):9.3g}, v = {v[-1]:9.4g}")


def main():
    parser = argparse.ArgumentParser()
    parser.add_argument("--solver", default=os.path.join(ROOT, "build/solver/dlmfd-solve"))
    parser.add_argument("--out", default="runs/lagged_turning")
    parser.add_argument("--coupling", default="incremental")
    parser.add_argument("--end", type=float, default=0.1)
    parser.add_argument("--jobs", type=int, default=2)
    args = parser.parse_args()
    runs = [(rho, ratio) for rho in (1.1, 1.5, 3.0) for ratio in (1.0, 1.0001, 1.25, 2.0, 4.0)]
    runs += [(1.1, 2.0, dt) for dt in (2.5e-4, 1e-4)]
    runs += [(1.1, 2.0, 5e-4, h) for h in (1.0 / 32, 1.0 / 128)]
    runs += [(rho, ratio, 5e-4, 1.0 / 64, "both") for rho, ratio in ((1.1, 2.0), (3.0, 2.0),
                                                                     (1.5, 1.25))]
    with ThreadPoolExecutor(args.jobs) as pool:
        for line in pool.map(lambda r: run(args, *r), runs):
            print(line, flush=True)


if __name__ == "__main__":
    main()
