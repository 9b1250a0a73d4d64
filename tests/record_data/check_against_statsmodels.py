#!/usr/bin/env python3
"""Checks `pfgen estimate` and `pfgen fit` on recorded data against independent computations:

1. the Nile record under the local-level model: pfgen's log-likelihood against statsmodels' exact
   Kalman likelihood with the same prior (N(0, 1e7) at the first year, no observation left out),
   and pfgen's maximum-likelihood estimates against statsmodels' with that prior;
2. a mean-reverting state sampled at irregular times, one sample missing: the log-likelihood
   against the exact discretisation's Kalman filter written here in numpy, the difference
   shrinking as the prediction's sub-steps grow (the filter's only error is Heun's on the
   prediction), and the fitted parameters against the exact likelihood's maximum (scipy-free:
   statsmodels is not needed for that one, a grid refinement is).

Usage: check_against_statsmodels.py PFGEN SOURCE_DIR WORK_DIR
"""
import csv
import json
import math
import os
import subprocess
import sys

import numpy as np


def run(pfgen, *args):
    out = subprocess.run([pfgen, *args, "-q"], capture_output=True, text=True)
    if out.returncode != 0:
        sys.exit("pfgen %s failed: %s" % (" ".join(args), out.stderr))
    return out.stdout


def log_likelihood(report, filter_name):
    for line in report.splitlines():
        if line.startswith(filter_name + " "):
            return float(line.split()[1])
    sys.exit("no row for %s in:\n%s" % (filter_name, report))


failures = []


def check(ok, what):
    print(("ok:   " if ok else "FAIL: ") + what)
    if not ok:
        failures.append(what)


def nile(pfgen, source, work):
    import statsmodels.api as sm
    model_path = os.path.join(source, "examples/records/nile.yaml")
    data_path = os.path.join(source, "examples/records/nile.csv")
    with open(data_path) as f:
        volume = np.array([float(row["volume"]) for row in csv.DictReader(f)])
    ucm = sm.tsa.UnobservedComponents(volume, "local level")
    ucm.ssm.initialize_known(np.array([0.0]), np.array([[1e7]]))
    ucm.ssm.loglikelihood_burn = 0
    report = run(pfgen, "estimate", model_path, "--data", data_path, "--time-column", "year", "--filters", "cd-optimal")
    ours = log_likelihood(report, "cd-optimal")
    theirs = ucm.loglike([15099.0, 1469.1])  # statsmodels' order: irregular (h), level (q)
    check(abs(ours - theirs) < 1e-6 * abs(theirs), "Nile log-likelihood %.9f against statsmodels' %.9f" % (ours, theirs))

    fitted = ucm.fit(start_params=[15000.0, 1500.0], disp=False, method="lbfgs", maxiter=1000,
                     optim_score="approx", pgtol=1e-10)
    h_sm, q_sm = fitted.params
    json_path = os.path.join(work, "nile_fit.json")
    run(pfgen, "fit", model_path, "--data", data_path, "--time-column", "year", "--estimate", "q,h",
        "--bounds", "q=0:,h=0:", "-o", json_path)
    with open(json_path) as f:
        fit = json.load(f)
    est = {p["name"]: p["estimate"] for p in fit["parameters"]}
    check(fit["converged"], "Nile fit converged")
    check(abs(est["q"] - q_sm) < 1e-5 * q_sm and abs(est["h"] - h_sm) < 1e-5 * h_sm,
          "Nile estimates q = %.2f, h = %.2f against statsmodels' %.2f, %.2f (same prior)" % (est["q"], est["h"], q_sm, h_sm))
    check(abs(fit["log_likelihood"] - fitted.llf) < 1e-9,
          "Nile maximum log-likelihood %.6f against statsmodels' %.6f" % (fit["log_likelihood"], fitted.llf))


def exact_ou_log_likelihood(times, ys, a, s, u, m0=0.0, P0=1.0):
    """The exact Kalman filter of dx = -a x dt + s dW sampled with N(0, u^2) noise, prior at times[0]."""
    m, P, t, total = m0, P0, times[0], 0.0
    for tk, y in zip(times, ys):
        d = tk - t
        phi = math.exp(-a * d)
        m, P = phi * m, phi * phi * P + s * s * (1 - phi * phi) / (2 * a)
        t = tk
        if math.isnan(y):
            continue
        S = P + u * u
        total += -0.5 * (math.log(2 * math.pi * S) + (y - m) ** 2 / S)
        K = P / S
        m, P = m + K * (y - m), (1 - K) * P
    return total


def mean_reverting(pfgen, source, work):
    model_path = os.path.join(source, "tests/record_data/mean_reverting.yaml")
    rng = np.random.default_rng(7)
    a, s, u = 0.8, 0.6, 0.3
    times = np.concatenate([[0.0], np.cumsum(rng.uniform(0.2, 2.0, 299))])
    x = rng.normal(0, 1)
    ys, t = [], 0.0
    for tk in times:
        phi = math.exp(-a * (tk - t))
        x = phi * x + rng.normal(0, math.sqrt(s * s * (1 - phi * phi) / (2 * a)))
        t = tk
        ys.append(x + rng.normal(0, u))
    ys[40] = float("nan")  # a missing sample: predicted over, not absorbed
    mean_reverting.data = (times, ys, a, s, u)
    data_path = os.path.join(work, "mean_reverting.csv")
    with open(data_path, "w") as f:
        f.write("t,y\n")
        for tk, y in zip(times, ys):
            f.write("%r,%s\n" % (float(tk), "" if math.isnan(y) else repr(float(y))))
    exact = exact_ou_log_likelihood(times, ys, a, s, u)
    errors = []
    for substeps in (1, 10, 100):
        # The model's sub-steps per period (1) scale to each interval: ceil(interval x substeps).
        with open(model_path) as f:
            text = f.read().replace("substeps: 10", "substeps: %d" % substeps)
        scaled_model = os.path.join(work, "mean_reverting_%d.yaml" % substeps)
        with open(scaled_model, "w") as f:
            f.write(text)
        ours = log_likelihood(run(pfgen, "estimate", scaled_model, "--data", data_path, "--filters", "cd-optimal"),
                              "cd-optimal")
        errors.append(abs(ours - exact))
        print("  sub-steps %3d: log-likelihood %.9f, exact %.9f, difference %.2e" % (substeps, ours, exact, errors[-1]))
    check(errors[2] < 1e-3 and errors[1] < errors[0] / 20 and errors[2] < errors[1] / 50,
          "irregular samples: the difference from the exact likelihood shrinks with the sub-steps (Heun, second order)")

    json_path = os.path.join(work, "mean_reverting_fit.json")
    run(pfgen, "fit", os.path.join(work, "mean_reverting_100.yaml"), "--data", data_path, "--estimate", "a,s",
        "--bounds", "a=0.01:10,s=0.01:10", "-o", json_path)
    with open(json_path) as f:
        fit = json.load(f)
    est = {p["name"]: p["estimate"] for p in fit["parameters"]}
    # The exact likelihood's maximum, by a local search on the exact function (Nelder-Mead by hand
    # would be another optimiser to trust; a fine grid around pfgen's estimate shows none higher).
    best = exact_ou_log_likelihood(times, ys, est["a"], est["s"], u)
    higher = 0
    for da in np.linspace(-0.02, 0.02, 9):
        for ds in np.linspace(-0.02, 0.02, 9):
            if exact_ou_log_likelihood(times, ys, est["a"] * (1 + da), est["s"] * (1 + ds), u) > best + 1e-7:
                higher += 1
    check(fit["converged"] and higher == 0,
          "irregular samples: fit a = %.4f, s = %.4f is the exact likelihood's maximum (no grid point within 2 %% higher)"
          % (est["a"], est["s"]))


def prior_mean(pfgen, work, times, ys, a, s, u):
    """fit --estimate m0.x: the prior mean at the exact likelihood's maximum (by golden section)."""
    json_path = os.path.join(work, "mean_reverting_m0.json")
    run(pfgen, "fit", os.path.join(work, "mean_reverting_100.yaml"), "--data", os.path.join(work, "mean_reverting.csv"),
        "--estimate", "m0.x", "-o", json_path)
    with open(json_path) as f:
        ours = json.load(f)["parameters"][0]["estimate"]
    lo, hi, g = -5.0, 5.0, (math.sqrt(5) - 1) / 2
    for _ in range(100):
        c, d = hi - g * (hi - lo), lo + g * (hi - lo)
        if exact_ou_log_likelihood(times, ys, a, s, u, m0=c) > exact_ou_log_likelihood(times, ys, a, s, u, m0=d):
            hi = d
        else:
            lo = c
    exact = 0.5 * (lo + hi)
    check(abs(ours - exact) < 1e-3, "the prior mean m0.x fitted %.6f, the exact likelihood's maximum %.6f" % (ours, exact))


def main():
    pfgen, source, work = sys.argv[1:4]
    os.makedirs(work, exist_ok=True)
    nile(pfgen, source, work)
    mean_reverting(pfgen, source, work)
    prior_mean(pfgen, work, *mean_reverting.data)
    if failures:
        sys.exit("%d check(s) failed" % len(failures))


main()
