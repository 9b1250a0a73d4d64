#!/usr/bin/env python3
"""Writes van_der_pol_increments.csv: a record of the Van der Pol model's sensor (examples/van_der_pol.yaml
at its parameters mu = 1, s = 0.5, r = 0.1), as a data logger would keep it: the time and the
increment dy of the integrated position signal over each 0.01 since the previous row.

The truth is integrated by Euler-Maruyama with steps of 1e-4 from a draw of the prior N(0, I);
seeded, so the file is the same on every run: python3 make_van_der_pol_record.py > van_der_pol_increments.csv
"""
import numpy as np

rng = np.random.default_rng(2026)
mu, s, r = 1.0, 0.5, 0.1
fine, per_row, rows = 1e-4, 100, 1000
x1, x2 = rng.normal(0.0, 1.0, 2)
print("t,dy")
print("0,")
for k in range(1, rows + 1):
    dy = 0.0
    for _ in range(per_row):
        dw1, dw2 = rng.normal(0.0, np.sqrt(fine), 2)
        dy += x1 * fine + r * dw2
        x1, x2 = x1 + x2 * fine, x2 + (mu * (1 - x1 * x1) * x2 - x1) * fine + s * x1 * dw1
    print("%s,%.12g" % (repr(round(k * per_row * fine, 10)), dy))
