#!/usr/bin/env python3
"""The polymer's wall value at a fixed disk: trA = 2 + 2 (lambda gamma_dot)^2 (issue 33 point 3).

On a no-slip wall at rest the velocity vanishes, so its tangential derivatives do too and, by
div u = 0, so does d(u.n)/dn: grad u = gamma_dot t n^T with gamma_dot = t . (du/dn) the wall shear
rate (n the unit normal into the liquid, t = e_z x n). In steady flow u . grad A = 0 there, and the
Oldroyd-B equation L A + A L^T = (A - I) / lambda has the one solution A_tt = 1 + 2 (lambda
gamma_dot)^2, A_tn = lambda gamma_dot, A_nn = 1: trA = 2 + 2 (lambda gamma_dot)^2 (the paper,
section 5.1: "all flows become viscometric at a solid wall").

This script reads the last field snapshot of a run (docs/results.md: nodal u, v, A11, A12, A22 on
the h-grid; the P1 interpolant on the SW-NE triangles, or the mean of the SW-NE and NW-SE
interpolants with domain.diagonals = "both") and evaluates, at N equally spaced points x_b = X +
R (cos th, sin th) on every disk's true circle (th_k = 2 pi (k + 1/2) / N, clear of the symmetry
line):
  trA       the P1 interpolant of trA at x_b (the triangle holding x_b is a cut one: its nodes
            inside the body carry the extension of the fluid's A, or I);
  trA_fit   a least-squares quadratic over the fluid nodes within 3h of x_b, at x_b (the fluid's
            values alone, extrapolated);
  g_tri     t . (grad u_h) n of that triangle (the discrete velocity's own gradient at x_b);
  g_node    t . L n, L the P1 interpolant at x_b of the nodal velocity gradient that step (35)
            freezes (the mean of the P1 gradients of the 6 triangles around each node, over both
            triangulations with "both": conformation/velocity_gradient.h);
  g_normal  the one-sided quadratic through u_t(0) = 0, u_t(h) and u_t(2h) along the normal into
            the liquid: (4 u_t(h) - u_t(2h)) / (2h), u_t the P1 interpolant of t . u (the
            estimate tests/convergence/polymer_wall_value_test.cc uses);
  g_fit     d(t . u)/dn of a least-squares quadratic over the fluid nodes within 3h of x_b and
            the no-slip zeros at the circle's points within 3h, h apart;
and the residuals r = trA - 2 - 2 (lambda g)^2 of the pairs in PAIRS, their largest |r| and RMS
over the points. Every point on the circle is counted; a point whose triangles reach outside the
grid is an error. A Newtonian run (no trA) counts as A = I: its shear rates can be compared. With
several runs (coarse to fine) it prints the observed orders log(e_c / e_f) / log(h_c / h_f) of each
largest |r| and RMS between successive runs; --profile THETA prints trA along the normal at THETA.
--torque compares the first disk's torque (particles.h5, the last record) with the torque of its
wall traction, R^2 times the integral over theta of the shear stress t . sigma n at x_b, taken two
ways from g_normal: eta_s g + G A_tn (A_tn = t . A n, the P1 interpolant of A at x_b; G = eta_p /
lambda) and the viscometric eta g (A at its wall value). In the steady liquid the three agree as h
-> 0; a wall shear rate that is too large for the body's load shows as a viscometric torque above
the body's (docs/evidence/cut_cell_boundary.md, "Imposing the wall value").
  /usr/bin/python3 bench/wall_value.py RUN [RUN ...] [--angles 128] [--csv FILE] [--profile THETA]
                                       [--torque]
Reference: Singh, Joseph, Hesla, Glowinski & Pan, J. Non-Newtonian Fluid Mech. 91 (2000), section
5.1; docs/evidence/cut_cell_boundary.md, "The polymer's wall value".
"""
import argparse
import glob
import math
import os
import sys
import tomllib

import h5py
import numpy as np

FIT_RADIUS = 3.0  # the fits' nodes: the fluid nodes within this many h of the point
GAMMAS = ("g_tri", "g_node", "g_normal", "g_fit")
# The pairs (trA estimate, shear-rate estimate) whose residual is reported.
PAIRS = (("trA", "g_tri"), ("trA", "g_node"), ("trA", "g_normal"), ("trA", "g_fit"),
         ("trA_fit", "g_fit"), ("trA_fit", "g_normal"))


def last_snapshot(run):
    snaps = sorted(glob.glob(os.path.join(run, "fields", "snap_*.h5")))
    if not snaps:
        sys.exit(f"{run}: no field snapshot")
    return snaps[-1]


class P1Field:
    """Nodal values on the uniform grid, P1 on one or both triangulations (core/grid.h)."""

    def __init__(self, x0, y0, h, both):
        self.x0, self.y0, self.h, self.both = x0, y0, h, both

    def _cell(self, f, x, y):
        s, r = (x - self.x0) / self.h, (y - self.y0) / self.h
        i, j = int(math.floor(s)), int(math.floor(r))
        if i < 0 or j < 0 or i + 1 >= f.shape[1] or j + 1 >= f.shape[0]:
            raise ValueError(f"point ({x}, {y}) outside the grid")
        return s - i, r - j, f[j, i], f[j, i + 1], f[j + 1, i], f[j + 1, i + 1]

    def value_grad(self, f, x, y):
        """The interpolant and its gradient (of the triangle holding the point) at (x, y)."""
        xi, eta, f00, f10, f01, f11 = self._cell(f, x, y)
        h = self.h
        if xi >= eta:  # SW-NE lower: (i,j), (i+1,j), (i+1,j+1)
            gx, gy = (f10 - f00) / h, (f11 - f10) / h
        else:  # SW-NE upper: (i,j), (i+1,j+1), (i,j+1)
            gx, gy = (f11 - f01) / h, (f01 - f00) / h
        val = f00 + gx * xi * h + gy * eta * h
        if not self.both:
            return val, np.array([gx, gy])
        if xi + eta <= 1.0:  # NW-SE lower-left: (i,j), (i+1,j), (i,j+1)
            hx, hy = (f10 - f00) / h, (f01 - f00) / h
            val2 = f00 + hx * xi * h + hy * eta * h
        else:  # NW-SE upper-right: (i+1,j), (i+1,j+1), (i,j+1)
            hx, hy = (f11 - f01) / h, (f11 - f10) / h
            val2 = f11 - hx * (1.0 - xi) * h - hy * (1.0 - eta) * h
        return 0.5 * (val + val2), 0.5 * np.array([gx + hx, gy + hy])


def node_gradient(f, h, both):
    """d/dx and d/dy of f at the interior nodes: the mean of the 6 triangles' P1 gradients around
    each node (and the mean of the two triangulations' means with "both"); NaN on the sides."""
    ny, nx = f.shape[0] - 1, f.shape[1] - 1
    dx_s = (f[:, 1:] - f[:, :-1]) / h  # horizontal edges (ny+1, nx)
    dy_s = (f[1:, :] - f[:-1, :]) / h  # vertical edges (ny, nx+1)
    # SW-NE per square (j, i): lower: dx on the bottom edge, dy on the right edge; upper: dx on the
    # top edge, dy on the left edge.
    low_x, low_y = dx_s[:-1, :], dy_s[:, 1:]
    up_x, up_y = dx_s[1:, :], dy_s[:, :-1]
    gx = np.full(f.shape, np.nan)
    gy = np.full(f.shape, np.nan)
    j, i = np.s_[1:-1], np.s_[1:-1]
    # node (i, j) touches: square (i,j) lower+upper, (i-1,j) lower, (i-1,j-1) lower+upper, (i,j-1)
    # upper.
    sq = lambda a, dj, di: a[1 + dj:ny + dj, 1 + di:nx + di]  # noqa: E731
    sx = sq(low_x, 0, 0) + sq(up_x, 0, 0) + sq(low_x, 0, -1) + sq(low_x, -1, -1) + sq(
        up_x, -1, -1) + sq(up_x, -1, 0)
    sy = sq(low_y, 0, 0) + sq(up_y, 0, 0) + sq(low_y, 0, -1) + sq(low_y, -1, -1) + sq(
        up_y, -1, -1) + sq(up_y, -1, 0)
    gx[j, i], gy[j, i] = sx / 6.0, sy / 6.0
    if not both:
        return gx, gy
    # NW-SE per square: lower-left: dx bottom, dy left; upper-right: dx top, dy right. Node (i, j)
    # touches square (i,j) lower-left, (i-1,j) lower-left+upper-right, (i-1,j-1) upper-right,
    # (i,j-1) lower-left+upper-right.
    ll_x, ll_y = dx_s[:-1, :], dy_s[:, :-1]
    ur_x, ur_y = dx_s[1:, :], dy_s[:, 1:]
    tx = sq(ll_x, 0, 0) + sq(ll_x, 0, -1) + sq(ur_x, 0, -1) + sq(ur_x, -1, -1) + sq(
        ll_x, -1, 0) + sq(ur_x, -1, 0)
    ty = sq(ll_y, 0, 0) + sq(ll_y, 0, -1) + sq(ur_y, 0, -1) + sq(ur_y, -1, -1) + sq(
        ll_y, -1, 0) + sq(ur_y, -1, 0)
    gx[j, i] = 0.5 * (gx[j, i] + tx / 6.0)
    gy[j, i] = 0.5 * (gy[j, i] + ty / 6.0)
    return gx, gy


def quadratic_fit(points, values, origin, n, t, h):
    """Least-squares quadratic in the local frame (s along n, tau along t, in units of h) through
    the points; returns its value and its d/ds (per unit length) at the origin."""
    d = points - origin
    s, tau = d @ n / h, d @ t / h
    basis = np.stack([np.ones_like(s), s, tau, s * s, s * tau, tau * tau], axis=1)
    c, *_ = np.linalg.lstsq(basis, values, rcond=None)
    return c[0], c[1] / h


def read_run(run):
    """lambda, both diagonals or not, and the last snapshot's grid, u, v, trA, bodies and time."""
    scene = tomllib.loads(open(os.path.join(run, "scene.toml")).read())
    lam = float(scene["fluid"]["relaxation_time"])
    both = scene["domain"].get("diagonals", "sw_ne") == "both"
    with h5py.File(last_snapshot(run), "r") as f:
        x, y = f["x"][:], f["y"][:]
        u, v = f["u"][:], f["v"][:]
        tra = f["trA"][:] if "trA" in f else np.full(u.shape, 2.0)  # a Newtonian run: A = I
        centres, radii = f["particles/position"][:], f["particles/radius"][:]
        time = float(f.attrs["time"])
    return lam, both, x, y, u, v, tra, centres, radii, time


def measure(run, angles):
    lam, both, x, y, u, v, tra, centres, radii, time = read_run(run)
    h = float(x[1] - x[0])
    p1 = P1Field(float(x[0]), float(y[0]), h, both)
    lu = node_gradient(u, h, both)
    lv = node_gradient(v, h, both)
    xx, yy = np.meshgrid(x, y)
    nodes = np.stack([xx.ravel(), yy.ravel()], axis=1)
    distance = np.min([np.hypot(nodes[:, 0] - c[0], nodes[:, 1] - c[1]) - r
                       for c, r in zip(centres, radii)], axis=0)
    fluid = distance >= 0.0
    rows = []
    for b, (c, radius) in enumerate(zip(centres, radii)):
        for k in range(angles):
            th = 2.0 * math.pi * (k + 0.5) / angles
            n = np.array([math.cos(th), math.sin(th)])
            t = np.array([-n[1], n[0]])
            xb = c + radius * n
            tr, _ = p1.value_grad(tra, *xb)
            _, gu = p1.value_grad(u, *xb)
            _, gv = p1.value_grad(v, *xb)
            grad = np.array([gu, gv])  # grad[i, j] = du_i / dx_j
            g_tri = t @ grad @ n
            lnode = np.array([[p1.value_grad(lu[0], *xb)[0], p1.value_grad(lu[1], *xb)[0]],
                              [p1.value_grad(lv[0], *xb)[0], p1.value_grad(lv[1], *xb)[0]]])
            g_node = t @ lnode @ n
            ut = []
            for s in (h, 2.0 * h):
                q = xb + s * n
                ut.append(t @ np.array([p1.value_grad(u, *q)[0], p1.value_grad(v, *q)[0]]))
            g_normal = (4.0 * ut[0] - ut[1]) / (2.0 * h)
            near = fluid & (np.hypot(nodes[:, 0] - xb[0], nodes[:, 1] - xb[1]) <= FIT_RADIUS * h)
            tra_fit, _ = quadratic_fit(nodes[near], tra.ravel()[near], xb, n, t, h)
            # u_t: the fluid nodes and the no-slip points of the circle within the radius (u = 0).
            dth = h / radius
            arc = th + dth * np.arange(-int(FIT_RADIUS), int(FIT_RADIUS) + 1)
            wall = c + radius * np.stack([np.cos(arc), np.sin(arc)], axis=1)
            pts = np.concatenate([nodes[near], wall])
            vals = np.concatenate([u.ravel()[near] * t[0] + v.ravel()[near] * t[1],
                                   np.zeros(len(wall))])
            _, g_fit = quadratic_fit(pts, vals, xb, n, t, h)
            row = {"body": b, "theta": th, "trA": tr, "trA_fit": tra_fit, "g_tri": g_tri,
                   "g_node": g_node, "g_normal": g_normal, "g_fit": g_fit}
            for a, g in PAIRS:
                row[f"r_{a}_{g}"] = row[a] - 2.0 - 2.0 * (lam * row[g]) ** 2
            rows.append(row)
    if any(not np.isfinite(list(r.values())).all() for r in rows):
        sys.exit(f"{run}: a point's value is not finite (a node gradient on a side?)")
    return {"run": run, "h": h, "lambda": lam, "both": both, "time": time, "rows": rows}


def profile(run, theta):
    """trA_h along the normal at theta (the P1 interpolant), against the wall value."""
    lam, both, x, y, u, v, tra, centres, radii, _ = read_run(run)
    c, radius = centres[0], radii[0]
    h = float(x[1] - x[0])
    p1 = P1Field(float(x[0]), float(y[0]), h, both)
    n = np.array([math.cos(theta), math.sin(theta)])
    t = np.array([-n[1], n[0]])
    xb = c + radius * n
    ut = [t @ np.array([p1.value_grad(u, *(xb + s * n))[0], p1.value_grad(v, *(xb + s * n))[0]])
          for s in (h, 2.0 * h)]
    g = (4.0 * ut[0] - ut[1]) / (2.0 * h)
    print(f"{run}: theta {theta:.4f}, g_normal {g:.4f}, wall value {2 + 2 * (lam * g) ** 2:.4f}")
    for k in range(9):
        q = xb + k * h * n
        if not (x[0] <= q[0] < x[-1] and y[0] <= q[1] < y[-1]):
            break  # the profile reaches the grid's side
        print(f"  s = {k * h:.6f} ({k} h): trA_h {p1.value_grad(tra, *q)[0]:.4f}")


def torque(run, angles):
    """The first disk's torque against its wall traction's (the module's header, --torque)."""
    lam, both, x, y, u, v, _, centres, radii, _ = read_run(run)
    scene = tomllib.loads(open(os.path.join(run, "scene.toml")).read())
    eta = float(scene["fluid"]["viscosity"])
    eta_s = eta * float(scene["fluid"]["solvent_ratio"])
    modulus = (eta - eta_s) / lam
    with h5py.File(last_snapshot(run), "r") as f:
        a11, a12, a22 = f["A11"][:], f["A12"][:], f["A22"][:]
    with h5py.File(os.path.join(run, "particles.h5"), "r") as f:
        body = float(f["torque"][-1, 0])
    h = float(x[1] - x[0])
    p1 = P1Field(float(x[0]), float(y[0]), h, both)
    c, radius = centres[0], radii[0]
    split = viscometric = 0.0
    for k in range(angles):
        th = 2.0 * math.pi * (k + 0.5) / angles
        n = np.array([math.cos(th), math.sin(th)])
        t = np.array([-n[1], n[0]])
        xb = c + radius * n
        ut = [t @ np.array([p1.value_grad(u, *(xb + s * n))[0], p1.value_grad(v, *(xb + s * n))[0]])
              for s in (h, 2.0 * h)]
        g = (4.0 * ut[0] - ut[1]) / (2.0 * h)
        a = np.array([[p1.value_grad(a11, *xb)[0], p1.value_grad(a12, *xb)[0]],
                      [p1.value_grad(a12, *xb)[0], p1.value_grad(a22, *xb)[0]]])
        weight = radius * radius * 2.0 * math.pi / angles
        split += weight * (eta_s * g + modulus * (t @ a @ n))
        viscometric += weight * eta * g
    print(f"{run}: torque {body:.5f}; of the wall traction: eta_s g + G A_tn {split:.5f}, "
          f"eta g {viscometric:.5f} ({100 * (viscometric / body - 1):+.2f} %)")


def summary(m):
    """Largest |r| and RMS r of each pair over the points."""
    out = {}
    for a, g in PAIRS:
        r = np.array([row[f"r_{a}_{g}"] for row in m["rows"]])
        out[(a, g)] = (float(np.max(np.abs(r))), float(np.sqrt(np.mean(r**2))))
    return out


def main():
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("runs", nargs="+")
    ap.add_argument("--angles", type=int, default=128)
    ap.add_argument("--csv", help="write every point of every run here")
    ap.add_argument("--profile", type=float, metavar="THETA",
                    help="also print trA_h along the normal at the angle THETA of the first disk, "
                    "at s = 0, h, 2h, ... 8h from the wall, and its wall value by g_normal")
    ap.add_argument("--torque", action="store_true",
                    help="also compare the first disk's torque with its wall traction's")
    a = ap.parse_args()
    if a.torque:
        for r in a.runs:
            torque(r, a.angles)
    if a.profile is not None:
        for r in a.runs:
            profile(r, a.profile)
    ms = [measure(r, a.angles) for r in a.runs]
    ss = [summary(m) for m in ms]
    for m in ms:
        wall = max(2 + 2 * (m["lambda"] * row["g_fit"]) ** 2 for row in m["rows"])
        print(f"{m['run']}: h {m['h']:.6g}, t {m['time']:.4g}, {len(m['rows'])} points, largest "
              f"trA {max(row['trA'] for row in m['rows']):.4f} (P1), "
              f"{max(row['trA_fit'] for row in m['rows']):.4f} (fit), wall value {wall:.4f} (g_fit)")
    print(f"{'trA':8} {'gamma':9} " + " ".join(f"{'max h=' + format(m['h'], '.4g'):>13} "
                                               f"{'rms':>9}" for m in ms) + "  orders max / rms")
    for pair in PAIRS:
        orders = []
        for c, f, mc, mf in zip(ss, ss[1:], ms, ms[1:]):
            ratio = math.log(mc["h"] / mf["h"])
            if ratio == 0.0:  # the same grid (another setting): no order
                orders.append("-")
                continue
            orders.append(" / ".join(f"{math.log(c[pair][k] / f[pair][k]) / ratio:.2f}"
                                     for k in (0, 1)))
        print(f"{pair[0]:8} {pair[1]:9} " + " ".join(f"{s[pair][0]:13.4e} {s[pair][1]:9.3e}"
                                                     for s in ss) + "  " + ", ".join(orders))
    if a.csv:
        with open(a.csv, "w") as out:
            keys = [k for k in ms[0]["rows"][0]]
            out.write("run,h," + ",".join(keys) + "\n")
            for m in ms:
                for row in m["rows"]:
                    out.write(f"{m['run']},{m['h']}," + ",".join(f"{row[k]:.10g}" for k in keys)
                              + "\n")


if __name__ == "__main__":
    main()
