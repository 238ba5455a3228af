#!/usr/bin/env python3
"""Tables of bench/cavity_representations.sh from its results directories (h5dump for the fields).

For each run: status and end time (summary.json), max trA and min eig A over all steps
(diagnostics.csv), the kinetic energy E(t) = 1/2 int |u|^2 dx (trapezoid rule on the velocity
nodes) at each field snapshot, u on the vertical centre line x = 1/2 and v on y = 3/4 at t = 8.
Writes docs/stability/cavity.csv; prints Markdown tables: survival, and where standard, log and
sqrt all completed, their differences (E over all snapshots, relative; centre-line u at t = 8).
Usage: bench/cavity_table.py WORK
"""
import csv
import json
import os
import subprocess
import sys
import tempfile

work = sys.argv[1]


def field(path, name):
    """A snapshot dataset as a list of rows (row j: y = j h), read with h5dump."""
    with tempfile.NamedTemporaryFile("r", suffix=".txt") as tmp:
        subprocess.run(["h5dump", "-d", "/" + name, "-y", "-w", "0", "-m", "%.17g", "-o",
                        tmp.name, path], check=True, stdout=subprocess.DEVNULL)
        values = [float(x) for x in tmp.read().replace("\n", ",").split(",") if x.strip()]
    m = int(round(len(values) ** 0.5))
    return [values[j * m:(j + 1) * m] for j in range(m)]


def energy(u, v):
    m = len(u)
    h = 1.0 / (m - 1)
    e = 0.0
    for j in range(m):
        for i in range(m):
            w = (0.5 if j in (0, m - 1) else 1.0) * (0.5 if i in (0, m - 1) else 1.0)
            e += w * (u[j][i] ** 2 + v[j][i] ** 2)
    return 0.5 * e * h * h


rows = []
for line in open(os.path.join(work, "runs.txt")):
    name, h, dt, wi, rep, _ = line.rstrip("\n").split("|")
    d = os.path.join(work, name)
    try:
        s = json.load(open(os.path.join(d, "summary.json")))
    except (OSError, ValueError):
        s = {"status": "missing", "reason": "", "time": float("nan")}
    max_tr, min_eig = float("nan"), float("nan")
    try:
        diag = list(csv.DictReader(open(os.path.join(d, "diagnostics.csv"))))
        max_tr = max(float(r["max_trA"]) for r in diag)
        min_eig = min(float(r["min_eig_A"]) for r in diag)
    except (OSError, ValueError, KeyError):
        pass
    energies, centre_u, line_v, tr_at = {}, None, None, ""
    snaps = sorted(os.listdir(os.path.join(d, "fields"))) if os.path.isdir(os.path.join(d, "fields")) else []
    for snap in snaps:
        path = os.path.join(d, "fields", snap)
        step = int(snap[5:11])
        t = round(step * float(dt), 9)
        if t == 0 or abs(t - round(t)) > 1e-9:
            continue  # E at t = 1, 2, ..., 8
        u, v = field(path, "u"), field(path, "v")
        energies[int(round(t))] = energy(u, v)
        if int(round(t)) == 8:
            m = len(u)
            centre_u = [u[j][(m - 1) // 2] for j in range(m)]
            line_v = [v[3 * (m - 1) // 4][i] for i in range(m)]
            tr = field(path, "trA")
            jmax, imax = max(((j, i) for j in range(m) for i in range(m)), key=lambda p: tr[p[0]][p[1]])
            tr_at = f"({imax / (m - 1):.3g}, {jmax / (m - 1):.3g})"
    rows.append(dict(run=name, h=h, dt=dt, wi=wi, rep=rep, status=s.get("status"),
                     t_end=s.get("time"), max_trA=max_tr, min_eig_A=min_eig,
                     energies=energies, centre_u=centre_u, line_v=line_v, tr_at=tr_at,
                     reason=(s.get("reason") or "")[:120]))

os.makedirs("docs/stability", exist_ok=True)
with open("docs/stability/cavity.csv", "w", newline="") as f:
    w = csv.writer(f)
    w.writerow(["run", "h", "dt", "wi", "representation", "status", "t_end", "max_trA", "min_eig_A"] +
               [f"E_t{k}" for k in range(1, 9)] + ["min_u_centre_t8", "max_trA_at_t8", "reason"])
    for r in rows:
        w.writerow([r["run"], r["h"], r["dt"], r["wi"], r["rep"], r["status"], r["t_end"],
                    f"{r['max_trA']:.6g}", f"{r['min_eig_A']:.6g}"] +
                   [f"{r['energies'][k]:.6e}" if k in r["energies"] else "" for k in range(1, 9)] +
                   [f"{min(r['centre_u']):.6f}" if r["centre_u"] else "", r["tr_at"], r["reason"]])

reps = ["standard", "log", "sqrt"]
grids = sorted({(r["h"], r["dt"]) for r in rows}, key=lambda p: (-float(p[0]), -float(p[1])))
wis = sorted({r["wi"] for r in rows}, key=float)


def find(h, dt, wi, rep):
    return next(r for r in rows if (r["h"], r["dt"], r["wi"], r["rep"]) == (h, dt, wi, rep))


print("Survival (ok: to t = 8; else the time of failure), max trA, min eig A over the run:\n")
print("| h | dt | Wi | " + " | ".join(reps) + " |")
print("|---|---|---|" + "---|" * len(reps))
for h, dt in grids:
    for wi in wis:
        cells = []
        for rep in reps:
            r = find(h, dt, wi, rep)
            state = "ok" if r["status"] == "completed" else f"failed t={r['t_end']:.3g}"
            cells.append(f"{state}, trA {r['max_trA']:.3g}, eig {r['min_eig_A']:.2g}")
        print(f"| 1/{round(1 / float(h))} | {dt} | {wi} | " + " | ".join(cells) + " |")

print("\nWhere at least two representations completed: E(8), its last change (E(8) - E(7)) / E(8), "
      "min u on x = 1/2 at t = 8 (a dash: the run failed), the largest difference of E(t) (t = 1..8, "
      "relative) and of u on x = 1/2 at t = 8 from the log run, where max trA is at t = 8 (log run):\n")
print("| h | dt | Wi | E(8) std, log, sqrt | last change std, log, sqrt | min u(1/2, y) std, log, sqrt "
      "| max dE/E from log: std, sqrt | max du from log: std, sqrt | max trA at (x, y) |")
print("|---|---|---|---|---|---|---|---|---|")


def cell(r, text):
    return text(r) if r["status"] == "completed" and r["centre_u"] else "-"


for h, dt in grids:
    for wi in wis:
        rs = [find(h, dt, wi, rep) for rep in reps]
        done = [r for r in rs if r["status"] == "completed" and r["centre_u"]]
        log = rs[1]
        if len(done) < 2 or log not in done:
            continue
        e = [cell(r, lambda r: f"{r['energies'][8]:.4e}") for r in rs]
        change = [cell(r, lambda r: f"{(r['energies'][8] - r['energies'][7]) / r['energies'][8]:.1e}")
                  for r in rs]
        umin = [cell(r, lambda r: f"{min(r['centre_u']):.4f}") for r in rs]
        de = [cell(r, lambda r: f"{max(abs(r['energies'][k] - log['energies'][k]) / log['energies'][k] for k in range(1, 9)):.1e}")
              for r in (rs[0], rs[2])]
        du = [cell(r, lambda r: f"{max(abs(a - b) for a, b in zip(r['centre_u'], log['centre_u'])):.1e}")
              for r in (rs[0], rs[2])]
        print(f"| 1/{round(1 / float(h))} | {dt} | {wi} | " + ", ".join(e) + " | " + ", ".join(change) +
              " | " + ", ".join(umin) + " | " + ", ".join(de) + " | " + ", ".join(du) +
              f" | {log['tr_at']} |")

print("\nThe log runs that completed: E(t) at t = 1 ... 8:\n")
print("| h | dt | Wi | " + " | ".join(f"E({k})" for k in range(1, 9)) + " |")
print("|---|---|---|" + "---|" * 8)
for h, dt in grids:
    for wi in wis:
        r = find(h, dt, wi, "log")
        if r["status"] == "completed" and len(r["energies"]) == 8:
            print(f"| 1/{round(1 / float(h))} | {dt} | {wi} | " +
                  " | ".join(f"{r['energies'][k]:.4e}" for k in range(1, 9)) + " |")
