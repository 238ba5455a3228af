#!/usr/bin/python3
"""A settling ellipse from a results directory (issue 37, point 2): its fall speed, Reynolds number
Re = rho U 2a / eta (a the semi-major axis), lateral position and orientation against time.

    bench/settling_ellipse.py RESULTS_DIR [--every 0.25]

The orientation is the long axis' angle from the horizontal folded into (-90, 90] degrees: 0 is
broadside-on (long axis horizontal), +-90 long axis vertical. Prints a table, then one line of
key = value for the last record.
"""
import argparse
import math
import re

import h5py
import numpy as np


def main():
    parser = argparse.ArgumentParser()
    parser.add_argument("results")
    parser.add_argument("--every", type=float, default=0.25)
    args = parser.parse_args()
    with h5py.File(args.results + "/particles.h5", "r") as f:
        t = f["time"][:]
        x = f["position"][:, 0, :]
        u = f["velocity"][:, 0, :]
        theta = f["angle"][:, 0]
        a = max(f["semi_axes"][0])
        scene = f["scene"][()].decode() if "scene" in f else ""
    rho = float(re.search(r"\[fluid\][^\[]*?density = ([0-9.e+-]+)", scene, re.S).group(1))
    eta = float(re.search(r"\[fluid\][^\[]*?viscosity = ([0-9.e+-]+)", scene, re.S).group(1))
    folded = (np.degrees(theta) + 90.0) % 180.0 - 90.0
    print(f"{'t':>7} {'x':>8} {'y':>8} {'v':>9} {'Re':>7} {'angle_deg':>10}")
    next_t = 0.0
    for i in range(len(t)):
        if t[i] + 1e-12 >= next_t or i == len(t) - 1:
            re_ = rho * abs(u[i, 1]) * 2 * a / eta
            print(f"{t[i]:7.3f} {x[i, 0]:8.4f} {x[i, 1]:8.4f} {u[i, 1]:9.4f} {re_:7.2f} "
                  f"{folded[i]:10.2f}")
            next_t += args.every
    re_end = rho * abs(u[-1, 1]) * 2 * a / eta
    print(f"t_end={t[-1]:.4g} fall_speed={-u[-1, 1]:.5g} reynolds={re_end:.4g} "
          f"x_end={x[-1, 0]:.5g} angle_end_deg={folded[-1]:.4g} "
          f"max_abs_angle_last_quarter_deg={np.max(np.abs(folded[t >= 0.75 * t[-1]])):.4g}")


if __name__ == "__main__":
    main()
