#!/usr/bin/env python3
"""The steady A11 of an Oldroyd-B liquid on the lid of Fattal & Kupferman's cavity, stretching alone.

On the lid y = 1 the velocity is (u(x), 0), u = 16 x^2 (1 - x)^2 (the full ramp), so a material point
of the lid stays on it and A11 obeys, along x' = u(x),
    dA11/dt = 2 u'(x) A11 + 2 (du/dy) A12 - (A11 - 1) / lambda.
Leaving out the shear term (which only adds to A11 where A12 > 0), the steady solution with A11 = 1
at the upstream corner x = 0 is
    A11(x) = u(x)^2 int_0^x exp(-(T(x) - T(s)) / lambda) / (lambda u(s)^3) ds,
T(x) = int dx / u = (-1/x + 1/(1 - x) + 2 ln(x / (1 - x))) / 16 the travel time. The integrand peaks
where the material has come from, s ~ 1 / (96 lambda): near the corner, where it lingers (u ~ 16 s^2)
and is stretched on its way out by (u(x) / u(s))^2. Prints max over x of A11 and where, and s*.
Usage: bench/cavity_lid_stress.py   (docs/evidence/stability.md, "Representations: the lid-driven cavity")
"""
import math


def u(x):
    return 16.0 * x * x * (1.0 - x) ** 2


def travel(x):
    return (-1.0 / x + 1.0 / (1.0 - x) + 2.0 * math.log(x / (1.0 - x))) / 16.0


def a11(x, lam, n=4000, s0=1e-6):
    total, prev = 0.0, None
    for k in range(n + 1):
        s = s0 * (x / s0) ** (k / n)  # geometric: the integrand lives near s ~ 1 / (96 lambda)
        f = math.exp(-(travel(x) - travel(s)) / lam) / (lam * u(s) ** 3)
        if prev is not None:
            total += 0.5 * (f + prev[1]) * (s - prev[0])
        prev = (s, f)
    return u(x) ** 2 * total


print("| Wi | max A11 on the lid | at x | s* = 1 / (96 Wi) |")
print("|---|---|---|---|")
for lam in (0.5, 1.0, 2.0, 3.0):
    value, where = max((a11(0.01 * k, lam), 0.01 * k) for k in range(1, 100))
    print(f"| {lam:g} | {value:.3g} | {where:.2f} | {1 / (96 * lam):.2g} |")
