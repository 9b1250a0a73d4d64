#!/usr/bin/env python3
"""Writes tests/data/double_well_increments.csv: 10 s of examples/reference/double_well.yaml (c = 0.5,
s = 0.5, r = 0.5) from x = (1, 0), Euler-Maruyama at dt = 1e-3, its observation increments dy summed over
each 0.01. Seeded, so the file is the same on every run:

    python3 tests/record_data/make_double_well_record.py > tests/data/double_well_increments.csv
"""
import math
import random

random.seed(5)
x1, x2, dt = 1.0, 0.0, 0.001
print("t,y\n0,0")
for k in range(1000):
    dy = 0
    for i in range(10):
        dy += x1 * dt + 0.5 * math.sqrt(dt) * random.gauss(0, 1)
        x1, x2 = x1 + x2 * dt, x2 + (x1 - x1**3 - 0.5 * x2) * dt + 0.5 * math.sqrt(dt) * random.gauss(0, 1)
    print(f"{round((k + 1) * 0.01, 10)},{dy:.8f}")
