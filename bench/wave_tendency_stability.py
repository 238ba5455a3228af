#!/usr/bin/env python3
"""Von Neumann bound of the wave step's tendency correction (engine/include/dlmfd/fluid/advection_wave.h).

One step of (33) + (34) for a Fourier mode of a constant velocity V on the uniform P1 mesh with both
diagonals (the mean of the SW-NE and NW-SE forms; pressure left out: the projection does not add
energy), in units h = dt = 1:
  s = u / (1 + nu K)                       (33), K the 5-point Laplacian, nu = nu dt / h^2 = c / Re_h
  r = s - u                                its tendency
  Q centred sub-steps of u_tt = -A u + L r from s with u_t(0) = L s + r   (A = M^-1 K_V, L = -M^-1 N(V, .))
  w = u(1) - r - phi / 2 (-A s - L L s)    (the compact-minus-wide term removed with the share phi)
with c = |V| dt / h, Re_h = |V| h / nu, Q = ceil(c / 0.5) (solvers.wave_max_courant). Prints, for
phi = 1, the largest Re_h at which max |w / u| <= 1 over the modes and 16 directions of V, as
c^3 Re_h = |V|^4 dt^3 / (nu h^2) (the engine's kWideFormBound is the smallest, 13.8), then checks
the engine's cap phi = min(1, kappa 13.8 / (c^3 Re_h)), kappa = 1/2, over a table of c and Re_h.
Pure Python, about a minute. Usage: bench/wave_tendency_stability.py
"""
import cmath
import math


def triangles(kind):
    """The triangles at node (0, 0): kind 'swne' (a, b, c), (a, c, d) or 'nwse' (a, b, d), (b, c, d)."""
    out = []
    for ci, cj in [(-1, -1), (0, -1), (-1, 0), (0, 0)]:
        a, b, c, d = (ci, cj), (ci + 1, cj), (ci + 1, cj + 1), (ci, cj + 1)
        out += [(a, b, c), (a, c, d)] if kind == "swne" else [(a, b, d), (b, c, d)]
    return [t for t in out if (0, 0) in t]


def gradients(t):
    (x0, y0), (x1, y1), (x2, y2) = t
    det = (x1 - x0) * (y2 - y0) - (x2 - x0) * (y1 - y0)
    g = [((y1 - y2) / det, (x2 - x1) / det), ((y2 - y0) / det, (x0 - x2) / det),
         ((y0 - y1) / det, (x1 - x0) / det)]
    return g, abs(det) / 2


def stencils(vx, vy):
    """Rows at (0, 0) of N(V, .) = V.G (vertex quadrature) and K_V, means over both diagonals."""
    n_row, kv_row = {}, {}
    for kind in ("swne", "nwse"):
        for t in triangles(kind):
            g, area = gradients(t)
            i = t.index((0, 0))
            for j, p in enumerate(t):
                n_row[p] = n_row.get(p, 0) + 0.5 * (area / 3) * (vx * g[j][0] + vy * g[j][1])
                kv_row[p] = kv_row.get(p, 0) + 0.5 * area * (vx * g[i][0] + vy * g[i][1]) * (
                    vx * g[j][0] + vy * g[j][1])
    return n_row, kv_row


def symbol(row, a, b):
    return sum(c * cmath.exp(1j * (a * p[0] + b * p[1])) for p, c in row.items())


def amplification(c, re_h, angle, phi, modes=32):
    q = max(1, math.ceil(c / 0.5 - 1e-12))
    tau = 1.0 / q
    n_row, kv_row = stencils(c * math.cos(angle), c * math.sin(angle))
    nu = c / re_h
    worst = 0.0
    for ia in range(modes + 1):
        for ib in range(modes + 1):
            a = -math.pi + 2 * math.pi * ia / modes
            b = -math.pi + 2 * math.pi * ib / modes
            el, a_op = -symbol(n_row, a, b), symbol(kv_row, a, b).real
            s = 1 / (1 + nu * (4 - 2 * math.cos(a) - 2 * math.cos(b)))
            r = s - 1
            u0, u1 = s, s + tau * (el * s + r) + tau * tau / 2 * (-a_op * s + el * r)
            for _ in range(1, q):
                u0, u1 = u1, 2 * u1 - u0 + tau * tau * (-a_op * u1 + el * r)
            w = u1 - r - phi * 0.5 * (-a_op * s - el * el * s)
            worst = max(worst, abs(w))
    return worst


ANGLES = [k * math.pi / 16 for k in range(16)]


def stable(c, re_h, phi):
    return max(amplification(c, re_h, angle, phi) for angle in ANGLES) <= 1 + 1e-9


print("phi = 1: largest stable Re_h (bisection)")
for c in [0.2, 0.4, 0.64, 0.8]:
    lo, hi = 1.0, 3000.0
    for _ in range(14):
        mid = math.sqrt(lo * hi)
        lo, hi = (mid, hi) if stable(c, mid, 1.0) else (lo, mid)
    print("  c %.2f  Re_h %8.2f  c^3 Re_h %.2f" % (c, lo, c ** 3 * lo))
print("the engine's cap, kappa = 1/2: max |w/u| - 1 (phi)")
for c in [0.1, 0.3, 0.5, 0.64, 0.8, 1.0]:
    cells = []
    for re_h in [3, 10, 30, 100, 300, 1000, 10000]:
        phi = min(1.0, 0.5 * 13.8 / (c ** 3 * re_h))
        g = max(amplification(c, re_h, angle, phi) for angle in ANGLES)
        cells.append("%.1e (%.2f)" % (g - 1, phi))
    print("  c %.2f " % c + " ".join(cells))
