#!/usr/bin/env python3
"""Writes delay_linear_increments.csv: a record of examples/delay_linear.yaml's late sensor (at its
parameters a = -0.5, sigma = 0.3, the delay h = 0.5 and B = 0.2), the time and the increment dy of
the integrated signal over each 0.01 since the previous row, for 10 time units.

The truth is integrated by Euler-Maruyama with steps of 1e-3 from the model's x0 = 1; the sensor
reads it h late, and before t = h it reads x(0) (the pre-history pfgen assumes, x(s) = x(0) for
s < 0). Seeded, so the file is the same on every run:
python3 make_delay_linear_record.py > delay_linear_increments.csv
"""
import numpy as np

rng = np.random.default_rng(2027)
a, sigma, h, b = -0.5, 0.3, 0.5, 0.2
fine, per_row, rows = 1e-3, 10, 1000
lag = round(h / fine)
x = [1.0]  # x at the fine grid's times 0, fine, 2 fine, ...
print("t,dy")
print("0,")
for k in range(1, rows + 1):
    dy = 0.0
    for _ in range(per_row):
        j = len(x) - 1
        dw1, dw2 = rng.normal(0.0, np.sqrt(fine), 2)
        dy += x[max(j - lag, 0)] * fine + b * dw2
        x.append(x[j] + a * x[j] * fine + sigma * dw1)
    print("%s,%.12g" % (repr(round(k * per_row * fine, 10)), dy))
