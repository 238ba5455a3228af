#!/usr/bin/env python3
"""Writes cases/fluidized_bed_1000.toml (issue 34, point 4): the fluid and the inflow of paper 5.4
(cases/paper/5.4_fluidized_bed_102.toml) in a bed 4 times as wide and 2.5 times as tall, with
1,000 disks of D = 0.2 on a lattice of 40 rows of 25 (0.32 apart across, 0.3925 up, from y = 0.2),
which fills the lowest 15.7 of the bed at a solid fraction of 0.25.

    python3 bench/fluidized_bed_case.py > cases/fluidized_bed_1000.toml
"""
import math

WIDTH, HEIGHT = 8.0, 20.0
COLUMNS, ROWS = 25, 40
DIAMETER = 0.2
DX = WIDTH / COLUMNS
DY = 0.3925
BED = ROWS * DY  # the lattice's cells: COLUMNS x ROWS of DX x DY
fraction = COLUMNS * ROWS * math.pi * DIAMETER**2 / 4 / (WIDTH * BED)

print(f'''title = "A fluidized bed of {COLUMNS * ROWS} disks (D = {DIAMETER}, solid fraction {fraction:.3f} over the lowest {BED:.2f}), the liquid and inflow of paper 5.4 in an {WIDTH:g} x {HEIGHT:g} bed (issue 34)"
# Written by bench/fluidized_bed_case.py; docs/evidence/performance.md, "A thousand particles".

[domain]
size = [{WIDTH}, {HEIGHT}]
h = 0.010416666666666666
[domain.boundary]
left   = {{ type = "wall" }}
right  = {{ type = "wall" }}
bottom = {{ type = "velocity", profile = "poiseuille", max = [0.0, 0.5] }}
top    = {{ type = "outflow" }}

[fluid]
density = 1.0
viscosity = 0.02
relaxation_time = 0.5
solvent_ratio = 0.5

gravity = [0.0, -981.0]

[time]
dt = 0.0004
end = 2.0

[particle_mesh]
h = 0.014285714285714285

[output]
fields_every = 0.1
particles_every = 0.01
checkpoint_every = 0.5''')
for row in range(ROWS):
    for column in range(COLUMNS):
        x = DX * (column + 0.5)
        y = 0.2 + DY * row
        print(f'''
[[particles]]
center = [{x:.6f}, {y:.6f}]
diameter = {DIAMETER}
density = 1.01''')
