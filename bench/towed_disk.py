#!/usr/bin/env python3
"""The towed disk's drag against the fixed disk's (docs/evidence/cut_cell_boundary.md, "A body in
prescribed motion"; bench/towed_disk.sh runs the cases).

  towed_disk.py table RUN [RUN ...] --fixed FIXED [FIXED ...] [--from T] [--bins BINS]
      One line per towed run (a dlmfd-solve output with particles.h5 written every step): the mean
      drag -F_x over whole crossings of a pressure cell (2h: the pattern of the P1-iso-P2 mesh
      repeats every 2h) after t = T (the steady state), the crossing oscillation's amplitude (half
      the range, and the largest Fourier amplitude, at the multiples of U/(2h), both relative to the
      mean, %), the mean against the fixed disk's drag (the mean of the FIXED runs' last values: the
      Galilean-equivalent disk at rest at sub-grid shifts), the drift (the slope of a line fit,
      % of the mean per unit time: 0 at a steady state), and the peak-to-peak of the drag's means
      binned by the centre's position mod h (BINS bins, % of the mean: the part of the oscillation
      that is the body's place on the grid).
  towed_disk.py spectrum RUN [RUN ...] --out FIGURE [--from T]
      The drag's amplitude spectrum after t = T against the frequency in units of U/h.
"""
import argparse
import sys

import h5py
import numpy as np


def read(run):
    with h5py.File(run + "/particles.h5", "r") as f:
        t = f["time"][:]
        force = f["force"][:, 0, :]
        x = f["position"][:, 0, :] if "position" in f else None
        u = f["velocity"][:, 0, :] if "velocity" in f else None
    return t, -force[:, 0], x, u


def grid_step(run):
    import re
    return float(re.search(r"h = ([0-9.e+-]+)", open(run + "/scene.toml").read()).group(1))


def binned_peak_to_peak(run, start, bins):
    """Peak-to-peak of the mean drag in BINS bins of the centre's x mod h after `start`."""
    t, drag, x, _ = read(run)
    h = grid_step(run)
    keep = t >= start - 1e-12
    phase = np.mod(x[keep, 0] / h, 1.0)
    which = np.minimum((phase * bins + 1e-9).astype(int), bins - 1)
    means = np.array([drag[keep][which == b].mean() for b in range(bins) if np.any(which == b)])
    return (means.max() - means.min()) / drag[keep].mean()


def steady_window(run, start):
    """The drag after `start` over whole crossings of 2h; the frequency U/h."""
    t, drag, _, u = read(run)
    speed = np.linalg.norm(u[-1])
    h = grid_step(run)
    keep = t >= start - 1e-12
    t, drag = t[keep], drag[keep]
    period = 2 * h / speed
    dt = t[1] - t[0]
    per = period / dt
    cells = int(len(t) / per)
    n = int(round(cells * per))
    return t[:n], drag[:n], speed / h, cells


def spectrum(drag, dt):
    d = drag - drag.mean()
    amp = 2.0 * np.abs(np.fft.rfft(d)) / len(d)
    freq = np.fft.rfftfreq(len(d), dt)
    return freq, amp


def table(args):
    fixed = np.array([read(r)[1][-1] for r in args.fixed]) if args.fixed else None
    if fixed is not None:
        print("fixed disk: %s mean %.7f spread %.4f %%" % (
            " ".join("%.7f" % v for v in fixed), fixed.mean(),
            100 * (fixed.max() - fixed.min()) / fixed.mean()))
    print("run,crossings_2h,mean_drag,half_range_pct,largest_crossing_harmonic_pct,vs_fixed_pct,"
          "drift_pct_per_unit_time,binned_peak_to_peak_pct")
    for run in args.runs:
        t, drag, f_cross, cells = steady_window(run, args.start)
        mean = drag.mean()
        freq, amp = spectrum(drag, t[1] - t[0])
        harmonics = [amp[np.argmin(np.abs(freq - 0.5 * k * f_cross))] for k in range(1, 100)
                     if 0.5 * k * f_cross <= freq[-1]]
        slope = np.polyfit(t, drag, 1)[0]
        vs = 100 * (mean / fixed.mean() - 1) if fixed is not None else float("nan")
        print("%s,%d,%.7f,%.4f,%.4f,%.4f,%.4f,%.4f" % (
            run, cells, mean, 100 * 0.5 * (drag.max() - drag.min()) / mean,
            100 * max(harmonics) / mean, vs, 100 * slope / mean,
            100 * binned_peak_to_peak(run, args.start, args.bins)))


def figure(args):
    import matplotlib
    matplotlib.use("Agg")
    import matplotlib.pyplot as plt
    fig, (a, b) = plt.subplots(1, 2, figsize=(10, 3.8))
    for run in args.runs:
        t, drag, f_cross, _ = steady_window(run, args.start)
        label = run.rstrip("/").split("/")[-1]
        parts = label.split("_")
        if len(parts) == 3 and parts[0] == "towed":
            label = "D/h = %s, U dt / h = %s" % (parts[1], parts[2])
        a.plot(t, 100 * (drag / drag.mean() - 1), lw=0.8, label=label)
        freq, amp = spectrum(drag, t[1] - t[0])
        b.semilogy(freq[1:] / f_cross, 100 * amp[1:] / drag.mean(), lw=0.8, label=label)
    a.set_xlabel("t")
    a.set_ylabel("drag / its mean - 1 (%)")
    a.set_title("towed disk, after t = %g" % args.start)
    b.set_xlabel("frequency / (U / h)  (1: one cell crossed)")
    b.set_ylabel("amplitude / mean drag (%)")
    b.axhline(0.1, color="k", lw=0.6, ls="--")
    b.set_title("spectrum (the issue's 0.1 % dashed)")
    b.legend(fontsize=7)
    fig.tight_layout()
    fig.savefig(args.out, dpi=110)


def main():
    p = argparse.ArgumentParser()
    p.add_argument("what", choices=["table", "spectrum"])
    p.add_argument("runs", nargs="+")
    p.add_argument("--fixed", nargs="*", default=[])
    p.add_argument("--from", dest="start", type=float, default=2.0)
    p.add_argument("--out", default="towed_disk_spectrum.png")
    p.add_argument("--bins", type=int, default=10)
    args = p.parse_args()
    table(args) if args.what == "table" else figure(args)


if __name__ == "__main__":
    sys.exit(main())
