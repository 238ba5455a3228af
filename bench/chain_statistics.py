#!/usr/bin/python3
"""Chain statistics of settling disks from a results directory (issue 37 point 3; the paper's 5.3a
in a channel periodic along the fall: cases/periodic/5.3a_eleven_disks_periodic.toml;
docs/evidence/validation_particles.md, "Sedimentation without end walls").

    bench/chain_statistics.py RESULTS_DIR [--gap 1.0] [--windows 4] [--csv DIR]

Near pairs: two disks whose surface gap is below GAP radii (periodic images along a periodic axis
counted). The pair angle is the angle of their line of centres to gravity (0: one above the other,
90: side by side). Chains: the groups of disks connected by near pairs; a chain's length is its
number of disks (a lone disk is a chain of 1). Over each of WINDOWS equal windows of the fall
distance (the mean drop of the disks): the histogram of pair angles (15-degree bins, every record
counted) and the distribution of chain lengths (the fraction of disks that sit in a chain of each
length). Prints both as tables, the fall distance reached and the mean fall speed per window; with
--csv DIR writes them (and the mean drop against time) as CSV files for `dlmfd chart --csv`
(bench/chain_statistics.sh draws the figure).
"""
import argparse
import math
import os
import tomllib

import h5py
import numpy as np


def load(directory):
    with h5py.File(directory + "/particles.h5", "r") as f:
        t = f["time"][:]
        x = f["position"][:]
        r = f["radius"][:]
        scene = tomllib.loads(f["scene"][()].decode() if isinstance(f["scene"][()], bytes)
                              else str(f["scene"][()]))
    size = scene["domain"]["size"]
    sides = scene["domain"].get("boundary", {})
    periods = [size[0] if sides.get("left", {}).get("type") == "periodic" else None,
               size[1] if sides.get("bottom", {}).get("type") == "periodic" else None]
    return t, x, r, periods


def separation(a, b, periods):
    d = b - a
    for k, period in enumerate(periods):
        if period:
            d[k] -= period * round(d[k] / period)
    return d


def record_statistics(x, r, periods, gap):
    """Pair angles (degrees) of the near pairs and the chain length of every disk, for one record."""
    n = len(r)
    parent = list(range(n))

    def find(i):
        while parent[i] != i:
            parent[i] = parent[parent[i]]
            i = parent[i]
        return i

    angles = []
    for i in range(n):
        for j in range(i + 1, n):
            d = separation(x[i], x[j], periods)
            dist = math.hypot(d[0], d[1])
            if dist - r[i] - r[j] < gap * 0.5 * (r[i] + r[j]):
                angles.append(math.degrees(math.atan2(abs(d[0]), abs(d[1]))))
                parent[find(i)] = find(j)
    roots = [find(i) for i in range(n)]
    lengths = [roots.count(root) for root in roots]
    return angles, lengths


def main():
    parser = argparse.ArgumentParser()
    parser.add_argument("results")
    parser.add_argument("--gap", type=float, default=1.0, help="near: surface gap below GAP radii")
    parser.add_argument("--windows", type=int, default=4)
    parser.add_argument("--csv", help="write the tables as CSV files into this directory")
    args = parser.parse_args()
    t, x, r, periods = load(args.results)
    n = len(r)
    # The mean drop: unwrap each disk's height across the periodic boundary first.
    y = x[:, :, 1].copy()
    if periods[1]:
        jumps = np.diff(y, axis=0)
        y[1:] -= periods[1] * np.cumsum(np.round(jumps / periods[1]), axis=0)
    drop = y[0].mean() - y.mean(axis=1)
    edges = np.linspace(0.0, drop[-1], args.windows + 1)
    bins = np.arange(0, 91, 15)
    print(f"records {len(t)}, t = {t[-1]:.2f}, fall distance {drop[-1]:.2f} "
          f"(the paper's 5.3a: 0.2 x 15.6 = 3.12; ratio {drop[-1] / 3.12:.1f}), "
          f"mean speed {drop[-1] / t[-1]:.4f}")
    print(f"near pairs: surface gap < {args.gap} radii; angle to gravity (0: vertical)")
    head = " | ".join(f"{bins[k]}-{bins[k + 1]}" for k in range(len(bins) - 1))
    print(f"| fall distance | t | mean speed | pairs a record | {head} | chains of length "
          "1 / 2 / 3 / 4 / 5+ (fraction of disks) | longest |")
    rows = []
    for w in range(args.windows):
        sel = np.where((drop >= edges[w]) & (drop <= edges[w + 1]))[0]
        angles, lengths = [], []
        for i in sel:
            a, ln = record_statistics(x[i], r, periods, args.gap)
            angles += a
            lengths += ln
        hist = np.histogram(angles, bins=bins)[0]
        frac = hist / max(1, len(angles))
        lengths = np.array(lengths)
        chain = [np.mean(lengths == k) for k in (1, 2, 3, 4)] + [np.mean(lengths >= 5)]
        speed = (drop[sel[-1]] - drop[sel[0]]) / (t[sel[-1]] - t[sel[0]])
        rows.append((edges[w], edges[w + 1], frac, chain, t[sel[0]], t[sel[-1]]))
        print(f"| {edges[w]:.1f}-{edges[w + 1]:.1f} | {t[sel[0]]:.1f}-{t[sel[-1]]:.1f} | {speed:.3f} "
              f"| {len(angles) / len(sel):.2f} | " + " | ".join(f"{v:.2f}" for v in frac)
              + " | " + " / ".join(f"{v:.2f}" for v in chain) + f" | {lengths.max()} of {n} |")
    if args.csv:
        write_csv(args.csv, t, drop, bins, rows)


def write_csv(directory, t, drop, bins, rows):
    """pair_angles.csv, chain_lengths.csv and fall.csv for `dlmfd chart --csv ... --group window`."""
    os.makedirs(directory, exist_ok=True)
    centres = 0.5 * (bins[1:] + bins[:-1])
    with open(os.path.join(directory, "pair_angles.csv"), "w") as f:
        f.write("window,angle,fraction\n")
        for a, b, frac, chain, t0, t1 in rows:
            for c, v in zip(centres, frac):
                f.write(f"drop {a:.0f}-{b:.0f},{c:g},{v:.6f}\n")
    with open(os.path.join(directory, "chain_lengths.csv"), "w") as f:
        f.write("window,length,fraction\n")
        for a, b, frac, chain, t0, t1 in rows:
            for k, v in enumerate(chain, start=1):
                f.write(f"drop {a:.0f}-{b:.0f},{k},{v:.6f}\n")
    with open(os.path.join(directory, "fall.csv"), "w") as f:
        f.write("t,drop\n")
        for ti, di in zip(t, drop):
            f.write(f"{ti:.4f},{di:.6f}\n")

if __name__ == "__main__":
    main()
