#!/usr/bin/python3
"""Jeffery's orbit from a results directory (issue 37, point 2): the period of the ellipse's
rotation and its angular velocity against Jeffery's law.

    bench/jeffery_orbit.py RESULTS_DIR [--ratio R] [--shear G]

Jeffery (1922), in 2D (Bretherton 1962): d theta / dt = -G (r^2 sin^2 theta + cos^2 theta) / (r^2 + 1)
for an ellipse of aspect ratio r in the shear u = G y, period T = 2 pi (r + 1/r) / G. The angle
passes theta = -pi/2 - k pi (broadside to the flow, fastest) once every half period: the measured
half periods are the times between successive crossings (linear interpolation between records;
the first comes at about T / 4, long after the liquid's start-up time rho H^2 / eta). Jeffery's law is checked over the last half
period: max |omega - omega_J(theta)| / max |omega_J|. Prints one line of key = value.
"""
import argparse
import math

import h5py
import numpy as np


def main():
    parser = argparse.ArgumentParser()
    parser.add_argument("results")
    parser.add_argument("--ratio", type=float, default=2.0)
    parser.add_argument("--shear", type=float, default=1.0)
    parser.add_argument("--particle", type=int, default=0)
    args = parser.parse_args()
    with h5py.File(args.results + "/particles.h5", "r") as f:
        t = f["time"][:]
        theta = f["angle"][:, args.particle]
        omega = f["angular_velocity"][:, args.particle]
    r, g = args.ratio, args.shear
    period = 2.0 * math.pi * (r + 1.0 / r) / g
    # Crossings of theta = -pi/2 - k pi: the angle turns clockwise (decreasing).
    phase = (theta + math.pi / 2) / math.pi  # crosses -k at the k-th broadside position
    crossings = []
    for i in range(1, len(t)):
        lo, hi = math.floor(phase[i - 1]), math.floor(phase[i])
        if hi < lo:  # passed the integer lo
            s = (phase[i - 1] - lo) / (phase[i - 1] - phase[i])
            crossings.append(t[i - 1] + s * (t[i] - t[i - 1]))
    # The first quarter period measured: from the first broadside crossing to the next aligned
    # one (theta = -pi, -2 pi, ...), T / 4 by the orbit's symmetry (the CI test's measure).
    if crossings:
        aligned = theta / math.pi
        for i in range(1, len(t)):
            if t[i - 1] >= crossings[0] and math.floor(aligned[i]) < math.floor(aligned[i - 1]):
                lo = math.floor(aligned[i - 1])
                s = (aligned[i - 1] - lo) / (aligned[i - 1] - aligned[i])
                quarter = t[i - 1] + s * (t[i] - t[i - 1]) - crossings[0]
                line_quarter = 100.0 * (4.0 * quarter / period - 1.0)
                break
        else:
            line_quarter = None
    halves = np.diff(crossings) if len(crossings) > 1 else np.array([])
    line = {"records": len(t), "t_end": t[-1], "crossings": len(crossings),
            "period_jeffery": period}
    if crossings and line_quarter is not None:
        line["quarter_error_pct"] = line_quarter
    if halves.size:
        measured = 2.0 * halves.mean()
        line["period"] = measured
        line["period_error_pct"] = 100.0 * (measured / period - 1.0)
        line["half_period_spread_pct"] = 100.0 * (halves.max() - halves.min()) / halves.mean()
        last = (t >= crossings[-2]) & (t <= crossings[-1])  # the last half period
        jeffery = -g * (r * r * np.sin(theta[last]) ** 2 + np.cos(theta[last]) ** 2) / (r * r + 1)
        line["omega_law_error_pct"] = 100.0 * np.max(np.abs(omega[last] - jeffery)) / np.max(
            np.abs(jeffery))
        # The slowest (aligned with the flow) and fastest (broadside) rates against Jeffery's.
        line["omega_aligned_ratio"] = omega[last].max() / (-g / (r * r + 1))
        line["omega_broadside_ratio"] = omega[last].min() / (-g * r * r / (r * r + 1))
    print(" ".join(f"{k}={v:.6g}" if isinstance(v, float) else f"{k}={v}"
                   for k, v in line.items()))


if __name__ == "__main__":
    main()
