#!/usr/bin/env python3
"""Parameter recovery on simulated records: for two nonlinear models, `pfgen fit` on many seeded
data sets, then how often the 95 % Wald intervals cover the true value, and whether the estimates'
spread matches their standard errors.

  A. the Van der Pol oscillator (examples/van_der_pol.yaml: cubic drift, state-multiplicative
     noise, continuous position sensor), mu = 1 fitted from 10 time units of increments every 0.01;
  B. a mean-reverting state read through a cubic sensor characteristic, sampled every 0.1
     (tests/record_data/cubic_sensor_sampled.yaml: a polynomial sampled observation), s = 1 fitted
     from 200 samples; the characteristic x + k3 x^3 with k3 = 0.1 (--cubic K3 for another).

The truths are simulated here, independently of pfgen: Euler-Maruyama at 1e-4 for A, the exact
Ornstein-Uhlenbeck transition for B, all data sets at once with numpy, seeded.

Usage: recovery.py PFGEN SOURCE_DIR WORK_DIR [--datasets K]   (the tests run K = 40; the guide's
table is K = 200). Exits 1 when a coverage falls outside its binomial 99.9 % range for K, or the
spread and the mean standard error differ by more than their sampling error allows.
"""
import argparse
import json
import math
import os
import subprocess
import sys

import numpy as np


def van_der_pol_records(k, rng):
    mu, s, r = 1.0, 0.5, 0.1
    fine, per_row, rows = 1e-4, 100, 1000
    x1, x2 = rng.normal(0.0, 1.0, k), rng.normal(0.0, 1.0, k)
    dy = np.zeros((rows, k))
    for row in range(rows):
        for _ in range(per_row):
            dw1 = rng.normal(0.0, math.sqrt(fine), k)
            dw2 = rng.normal(0.0, math.sqrt(fine), k)
            dy[row] += x1 * fine + r * dw2
            x1, x2 = x1 + x2 * fine, x2 + (mu * (1 - x1 * x1) * x2 - x1) * fine + s * x1 * dw1
    times = np.arange(rows + 1) * per_row * fine
    return times, dy


def cubic_sensor_records(k, rng, k3):
    a, s, u, period, rows = 1.0, 1.0, 0.1, 0.1, 200
    x = rng.normal(0.0, math.sqrt(0.5), k)
    phi = math.exp(-a * period)
    spread = s * math.sqrt((1 - phi * phi) / (2 * a))
    y = np.zeros((rows, k))
    for row in range(rows):
        x = phi * x + spread * rng.normal(0.0, 1.0, k)  # the exact transition over one period
        y[row] = x + k3 * x ** 3 + u * rng.normal(0.0, 1.0, k)
    times = (np.arange(rows) + 1) * period
    return times, y


def fit(pfgen, model, data, work, name, extra):
    out = os.path.join(work, name + ".json")
    done = subprocess.run([pfgen, "fit", model, "--data", data, "-o", out, "-q", *extra], capture_output=True, text=True)
    if done.returncode != 0:
        return None
    with open(out) as f:
        return json.load(f)["parameters"][0]


def study(label, pfgen, model, extra, truth, times, values, work, first_row_empty):
    k = values.shape[1]
    estimates, errors, covered = [], [], 0
    for j in range(k):
        data = os.path.join(work, "%s_%03d.csv" % (label, j))
        with open(data, "w") as f:
            f.write("t,y\n")
            if first_row_empty:
                f.write("0,\n")
            for t, v in zip(times[1:] if first_row_empty else times, values[:, j]):
                f.write("%r,%r\n" % (float(t), float(v)))
        p = fit(pfgen, model, data, work, "%s_%03d" % (label, j), extra)
        if p is None or p["std_error"] is None:
            continue
        estimates.append(p["estimate"])
        errors.append(p["std_error"])
        covered += p["wald"][0] <= truth <= p["wald"][1]
    n = len(estimates)
    spread, mean_error = float(np.std(estimates, ddof=1)), float(np.mean(errors))
    # Binomial 99.9 % range of the coverage count for a true 95 % (normal approximation).
    low, high = n * 0.95 - 3.29 * math.sqrt(n * 0.95 * 0.05), n * 0.95 + 3.29 * math.sqrt(n * 0.95 * 0.05)
    # The spread's relative sampling error is about 1 / sqrt(2 (n - 1)); allow 3.29 of them.
    ratio, allowed = spread / mean_error, 3.29 / math.sqrt(2 * (n - 1))
    print("%s: %d of %d fits converged with standard errors; true %g, mean estimate %.4g" % (label, n, k, truth, np.mean(estimates)))
    print("  95 %% Wald intervals cover the truth in %d of %d (%.1f %%; 99.9 %% range %.0f to %.0f)" %
          (covered, n, 100.0 * covered / n, low, high))
    print("  spread of the estimates %.4g, mean standard error %.4g: ratio %.3f (1 within %.3f)" %
          (spread, mean_error, ratio, allowed))
    return n >= 0.95 * k and low <= covered <= high + 1 and abs(ratio - 1) <= allowed


def main():
    parser = argparse.ArgumentParser()
    parser.add_argument("pfgen")
    parser.add_argument("source")
    parser.add_argument("work")
    parser.add_argument("--datasets", type=int, default=40)
    parser.add_argument("--cubic", type=float, default=0.1, help="the sensor's k3 (the model file's is 0.3)")
    a = parser.parse_args()
    os.makedirs(a.work, exist_ok=True)
    rng = np.random.default_rng(20261129)
    ok = True
    times, values = van_der_pol_records(a.datasets, rng)
    ok &= study("van_der_pol", a.pfgen, os.path.join(a.source, "examples/van_der_pol.yaml"),
                ["--estimate", "mu", "--bounds", "mu=0:5", "--filter", "optimal"], 1.0, times, values, a.work, True)
    times, values = cubic_sensor_records(a.datasets, rng, a.cubic)
    ok &= study("cubic_sensor", a.pfgen, os.path.join(a.source, "tests/record_data/cubic_sensor_sampled.yaml"),
                ["--estimate", "s", "--bounds", "s=0.01:10", "--filter", "cd-optimal", "--t0", "0", "--set",
                 "k3=%r" % a.cubic], 1.0, times, values, a.work, False)
    sys.exit(0 if ok else 1)


main()
