#!/usr/bin/python3
"""Prototypes of the particle boundary on the engine's discretization (issue 33, point 5).

Steady Stokes flow past a fixed disk in a channel, solved directly (SuperLU) on the engine's
elements: P1-iso-P2 velocity on the h-triangles of a uniform grid (SW-NE diagonals), P1 pressure on
the 2h macro-triangles, viscous form eta grad u : grad v, inflow, walls and a do-nothing outflow.
Three treatments of the disk, compared over sub-grid positions of its centre:

  dlm    the engine's default: collocation multipliers on the true circle (N_b = floor(2 pi R /
         (c h)) boundary points, interior lattice points at least sqrt(2) h from them), the velocity
         read at each point by the P2 basis of its macro-triangle (particles/collocation_points.h).
  sharp  sharp-edge extension (Barbeau, Etienne, Beguin & Blais, J. Comput. Phys. 2022, in Lethe):
         the momentum rows of the velocity nodes inside the disk near the circle are replaced by an
         extrapolation along the normal, u_g = L0 U_b + L1 u(x_b + s n) + L2 u(x_b + 2 s n) (quadratic
         Lagrange in the normal coordinate; u at the two fluid points by the P2 basis of their
         macro-triangle); deeper nodes are rigid. The fluid rows keep the full stencils.
  cut    cut-element quadrature with Nitsche's boundary condition (Burman & Hansbo): the viscous and
         divergence forms integrated over the fluid part of every cut h-triangle (the circle as the
         zero line of the linear interpolant of its distance), symmetric Nitsche terms on that chord,
         ghost penalties on the faces of cut elements (velocity gradient jumps; pressure gradient
         jumps on the macro-triangles).

The force on the disk is read the same way for all three, from the volume residual (a test function
equal to 1 on the disk and its cut layer): F = -sum_i Phi_i (eta K u + D^T p)_i.

Usage: boundary_prototypes.py METHOD D_OVER_H SHIFT... [--key value]; prints one CSV line per
shift: method, D/h, shift (units of h), F_x, F_y, unknowns, CPU seconds.
       boundary_prototypes.py table CSV... [--reference F]: per method and D/h, F_x moved back to the
shift 0 position with the slope of the 2h shift (the same discrete geometry, so the difference is
physical), then the mean, the spread (max - min) and the largest error over the shifts in [0, 2h),
and the observed orders between successive D/h. Results: docs/evidence/cut_cell_boundary.md, "A second-order
boundary: the prototypes" (issue 33).
"""
import argparse
import math
import sys
import time

import numpy as np
import scipy.sparse as sp
import scipy.sparse.linalg as spla


class Grid:
    """Velocity nodes (i, j), i = 0..nx, on spacing h; pressure nodes on every second node."""

    def __init__(self, length, height, h):
        self.h = h
        self.nx = int(round(length / h))
        self.ny = int(round(height / h))
        assert self.nx % 2 == 0 and self.ny % 2 == 0, "the 2h macro-grid needs even cell counts"
        self.n = (self.nx + 1) * (self.ny + 1)
        self.px, self.py = self.nx // 2, self.ny // 2
        self.np = (self.px + 1) * (self.py + 1)
        i, j = np.meshgrid(np.arange(self.nx + 1), np.arange(self.ny + 1))
        self.x = (i * h).ravel().astype(float)
        self.y = (j * h).ravel().astype(float)
        self.i = i.ravel()
        self.j = j.ravel()
        # h-triangles: square (i, j) below (0, 1, 2) and above (0, 2, 3) its SW-NE diagonal
        si, sj = np.meshgrid(np.arange(self.nx), np.arange(self.ny))
        si, sj = si.ravel(), sj.ravel()
        n00 = self.vid(si, sj)
        n10 = self.vid(si + 1, sj)
        n11 = self.vid(si + 1, sj + 1)
        n01 = self.vid(si, sj + 1)
        self.tri = np.concatenate([np.stack([n00, n10, n11], 1), np.stack([n00, n11, n01], 1)])
        self.area = 0.5 * h * h
        self.grad = self._gradients(self.tri)

    def vid(self, i, j):
        return j * (self.nx + 1) + i

    def pid(self, i, j):
        return j * (self.px + 1) + i

    def _gradients(self, tri):
        x = self.x[tri]
        y = self.y[tri]
        twice = (x[:, 1] - x[:, 0]) * (y[:, 2] - y[:, 0]) - (x[:, 2] - x[:, 0]) * (y[:, 1] - y[:, 0])
        g = np.zeros((len(tri), 3, 2))
        for k in range(3):
            k1, k2 = (k + 1) % 3, (k + 2) % 3
            g[:, k, 0] = (y[:, k1] - y[:, k2]) / twice
            g[:, k, 1] = (x[:, k2] - x[:, k1]) / twice
        return g

    def macro(self, px, py):
        """Macro-triangle of points: (3 pressure nodes, barycentric weights, 6 P2 velocity nodes)."""
        H = 2 * self.h
        I = np.clip(np.floor(px / H).astype(int), 0, self.px - 1)
        J = np.clip(np.floor(py / H).astype(int), 0, self.py - 1)
        xi = px / H - I
        eta = py / H - J
        lower = xi >= eta
        # vertices in macro-node units
        a = np.stack([I, J], 1)
        b = np.where(lower[:, None], np.stack([I + 1, J], 1), np.stack([I + 1, J + 1], 1))
        c = np.where(lower[:, None], np.stack([I + 1, J + 1], 1), np.stack([I, J + 1], 1))
        l0 = np.where(lower, 1 - xi, 1 - eta)
        l1 = np.where(lower, xi - eta, xi)
        l2 = np.where(lower, eta, eta - xi)
        pn = np.stack([self.pid(a[:, 0], a[:, 1]), self.pid(b[:, 0], b[:, 1]),
                       self.pid(c[:, 0], c[:, 1])], 1)
        lam = np.stack([l0, l1, l2], 1)
        va = 2 * a
        vb = 2 * b
        vc = 2 * c
        vn = np.stack([self.vid(va[:, 0], va[:, 1]), self.vid(vb[:, 0], vb[:, 1]),
                       self.vid(vc[:, 0], vc[:, 1]),
                       self.vid((va[:, 0] + vb[:, 0]) // 2, (va[:, 1] + vb[:, 1]) // 2),
                       self.vid((vb[:, 0] + vc[:, 0]) // 2, (vb[:, 1] + vc[:, 1]) // 2),
                       self.vid((vc[:, 0] + va[:, 0]) // 2, (vc[:, 1] + va[:, 1]) // 2)], 1)
        return pn, lam, vn

    def p2_weights(self, px, py):
        _, lam, vn = self.macro(px, py)
        l0, l1, l2 = lam[:, 0], lam[:, 1], lam[:, 2]
        w = np.stack([l0 * (2 * l0 - 1), l1 * (2 * l1 - 1), l2 * (2 * l2 - 1),
                      4 * l0 * l1, 4 * l1 * l2, 4 * l2 * l0], 1)
        return vn, w

    def p1_weights(self, px, py):
        """P1 basis of the h-triangle holding each point (the P1-iso-P2 field itself)."""
        h = self.h
        i = np.clip(np.floor(px / h).astype(int), 0, self.nx - 1)
        j = np.clip(np.floor(py / h).astype(int), 0, self.ny - 1)
        xi = px / h - i
        eta = py / h - j
        lower = xi >= eta
        n00, n10, n11, n01 = self.vid(i, j), self.vid(i + 1, j), self.vid(i + 1, j + 1), self.vid(i, j + 1)
        vn = np.where(lower[:, None], np.stack([n00, n10, n11], 1), np.stack([n00, n11, n01], 1))
        w = np.where(lower[:, None], np.stack([1 - xi, xi - eta, eta], 1),
                     np.stack([1 - eta, xi, eta - xi], 1))
        return vn, w


def coo(rows, cols, vals, shape):
    return sp.csr_matrix((np.ravel(vals), (np.ravel(rows), np.ravel(cols))), shape=shape)


def stokes_forms(g, weights=None, centroids=None, tris=None):
    """eta = 1 Laplacian K (n x n) and divergence D (np x 2n), D u = -int q div u, over triangles
    `tris` with the given (fluid) areas and centroids (default: every h-triangle, whole)."""
    if tris is None:
        tris = np.arange(len(g.tri))
    tri = g.tri[tris]
    grad = g.grad[tris]
    area = np.full(len(tris), g.area) if weights is None else weights
    if centroids is None:
        cx = g.x[tri].mean(1)
        cy = g.y[tri].mean(1)
    else:
        cx, cy = centroids
    kv = area[:, None, None] * np.einsum("tad,tbd->tab", grad, grad)
    K = coo(np.repeat(tri, 3, 1), np.tile(tri, (1, 3)), kv, (g.n, g.n))
    pn, lam, _ = g.macro(cx, cy)
    rows, cols, vals = [], [], []
    for c in range(2):
        # -area * q(centroid) * d_c phi_n
        rows.append(np.repeat(pn, 3, 1))
        cols.append(np.tile(tri + c * g.n, (1, 3)))
        vals.append(-area[:, None] * (lam[:, :, None] * grad[:, None, :, c]).reshape(len(tri), 9))
    D = coo(np.concatenate(rows, 1), np.concatenate(cols, 1), np.concatenate(vals, 1),
            (g.np, 2 * g.n))
    return K, D


class Scene:
    def __init__(self, args, shift):
        self.eta = args.viscosity
        self.length, self.height = args.size
        self.radius = 0.5 * args.diameter
        self.h = args.diameter / args.d_over_h
        self.center = np.array([args.center[0] + shift * self.h, args.center[1]])
        self.umax = args.umax


def boundary_rows(g, sc):
    """Dirichlet velocity dofs (inflow profile, walls) and their values."""
    left = g.i == 0
    wall = (g.j == 0) | (g.j == g.ny)
    nodes = np.flatnonzero(left | wall)
    H = sc.height
    ux = np.where(wall[nodes], 0.0, 4 * sc.umax * g.y[nodes] * (H - g.y[nodes]) / H ** 2)
    dofs = np.concatenate([nodes, nodes + g.n])
    vals = np.concatenate([ux, np.zeros(len(nodes))])
    return dofs, vals


def replace_rows(A, rhs, dofs, R, vals):
    """Rows `dofs` of A replaced by the rows of R (same count), right-hand side by vals."""
    keep = np.ones(A.shape[0])
    keep[dofs] = 0.0
    P = coo(dofs, np.arange(len(dofs)), np.ones(len(dofs)), (A.shape[0], len(dofs)))
    A = sp.diags(keep) @ A + P @ R
    rhs = rhs.copy()
    rhs[dofs] = vals
    return A.tocsc(), rhs


def identity_rows(dofs, size):
    return coo(np.arange(len(dofs)), dofs, np.ones(len(dofs)), (len(dofs), size))


def disk_force(g, sc, K, D, u, p, reach, C=None):
    """F = -sum over nodes within R + reach of (eta K u + C(u) u + D^T p), per component."""
    r = np.hypot(g.x - sc.center[0], g.y - sc.center[1])
    phi = (r < sc.radius + reach).astype(float)
    Ku = K * sc.eta if C is None else K * sc.eta + C
    res = np.concatenate([Ku @ u[:g.n], Ku @ u[g.n:]]) + D.T @ p
    return -phi @ res[:g.n], -phi @ res[g.n:]


def convection(g, tri, grad, mloc, w):
    """int (w . grad u) v over the triangles `tri` with local mass matrices mloc (rho = 1)."""
    W = np.stack([w[:g.n][tri], w[g.n:][tri]], 2)
    adv = np.einsum("tkd,tjd->tkj", W, grad)
    return coo(np.repeat(tri, 3, 1), np.tile(tri, (1, 3)), np.einsum("tik,tkj->tij", mloc, adv),
               (g.n, g.n))


def picard(assemble, args, nu):
    """Stokes, then (Navier-Stokes) Oseen iterations on the advecting velocity."""
    sol = solve(*assemble(None))
    if not args.navier_stokes:
        return sol, None
    for _ in range(args.picard_max):
        w = sol[:nu]
        new = solve(*assemble(w))
        change = np.linalg.norm(new[:nu] - w) / np.linalg.norm(new[:nu])
        sol = new
        if change < args.picard_tol:
            return sol, w
    raise RuntimeError(f"Picard iterations did not converge: change {change:.2e}")


def solve(A, rhs):
    lu = spla.splu(A.tocsc(), permc_spec="COLAMD", diag_pivot_thresh=1.0)
    return lu.solve(rhs)


def run_dlm(g, sc, args):
    K, D = stokes_forms(g)
    R, h = sc.radius, g.h
    nb = max(3, int(math.floor(2 * math.pi * R / (args.spacing * h) + 1e-9)))
    ang = 2 * math.pi * np.arange(nb) / nb
    pts = [np.stack([R * np.cos(ang), R * np.sin(ang)], 1)]
    reach = int(math.ceil(R / h))
    a, b = np.meshgrid(np.arange(-reach, reach + 1), np.arange(-reach, reach + 1))
    lat = np.stack([a.ravel() * h, b.ravel() * h], 1)
    lat = lat[np.hypot(lat[:, 0], lat[:, 1]) < R]
    dmin = np.min(np.hypot(lat[:, None, 0] - pts[0][None, :, 0], lat[:, None, 1] - pts[0][None, :, 1]), 1)
    pts.append(lat[dmin >= math.sqrt(2) * h])
    pts = np.concatenate(pts) + sc.center
    vn, w = g.p2_weights(pts[:, 0], pts[:, 1])
    m = len(pts)
    E = coo(np.repeat(np.arange(m), 6), vn, w, (m, g.n))
    Z = sp.csr_matrix((m, g.n))
    N = 2 * g.n + g.np + 2 * m
    mloc = np.broadcast_to(g.area / 12 * (1 + np.eye(3)), (len(g.tri), 3, 3))
    dofs, vals = boundary_rows(g, sc)

    def assemble(w):
        Km = sc.eta * K if w is None else sc.eta * K + convection(g, g.tri, g.grad, mloc, w)
        A = sp.bmat([[Km, None, D[:, :g.n].T, E.T, None],
                     [None, Km, D[:, g.n:].T, None, E.T],
                     [D[:, :g.n], D[:, g.n:], None, None, None],
                     [E, Z, None, None, None],
                     [Z, E, None, None, None]], format="csr")
        A = A + sp.diags(np.concatenate([np.zeros(2 * g.n), -1e-12 * np.ones(g.np), np.zeros(2 * m)]))
        return replace_rows(A, np.zeros(N), dofs, identity_rows(dofs, N), vals)

    s, w = picard(assemble, args, 2 * g.n)
    u, p = s[:2 * g.n], s[2 * g.n:2 * g.n + g.np]
    C = None if w is None else convection(g, g.tri, g.grad, mloc, w)
    return disk_force(g, sc, K, D, u, p, 4 * h, C), N


def run_sharp(g, sc, args):
    K, D = stokes_forms(g)
    h = g.h
    dx, dy = g.x - sc.center[0], g.y - sc.center[1]
    r = np.hypot(dx, dy)
    phi = r - sc.radius
    inside = phi < 0
    # ghost nodes: inside nodes within band * h of the circle (band 0: those of cut h-triangles)
    if args.band > 0:
        ghost = inside & (phi > -args.band * h)
    else:
        tin = inside[g.tri]
        cut = tin.any(1) & ~tin.all(1)
        ghost = np.zeros(g.n, bool)
        ghost[g.tri[cut][tin[cut]]] = True
    rigid = inside & ~ghost
    gi = np.flatnonzero(ghost)
    nx, ny = dx[gi] / r[gi], dy[gi] / r[gi]
    d = -phi[gi]
    s = args.sample * h
    bx, by = sc.center[0] + sc.radius * nx, sc.center[1] + sc.radius * ny
    if args.order == 2:
        L0 = (d + s) * (d + 2 * s) / (2 * s * s)
        L = [-d * (d + 2 * s) / (s * s), d * (d + s) / (2 * s * s)]
    else:
        L0 = (d + s) / s
        L = [-d / s]
    rows, cols, vals = [np.arange(len(gi))], [gi], [np.ones(len(gi))]
    interp = g.p2_weights if args.interp == "p2" else g.p1_weights
    for k, Lk in enumerate(L, start=1):
        vn, w = interp(bx + k * s * nx, by + k * s * ny)
        rows.append(np.repeat(np.arange(len(gi)), vn.shape[1]))
        cols.append(vn.ravel())
        vals.append((-Lk[:, None] * w).ravel())
    Cg = coo(np.concatenate(rows), np.concatenate(cols), np.concatenate(vals), (len(gi), g.n))
    # a fixed disk: U_b = 0, so L0 multiplies zero
    N = 2 * g.n + g.np
    A = sp.bmat([[sc.eta * K, None, D[:, :g.n].T],
                 [None, sc.eta * K, D[:, g.n:].T],
                 [D[:, :g.n], D[:, g.n:], None]], format="csr")
    rhs = np.zeros(N)
    bdofs, bvals = boundary_rows(g, sc)
    ri = np.flatnonzero(rigid)
    Zg = sp.csr_matrix((len(gi), g.n))
    Rows = sp.vstack([identity_rows(bdofs, N),
                      sp.hstack([Cg, Zg, sp.csr_matrix((len(gi), g.np))]),
                      sp.hstack([Zg, Cg, sp.csr_matrix((len(gi), g.np))]),
                      identity_rows(np.concatenate([ri, ri + g.n]), N)]).tocsr()
    dofs = np.concatenate([bdofs, gi, gi + g.n, ri, ri + g.n])
    vals = np.concatenate([bvals, np.zeros(2 * len(gi) + 2 * len(ri))])
    if args.pressure == "extend":
        # pressure nodes inside the disk: their continuity rows replaced by the same quadratic
        # extrapolation of p along the normal (samples 2h apart, read by the macro P1 basis); the
        # deep ones (more than 3h inside) p = 0
        ppx = (np.arange(g.np) % (g.px + 1)) * 2 * h - sc.center[0]
        ppy = (np.arange(g.np) // (g.px + 1)) * 2 * h - sc.center[1]
        pr = np.hypot(ppx, ppy)
        pphi = pr - sc.radius
        pg = np.flatnonzero((pphi < 0) & (pphi > -3 * h))
        pdead = np.flatnonzero(pphi <= -3 * h)
        pnx, pny, dp, sp_ = ppx[pg] / pr[pg], ppy[pg] / pr[pg], -pphi[pg], 2 * h
        Lp = [-dp * (dp + 2 * sp_) / (sp_ * sp_), dp * (dp + sp_) / (2 * sp_ * sp_)]
        rows, cols, vals_p = [np.arange(len(pg))], [pg + 2 * g.n], [np.ones(len(pg))]
        for k, Lk in enumerate(Lp, start=1):
            pn, lam, _ = g.macro(sc.center[0] + (sc.radius + k * sp_) * pnx,
                                 sc.center[1] + (sc.radius + k * sp_) * pny)
            rows.append(np.repeat(np.arange(len(pg)), 3))
            cols.append((pn + 2 * g.n).ravel())
            vals_p.append((-Lk[:, None] * lam).ravel())
        Cp = coo(np.concatenate(rows), np.concatenate(cols), np.concatenate(vals_p), (len(pg), N))
        Rows = sp.vstack([Rows, Cp, identity_rows(pdead + 2 * g.n, N)]).tocsr()
        dofs = np.concatenate([dofs, pg + 2 * g.n, pdead + 2 * g.n])
        vals = np.concatenate([vals, np.zeros(len(pg) + len(pdead))])
    else:
        # pressure nodes whose whole support is replaced: p = 0, their continuity row dropped
        replaced = np.zeros(2 * g.n, bool)
        replaced[dofs] = True
        Dc = D.tocsr()
        free = Dc.multiply(~replaced[None, :]).astype(bool).sum(1).A.ravel() == 0
        dead = np.flatnonzero(free) + 2 * g.n
        Rows = sp.vstack([Rows, identity_rows(dead, N)]).tocsr()
        dofs = np.concatenate([dofs, dead])
        vals = np.concatenate([vals, np.zeros(len(dead))])
    A, rhs = replace_rows(A, rhs, dofs, Rows, vals)
    sol = solve(A, rhs)
    u, p = sol[:2 * g.n], sol[2 * g.n:]
    return disk_force(g, sc, K, D, u, p, 4 * h), N


def clip_fluid(xs, ys, ph):
    """Fluid part (phi >= 0 of the linear interpolant) of one triangle: polygon and chord."""
    poly, chord = [], []
    for k in range(3):
        k1 = (k + 1) % 3
        if ph[k] >= 0:
            poly.append((xs[k], ys[k]))
        if (ph[k] >= 0) != (ph[k1] >= 0):
            t = ph[k] / (ph[k] - ph[k1])
            pt = (xs[k] + t * (xs[k1] - xs[k]), ys[k] + t * (ys[k1] - ys[k]))
            poly.append(pt)
            chord.append(pt)
    return poly, chord


def polygon_area_centroid(poly):
    a = cx = cy = 0.0
    n = len(poly)
    for k in range(n):
        x0, y0 = poly[k]
        x1, y1 = poly[(k + 1) % n]
        c = x0 * y1 - x1 * y0
        a += c
        cx += (x0 + x1) * c
        cy += (y0 + y1) * c
    a *= 0.5
    return abs(a), (cx / (6 * a), cy / (6 * a))


def polygon_mass(poly, x0, y0, grad):
    """int phi_i phi_k over a polygon inside a triangle (fan, edge-midpoint rule: exact)."""
    m = np.zeros((3, 3))
    for k in range(1, len(poly) - 1):
        a, b, c = np.array(poly[0]), np.array(poly[k]), np.array(poly[k + 1])
        area = 0.5 * abs((b[0] - a[0]) * (c[1] - a[1]) - (c[0] - a[0]) * (b[1] - a[1]))
        for q in (0.5 * (a + b), 0.5 * (b + c), 0.5 * (c + a)):
            ph = grad @ (q - np.array([x0, y0]))
            ph[0] += 1.0
            m += area / 3 * np.outer(ph, ph)
    return m


def face_jumps(tri, grad, active, touched):
    """Edges shared by two active triangles, at least one of them `touched`: the jump of the
    normal derivative of each basis function across the edge (rows: nodes, values), length."""
    ntri = len(tri)
    edges = np.concatenate([tri[:, [0, 1]], tri[:, [1, 2]], tri[:, [2, 0]]])
    owner = np.tile(np.arange(ntri), 3)
    key = np.sort(edges, 1)
    order = np.lexsort((key[:, 1], key[:, 0]))
    ks = key[order]
    same = np.all(ks[1:] == ks[:-1], 1)
    first = order[:-1][same]
    second = order[1:][same]
    t1, t2 = owner[first], owner[second]
    keep = active[t1] & active[t2] & (touched[t1] | touched[t2])
    return key[first[keep]], t1[keep], t2[keep]


def ghost_penalty(g_tri, g_grad, coords, active, touched, nsize, scale):
    ekey, t1, t2 = face_jumps(g_tri, g_grad, active, touched)
    xa, ya = coords[0][ekey[:, 0]], coords[1][ekey[:, 0]]
    xb, yb = coords[0][ekey[:, 1]], coords[1][ekey[:, 1]]
    ln = np.hypot(xb - xa, yb - ya)
    nrm = np.stack([(yb - ya) / ln, -(xb - xa) / ln], 1)
    # jump vector over the 6 node slots of the two triangles
    nodes = np.concatenate([g_tri[t1], g_tri[t2]], 1)
    j1 = np.einsum("tkd,td->tk", g_grad[t1], nrm)
    j2 = -np.einsum("tkd,td->tk", g_grad[t2], nrm)
    jv = np.concatenate([j1, j2], 1)
    vals = scale * ln[:, None, None] * jv[:, :, None] * jv[:, None, :]
    return coo(np.repeat(nodes, 6, 1), np.tile(nodes, (1, 6)), vals, (nsize, nsize))


def run_cut(g, sc, args):
    h = g.h
    phin = np.hypot(g.x - sc.center[0], g.y - sc.center[1]) - sc.radius
    phin[np.abs(phin) < 1e-9 * h] = 0.0  # a node on the circle, up to round-off
    pt = phin[g.tri]
    full = (pt >= 0).all(1)
    cut = (pt > 0).any(1) & ~full  # a triangle that only touches the circle is inside
    active = full | cut
    ft = np.flatnonzero(full)
    ct = np.flatnonzero(cut)
    areas, cxs, cys = [], [], []
    seg_a, seg_b, seg_n = [], [], []
    mloc_cut = []
    for t in ct:
        xs, ys = g.x[g.tri[t]], g.y[g.tri[t]]
        poly, chord = clip_fluid(xs, ys, pt[t])
        a, (cx, cy) = polygon_area_centroid(poly)
        mloc_cut.append(polygon_mass(poly, xs[0], ys[0], g.grad[t]))
        areas.append(a)
        cxs.append(cx)
        cys.append(cy)
        gphi = pt[t] @ g.grad[t]  # gradient of the linear distance: points into the fluid
        seg_a.append(chord[0])
        seg_b.append(chord[1])
        seg_n.append(-gphi / np.linalg.norm(gphi))
    areas = np.array(areas)
    tris = np.concatenate([ft, ct])
    w = np.concatenate([np.full(len(ft), g.area), areas])
    cx = np.concatenate([g.x[g.tri[ft]].mean(1), cxs])
    cy = np.concatenate([g.y[g.tri[ft]].mean(1), cys])
    K, D = stokes_forms(g, w, (cx, cy), tris)
    # Nitsche on the chords: two-point Gauss
    seg_a, seg_b, seg_n = np.array(seg_a), np.array(seg_b), np.array(seg_n)
    ln = np.linalg.norm(seg_b - seg_a, axis=1)
    tri = g.tri[ct]
    grad = g.grad[ct]
    dn = np.einsum("tkd,td->tk", grad, seg_n)  # d_n phi_k on the chord
    Nit = sp.csr_matrix((g.n, g.n))
    Pn = [sp.csr_matrix((g.np, g.n)), sp.csr_matrix((g.np, g.n))]
    gam = args.nitsche
    for gp in (0.5 - 0.5 / math.sqrt(3), 0.5 + 0.5 / math.sqrt(3)):
        qx = seg_a[:, 0] + gp * (seg_b[:, 0] - seg_a[:, 0])
        qy = seg_a[:, 1] + gp * (seg_b[:, 1] - seg_a[:, 1])
        # P1 basis of the cut triangle at the Gauss point
        x0, y0 = g.x[tri[:, 0]], g.y[tri[:, 0]]
        phiq = np.stack([1 + grad[:, 0, 0] * (qx - x0) + grad[:, 0, 1] * (qy - y0),
                         grad[:, 1, 0] * (qx - x0) + grad[:, 1, 1] * (qy - y0),
                         grad[:, 2, 0] * (qx - x0) + grad[:, 2, 1] * (qy - y0)], 1)
        wq = 0.5 * ln
        # -(d_n u) v - (d_n v) u + gam/h u v
        m = wq[:, None, None] * (-phiq[:, :, None] * dn[:, None, :] - dn[:, :, None] * phiq[:, None, :]
                                 + gam / h * phiq[:, :, None] * phiq[:, None, :])
        Nit = Nit + coo(np.repeat(tri, 3, 1), np.tile(tri, (1, 3)), m, (g.n, g.n))
        pn, lam, _ = g.macro(qx, qy)
        for c in range(2):
            # continuity row q: + int q u.n ; its transpose gives + int p v.n in momentum
            v = wq[:, None, None] * lam[:, :, None] * phiq[:, None, :] * seg_n[:, c][:, None, None]
            Pn[c] = Pn[c] + coo(np.repeat(pn, 3, 1), np.tile(tri, (1, 3)), v, (g.np, g.n))
    touched = np.zeros(len(g.tri), bool)
    touched[ct] = True
    J = ghost_penalty(g.tri, g.grad, (g.x, g.y), active, touched, g.n, args.ghost * h)
    # pressure ghost penalty on the macro-triangles that hold a cut h-triangle
    ptri, pgrad, pactive, ptouched = macro_mesh(g, active, cut)
    px = (np.arange(g.np) % (g.px + 1)) * 2 * h
    py = (np.arange(g.np) // (g.px + 1)) * 2 * h
    Jp = ghost_penalty(ptri, pgrad, (px, py), pactive, ptouched, g.np, args.ghost_p * (2 * h) ** 3)
    Du = D + sp.hstack([Pn[0], Pn[1]])
    Ks = sc.eta * (K + Nit + J)
    N = 2 * g.n + g.np
    mloc = np.concatenate([np.broadcast_to(g.area / 12 * (1 + np.eye(3)), (len(ft), 3, 3)),
                           np.array(mloc_cut).reshape(-1, 3, 3)])
    bdofs, bvals = boundary_rows(g, sc)
    vact = np.zeros(g.n, bool)
    vact[g.tri[active]] = True
    dead_v = np.flatnonzero(~vact)
    pact = np.zeros(g.np, bool)
    pact[ptri[pactive]] = True
    dead_p = np.flatnonzero(~pact)
    dofs = np.concatenate([bdofs, dead_v, dead_v + g.n, dead_p + 2 * g.n])
    vals = np.concatenate([bvals, np.zeros(2 * len(dead_v) + len(dead_p))])

    def assemble(w):
        Km = Ks if w is None else Ks + convection(g, g.tri[tris], g.grad[tris], mloc, w)
        A = sp.bmat([[Km, None, Du[:, :g.n].T],
                     [None, Km, Du[:, g.n:].T],
                     [Du[:, :g.n], Du[:, g.n:], -Jp / sc.eta]], format="csr")
        return replace_rows(A, np.zeros(N), dofs, identity_rows(dofs, N), vals)

    sol, w = picard(assemble, args, 2 * g.n)
    u, p = sol[:2 * g.n], sol[2 * g.n:]
    C = None if w is None else convection(g, g.tri[tris], g.grad[tris], mloc, w)
    return disk_force(g, sc, K, D, u, p, 1.5 * h, C), N


def macro_mesh(g, active, cut):
    """The 2h triangles (SW-NE), their P1 gradients, and which hold an active / cut h-triangle."""
    si, sj = np.meshgrid(np.arange(g.px), np.arange(g.py))
    si, sj = si.ravel(), sj.ravel()
    n00, n10, n11, n01 = g.pid(si, sj), g.pid(si + 1, sj), g.pid(si + 1, sj + 1), g.pid(si, sj + 1)
    ptri = np.concatenate([np.stack([n00, n10, n11], 1), np.stack([n00, n11, n01], 1)])
    H = 2 * g.h
    px = (ptri % (g.px + 1)) * H
    py = (ptri // (g.px + 1)) * H
    twice = (px[:, 1] - px[:, 0]) * (py[:, 2] - py[:, 0]) - (px[:, 2] - px[:, 0]) * (py[:, 1] - py[:, 0])
    pgrad = np.zeros((len(ptri), 3, 2))
    for k in range(3):
        k1, k2 = (k + 1) % 3, (k + 2) % 3
        pgrad[:, k, 0] = (py[:, k1] - py[:, k2]) / twice
        pgrad[:, k, 1] = (px[:, k2] - px[:, k1]) / twice
    # h-triangle -> macro-triangle through its centroid
    cx = g.x[g.tri].mean(1)
    cy = g.y[g.tri].mean(1)
    I = np.floor(cx / H).astype(int)
    Jm = np.floor(cy / H).astype(int)
    lower = (cx / H - I) >= (cy / H - Jm)
    mt = np.where(lower, 0, len(si)) + Jm * g.px + I
    pactive = np.zeros(len(ptri), bool)
    ptouched = np.zeros(len(ptri), bool)
    pactive[mt[active]] = True
    ptouched[mt[cut]] = True
    return ptri, pgrad, pactive, ptouched


def table(argv):
    ap = argparse.ArgumentParser()
    ap.add_argument("csv", nargs="+")
    ap.add_argument("--reference", type=float, default=None)
    a = ap.parse_args(argv)
    runs = {}
    for path in a.csv:
        for line in open(path):
            f = line.strip().split(",")
            if len(f) < 7 or f[0] not in ("dlm", "sharp", "cut", "engine"):
                continue
            runs.setdefault((f[0], float(f[1])), {})[float(f[2])] = (float(f[3]), float(f[6]))
    prev = {}
    for (method, d), byshift in sorted(runs.items()):
        if 0.0 not in byshift or 2.0 not in byshift:
            print(f"{method} D/h {d:g}: needs the shifts 0 and 2 for the slope")
            continue
        slope = (byshift[2.0][0] - byshift[0.0][0]) / 2.0  # per unit of shift
        shifts = sorted(s for s in byshift if s < 2.0)
        fx = np.array([byshift[s][0] - slope * s for s in shifts])
        cpu = np.mean([byshift[s][1] for s in shifts])
        mean = fx.mean()
        spread = (fx.max() - fx.min()) / mean
        line = (f"{method} D/h {d:g} shifts {' '.join(f'{s:g}' for s in shifts)}: "
                f"F_x {' '.join(f'{v:.5f}' for v in fx)}; mean {mean:.5f}, spread {100 * spread:.3f} %")
        if a.reference:
            err = (fx - a.reference) / a.reference
            worst = np.max(np.abs(err))
            line += (f", mean error {100 * (mean / a.reference - 1):+.3f} %, worst {100 * worst:.3f} %")
            if method in prev:
                d0, m0, w0, s0 = prev[method]
                r = math.log(d / d0)
                line += (f"; orders: mean {math.log(abs(m0 / a.reference - 1) / abs(mean / a.reference - 1)) / r:.2f}, "
                         f"worst {math.log(w0 / worst) / r:.2f}, spread {math.log(s0 / spread) / r:.2f}")
            prev[method] = (d, mean, worst, spread)
        line += f"; slope {slope / (0.1 / d):.3f} per unit x; {cpu:.2f} CPU s a solve"
        print(line)


def main():
    if len(sys.argv) > 1 and sys.argv[1] == "table":
        return table(sys.argv[2:])
    ap = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    ap.add_argument("method", choices=["dlm", "sharp", "cut"])
    ap.add_argument("d_over_h", type=float)
    ap.add_argument("shifts", type=float, nargs="+", help="centre shift along x in units of h")
    ap.add_argument("--size", type=float, nargs=2, default=[0.8, 0.4])
    ap.add_argument("--center", type=float, nargs=2, default=[0.2, 0.2])
    ap.add_argument("--diameter", type=float, default=0.1)
    ap.add_argument("--umax", type=float, default=0.3)
    ap.add_argument("--viscosity", type=float, default=1.0)
    ap.add_argument("--navier-stokes", action="store_true", help="steady Navier-Stokes (Picard)")
    ap.add_argument("--picard-max", type=int, default=40)
    ap.add_argument("--picard-tol", type=float, default=1e-8)
    ap.add_argument("--spacing", type=float, default=2.0, help="dlm: boundary point spacing c")
    ap.add_argument("--band", type=float, default=0.0,
                    help="sharp: ghost band depth in h (0: the inside nodes of cut h-triangles)")
    ap.add_argument("--sample", type=float, default=1.0, help="sharp: fluid sample spacing s / h")
    ap.add_argument("--order", type=int, default=2, help="sharp: extrapolation order 1 or 2")
    ap.add_argument("--interp", choices=["p2", "p1"], default="p2",
                    help="sharp: how the fluid points are read")
    ap.add_argument("--pressure", choices=["free", "extend"], default="free",
                    help="sharp: pressure nodes inside the disk free, or extended along the normal")
    ap.add_argument("--nitsche", type=float, default=20.0, help="cut: Nitsche penalty gamma")
    ap.add_argument("--ghost", type=float, default=0.1, help="cut: velocity ghost penalty")
    ap.add_argument("--ghost-p", type=float, default=0.01, help="cut: pressure ghost penalty")
    args = ap.parse_args()
    run = {"dlm": run_dlm, "sharp": run_sharp, "cut": run_cut}[args.method]
    for shift in args.shifts:
        sc = Scene(args, shift)
        g = Grid(sc.length, sc.height, sc.h)
        t0 = time.process_time()
        (fx, fy), n = run(g, sc, args)
        print(f"{args.method},{args.d_over_h:g},{shift:g},{fx:.7f},{fy:.7f},{n},"
              f"{time.process_time() - t0:.2f}", flush=True)


if __name__ == "__main__":
    sys.exit(main())
