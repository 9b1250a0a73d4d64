#!/usr/bin/env python3
"""Checks `pfgen estimate` and `pfgen fit` on records of delayed observations against computations
written here in numpy, independently of pfgen's generated code:

1. a record of dx = a x dt + sigma dW1, dy = x(t - h) dt + B dW2 (examples/delay_linear.yaml,
   h = 0.5) simulated here, x(t - h) read from the simulated path (x(s) = x(0) before the start);
2. the delayed filters `delay-uncorrected` and `delay-optimal` (docs/theory.md section 2.6) written
   out for this scalar model with Heun's step on the record's grid, the history of m and x* kept
   in a list: their estimates (the CSV's m and sd) and their log-likelihoods (the filter's and the
   increments' log-density) against pfgen estimate's, to rounding;
3. the record's step: a record at another step (dt = 0.02, so h = 25 steps) gives its own plugin,
   again equal to the numpy filter; a record starting at t = 3 (the model's coefficients do not
   depend on t) gives the same numbers as the one starting at 0;
4. the fit of a on a longer record: pfgen's maximum is where the numpy filter's likelihood,
   evaluated on a grid of a, peaks, with the same value there. The delayed filters' likelihood is
   an approximate filter's (its innovation reads m(t - h), not E[x(t - h) | Y(t)]; docs/theory.md
   2.6), and its maximum is not the true a: the exact likelihood of the record, the Kalman filter
   on the state augmented with its D delayed copies, written here, peaks at the true a = -0.5 and
   is higher there than at the delayed filter's estimate (which the guide states).

Usage: check_delayed.py PFGEN SOURCE_DIR WORK_DIR
"""
import csv
import json
import math
import os
import subprocess
import sys

import numpy as np

A_TRUE, SIGMA, H, B = -0.5, 0.3, 0.5, 0.2
M0, P0, X0 = 0.5, 0.25, 1.0

failures = []


def check(ok, what):
    print(("ok:   " if ok else "FAIL: ") + what)
    if not ok:
        failures.append(what)


def run(pfgen, *args):
    out = subprocess.run([pfgen, *args, "-q"], capture_output=True, text=True)
    if out.returncode != 0:
        sys.exit("pfgen %s failed: %s" % (" ".join(args), out.stderr))
    return out.stdout


def simulate(seed, rows, dt, fine=10):
    """Euler-Maruyama on dt / fine; each row's dy integrates x(s - h) over the interval on the
    fine grid (left points) plus B's increment. x(s) = x(0) for s < 0."""
    rng = np.random.default_rng(seed)
    d = dt / fine
    delay = int(round(H / d))
    steps = rows * fine
    x = np.empty(steps + 1)
    x[0] = X0
    dw = rng.standard_normal(steps) * math.sqrt(d)
    for k in range(steps):
        x[k + 1] = x[k] + A_TRUE * x[k] * d + SIGMA * dw[k]
    past = np.concatenate([np.full(delay, X0), x[: steps + 1 - delay]])  # x(t_k - h) on the fine grid
    drift = past[:steps] * d
    dy = drift.reshape(rows, fine).sum(axis=1) + B * math.sqrt(dt) * rng.standard_normal(rows)
    return dy


def write_record(path, t0, dt, dy):
    with open(path, "w") as f:
        f.write("t,y\n%r,\n" % t0)
        for k, v in enumerate(dy):
            f.write("%r,%r\n" % (t0 + (k + 1) * dt, float(v)))


def numpy_filter(kind, a, dt, dy):
    """The delayed filter of docs/theory.md 2.6 for the scalar model, Heun's step k from t_k = k dt
    with m(t - h) (and x*) at grid index k - D in the predictor and k + 1 - D in the corrector, the
    pre-history m0 (x* = m0) before 0, Phi* = 0 over every step starting before h. Returns m and P
    after each row, the filter's log-likelihood and the increments' log-density."""
    D = int(round(H / dt))
    R = B * B
    m, P, xs = M0, P0, M0
    history_m, history_xs = [], []  # values at grid indices 0, 1, ...

    def past(values, j):
        return values[j] if j >= 0 else M0

    def rates(mm, PP, xx, md, phi):
        gain = PP * (phi if kind == "delay-optimal" else 1.0) / R
        h = md
        return (a * mm, 2 * a * PP + SIGMA ** 2 - gain * gain * R, a * xx, gain, h)

    ms, Ps, girsanov, density = [], [], 0.0, 0.0
    for k, inc in enumerate(dy):
        history_m.append(m)
        history_xs.append(xs)
        md0 = past(history_m, k - D)
        phi0 = 0.0 if k < D else past(history_xs, k - D) / xs
        dm, dP, dxs, K, h = rates(m, P, xs, md0, phi0)
        girsanov += h * inc / R - 0.5 * h * h * dt / R
        e = inc - h * dt
        density += -0.5 * (math.log(2 * math.pi * R * dt) + e * e / (R * dt))
        first = (dm * dt + K * (inc - h * dt), dP * dt, dxs * dt)
        mp, Pp, xp = m + first[0], P + first[1], xs + first[2]
        md1 = past(history_m, k + 1 - D) if D > 0 else mp
        phi1 = 0.0 if k < D else past(history_xs, k + 1 - D) / xp
        dm, dP, dxs, K, h = rates(mp, Pp, xp, md1, phi1)
        second = (dm * dt + K * (inc - h * dt), dP * dt, dxs * dt)
        m += (first[0] + second[0]) / 2
        P += (first[1] + second[1]) / 2
        xs += (first[2] + second[2]) / 2
        ms.append(m)
        Ps.append(P)
    return np.array(ms), np.array(Ps), girsanov, density


def exact_log_likelihood(a, dt, dy):
    """The record's exact Gaussian log-density on the grid: the Kalman filter on z_k = (x_k, ...,
    x_{k-D}) with x_{k+1} = e^{a dt} x_k + w_k (the exact transition) and dy_k = x_{k-D} dt + B dW
    (the filter's left-point rate), the prior N(m0, P0) on x_0 and the pre-history x_j = x_0, j < 0."""
    D = int(round(H / dt))
    n = D + 1
    F = np.zeros((n, n))
    F[0, 0] = math.exp(a * dt)
    F[1:, :-1] = np.eye(D)
    q = SIGMA ** 2 * (math.exp(2 * a * dt) - 1) / (2 * a)
    m, P = np.full(n, M0), np.full((n, n), P0)
    R = B * B * dt
    total = 0.0
    for v in dy:
        S = P[-1, -1] * dt * dt + R
        e = v - m[-1] * dt
        total += -0.5 * (math.log(2 * math.pi * S) + e * e / S)
        K = P[:, -1] * dt / S
        m = m + K * e
        P = P - np.outer(K, P[-1, :] * dt)
        m = F @ m
        P = F @ P @ F.T
        P[0, 0] += q
    return total


def scores(report, name):
    for line in report.splitlines():
        if line.startswith(name + " "):
            fields = line.split()
            return float(fields[1]), float(fields[2])
    sys.exit("no row for %s in:\n%s" % (name, report))


def estimates(path, name):
    with open(path) as f:
        rows = list(csv.DictReader(f))[1:]  # the first row starts the record
    return (np.array([float(r[name + "_m_x"]) for r in rows]), np.array([float(r[name + "_sd_x"]) for r in rows]))


def against_numpy(pfgen, model, work, t0, dt, dy, label):
    data = os.path.join(work, "record_%s.csv" % label)
    write_record(data, t0, dt, dy)
    out = os.path.join(work, "estimates_%s.csv" % label)
    report = run(pfgen, "estimate", model, "--data", data, "--filters", "delay-uncorrected,delay-optimal", "-o", out,
                 "--cache-dir", os.path.join(work, "cache"))
    for kind in ("delay-uncorrected", "delay-optimal"):
        m, P, girsanov, density = numpy_filter(kind, A_TRUE, dt, dy)
        ours_m, ours_sd = estimates(out, kind)
        ll, ld = scores(report, kind)
        dm = np.max(np.abs(ours_m - m))
        dsd = np.max(np.abs(ours_sd - np.sqrt(P)))
        check(dm < 1e-11 and dsd < 1e-11,
              "%s, %s: m and sd equal the numpy filter's over %d rows (largest differences %.2g, %.2g)" %
              (label, kind, len(dy), dm, dsd))
        check(abs(ll - girsanov) < 2e-6 and abs(ld - density) < 2e-6,
              "%s, %s: log-likelihood %.6f and log-density %.6f against numpy's %.6f and %.6f" %
              (label, kind, ll, ld, girsanov, density))
    return report


def main():
    if len(sys.argv) != 4:
        sys.exit(__doc__)
    pfgen, source, work = sys.argv[1:]
    os.makedirs(work, exist_ok=True)
    model = os.path.join(source, "examples/delay_linear.yaml")

    dy = simulate(seed=11, rows=1000, dt=0.01)
    first = against_numpy(pfgen, model, work, 0.0, 0.01, dy, "dt 0.01")
    shifted = against_numpy(pfgen, model, work, 3.0, 0.01, dy, "dt 0.01 from t = 3")
    table = lambda report: [line for line in report.splitlines()[3:] if not line.startswith("Wrote ")]
    check(table(first) == table(shifted), "a record starting at t = 3 gives the scores of the one starting at 0")
    columns = lambda label: [line.split(",", 1)[1] for line in open(os.path.join(work, "estimates_%s.csv" % label))]
    check(columns("dt 0.01") == columns("dt 0.01 from t = 3"),
          "a record starting at t = 3 gives the estimates of the one starting at 0, bit for bit")
    against_numpy(pfgen, model, work, 0.0, 0.02, simulate(seed=12, rows=500, dt=0.02), "dt 0.02")

    # Recovery: a on 100 time units of increments every 0.01.
    dy = simulate(seed=5, rows=10000, dt=0.01)
    data = os.path.join(work, "long.csv")
    write_record(data, 0.0, 0.01, dy)
    fit_path = os.path.join(work, "fit.json")
    run(pfgen, "fit", model, "--data", data, "--filter", "delay-uncorrected", "--estimate", "a", "--bounds", "a=-5:0",
        "-o", fit_path, "--cache-dir", os.path.join(work, "cache"))
    with open(fit_path) as f:
        fitted = json.load(f)
    parameter = fitted["parameters"][0]
    estimate, error = parameter["estimate"], parameter["std_error"]
    print("fit of a by delay-uncorrected: %.4f (standard error %.4f); simulated with a = %g" % (estimate, error, A_TRUE))
    grid = np.linspace(estimate - 0.02, estimate + 0.02, 9)
    values = [numpy_filter("delay-uncorrected", a, 0.01, dy)[3] for a in grid]
    peak = int(np.argmax(values))
    check(fitted["converged"] and peak == 4 and abs(fitted["log_likelihood"] - values[4]) < 1e-6 * abs(values[4]),
          "the numpy filter's log-density peaks at the fitted a (grid point %d of 9) and equals the fit's %.6f there" %
          (peak + 1, fitted["log_likelihood"]))
    exact = {a: exact_log_likelihood(a, 0.01, dy) for a in (A_TRUE - 0.1, A_TRUE, A_TRUE + 0.1, estimate)}
    check(exact[A_TRUE] > max(exact[A_TRUE - 0.1], exact[A_TRUE + 0.1]) and exact[A_TRUE] > exact[estimate] + 2,
          "the exact likelihood peaks near the true a (%.3f at a = %g, %.3f and %.3f at a -+ 0.1, %.3f at the "
          "delayed filter's estimate)" % (exact[A_TRUE], A_TRUE, exact[A_TRUE - 0.1], exact[A_TRUE + 0.1], exact[estimate]))

    if failures:
        sys.exit("%d check(s) failed" % len(failures))


if __name__ == "__main__":
    main()
