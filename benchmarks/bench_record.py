#!/usr/bin/env python3
"""Filters on recorded data, timed side by side in one run (docs/benchmarks.md, "Recorded data"):

1. one log-likelihood evaluation of the Nile record (100 years, the local-level model) by pfgen's
   compiled filter (bench_record), by statsmodels' UnobservedComponents.loglike (its Kalman filter
   in Cython), and by a Python loop over pfgen's `eval` (Filter.eval for the prediction's drifts
   and the update's S and K at each year: what a user writes without `estimate`); the three
   log-likelihoods are printed too, and must agree;
2. `pfgen estimate` over a continuous record of 10^6 steps of a 3-state model (the Lorenz system
   with state-multiplicative noise, two states observed), the plugin cached;
3. `pfgen fit` of the boarding-school influenza record (14 days, SIR model, beta and gamma), the
   plugin cached;
4. `pfgen estimate` streaming a record of 10^7 steps of a one-state model
   (benchmarks/models/ou_continuous.yaml, the record written here by numpy), its time and the
   process's peak memory (the record is 254 MB; held whole it would need more than that).

Usage: bench_record.py --build BUILD_DIR [--bench BENCH_RECORD] [--work DIR] [--repeats R]
Ratios are against pfgen's own time measured in the same run (these machines are noisy).
"""
import argparse
import math
import os
import statistics
import subprocess
import sys
import time

import numpy as np


def median_seconds(function, repeats, min_time=0.2):
    times = []
    for _ in range(repeats):
        count, start = 0, time.perf_counter()
        while True:
            function()
            count += 1
            elapsed = time.perf_counter() - start
            if elapsed >= min_time:
                break
        times.append(elapsed / count)
    return statistics.median(times)


def command_seconds(argv, repeats):
    subprocess.run(argv, check=True, capture_output=True)  # the plugin into the cache first
    times = []
    for _ in range(repeats):
        start = time.perf_counter()
        subprocess.run(argv, check=True, capture_output=True)
        times.append(time.perf_counter() - start)
    return statistics.median(times)


def nile(build, bench, source, repeats):
    model = os.path.join(source, "examples/records/nile.yaml")
    data = os.path.join(source, "examples/records/nile.csv")
    out = subprocess.run([bench, model, data, "--time-column", "year",
                          "--filter", "cd-optimal", "--repeats", str(repeats)], check=True, capture_output=True,
                         text=True).stdout
    print("  pfgen (compiled filter):      " + out.strip())
    ours = float(out.split("one evaluation ")[1].split(" s")[0])
    ours_ll = float(out.split("log-likelihood ")[1].split(",")[0])

    volume = np.loadtxt(data, delimiter=",", skiprows=1)[:, 1]
    import statsmodels.api as sm
    ucm = sm.tsa.UnobservedComponents(volume, "local level")
    ucm.ssm.initialize_known(np.array([0.0]), np.array([[1e7]]))
    ucm.ssm.loglikelihood_burn = 0
    params = np.array([15099.0, 1469.1])
    theirs_ll = ucm.loglike(params)
    theirs = median_seconds(lambda: ucm.loglike(params), repeats)
    print("  statsmodels loglike:          log-likelihood %.9f, one evaluation %.3g s" % (theirs_ll, theirs))

    sys.path.insert(0, os.path.join(build, "python"))
    import pfgen
    f = pfgen.Model.load(model).derive("cd-optimal")

    def eval_loop():
        # Heun over each year on eval's prediction drifts, then the update from eval's S and K.
        m, P, total = 0.0, 1e7, 0.0
        for k, y in enumerate(volume):
            if k > 0:
                d1 = f.eval(k - 1, [m], [[P]])["prediction"]
                m1, P1 = m + d1["m_drift"][0], P + d1["P_drift"][0][0]
                d2 = f.eval(k, [m1], [[P1]])["prediction"]
                m, P = m + 0.5 * (d1["m_drift"][0] + d2["m_drift"][0]), P + 0.5 * (d1["P_drift"][0][0] + d2["P_drift"][0][0])
            u = f.eval(k, [m], [[P]])["update"]
            S, K = u["innovation_covariance"][0][0], u["gain"][0][0]
            total += -0.5 * (math.log(2 * math.pi * S) + (y - m) ** 2 / S)
            m, P = m + K * (y - m), P - K * S * K
        return total

    loop_ll = eval_loop()
    loop = median_seconds(eval_loop, max(3, repeats // 3), min_time=0.5)
    print("  Python loop over pfgen eval:  log-likelihood %.9f, one evaluation %.3g s" % (loop_ll, loop))
    agree = abs(ours_ll - theirs_ll) < 1e-6 * abs(theirs_ll) and abs(ours_ll - loop_ll) < 1e-6 * abs(theirs_ll)
    print("  statsmodels / pfgen %.1f x, eval loop / pfgen %.0f x; log-likelihoods agree: %s" %
          (theirs / ours, loop / ours, "yes" if agree else "NO"))
    return agree


def lorenz_record(path, steps):
    if os.path.exists(path):
        return
    rng = np.random.default_rng(5)
    sigma, rho, beta, s, dt = 10.0, 28.0, 2.6667, 0.2, 1e-3
    x = np.array([1.0, 1.0, 20.0])
    noise = rng.normal(0.0, math.sqrt(dt), (steps, 5))
    with open(path, "w") as out:
        out.write("t,y1,y2\n0,,\n")
        lines = []
        for k in range(steps):
            f = np.array([sigma * (x[1] - x[0]), x[0] * (rho - x[2]) - x[1], x[0] * x[1] - beta * x[2]])
            dy1, dy2 = x[0] * dt + 0.5 * noise[k, 3], x[2] * dt + 0.5 * noise[k, 4]
            x = x + f * dt + s * x * noise[k, :3]
            lines.append("%.3f,%.9g,%.9g\n" % ((k + 1) * dt, dy1, dy2))
            if len(lines) == 10000:
                out.write("".join(lines))
                lines = []
        out.write("".join(lines))


def stream(pfgen, source, work, rows, repeats):
    import scipy.signal
    path = os.path.join(work, "ou_%d.csv" % rows)
    if not os.path.exists(path):
        rng = np.random.default_rng(1)
        dt, a, s, r = 1e-3, 1.0, 0.5, 0.1
        phi = math.exp(-a * dt)
        x = scipy.signal.lfilter([1.0], [1.0, -phi], rng.normal(0, s * math.sqrt((1 - phi * phi) / (2 * a)), rows))
        dy = x * dt + r * math.sqrt(dt) * rng.normal(0, 1, rows)
        with open(path, "w") as f:
            f.write("t,dy\n0,\n")
            np.savetxt(f, np.column_stack([np.arange(1, rows + 1) * dt, dy]), fmt=["%.3f", "%.9e"], delimiter=",")
    argv = [pfgen, "estimate", os.path.join(source, "benchmarks/models/ou_continuous.yaml"), "--data", path,
            "--filters", "optimal", "-q"]
    seconds = command_seconds(argv, max(1, repeats // 2))
    # The peak memory of one more run, that process's own (wait4's usage, in KiB). A child's peak
    # counts what it held before exec, a copy of its parent: so a small interpreter starts it, not
    # this one, which holds numpy's arrays and statsmodels.
    starter = ("import os, sys\npid = os.fork()\nif pid == 0:\n    null = os.open(os.devnull, os.O_WRONLY)\n"
               "    os.dup2(null, 1)\n    os.dup2(null, 2)\n    os.execv(sys.argv[1], sys.argv[1:])\n"
               "_, status, usage = os.wait4(pid, 0)\nprint(os.waitstatus_to_exitcode(status), usage.ru_maxrss)\n")
    done = subprocess.run([sys.executable, "-S", "-c", starter, *argv], capture_output=True, text=True, check=True)
    status, peak_kib = done.stdout.split()
    if status != "0":
        sys.exit("pfgen estimate failed on the streamed record")
    peak_mib = int(peak_kib) / 1024
    print("4. pfgen estimate streaming %d continuous steps (%.0f MB record) of a one-state model: %.2f s, peak memory "
          "%.0f MiB" % (rows, os.path.getsize(path) / 1e6, seconds, peak_mib))


def main():
    parser = argparse.ArgumentParser()
    parser.add_argument("--build", default="build", help="the build with pfgen and the Python module")
    parser.add_argument("--bench", help="bench_record (default: BUILD/benchmarks/bench_record; it needs "
                                        "-DPFGEN_BUILD_BENCHMARKS=ON)")
    parser.add_argument("--work", default="build/bench_record")
    parser.add_argument("--repeats", type=int, default=7)
    parser.add_argument("--steps", type=int, default=1000000)
    parser.add_argument("--stream-rows", type=int, default=10000000)
    a = parser.parse_args()
    source = os.path.dirname(os.path.dirname(os.path.abspath(__file__)))
    pfgen = os.path.join(a.build, "generator/pfgen")
    os.makedirs(a.work, exist_ok=True)
    print("1. One log-likelihood evaluation of the Nile record (100 years):")
    ok = nile(a.build, a.bench or os.path.join(a.build, "benchmarks/bench_record"), source, a.repeats)

    record = os.path.join(a.work, "lorenz_%d.csv" % a.steps)
    lorenz_record(record, a.steps)
    seconds = command_seconds([pfgen, "estimate", os.path.join(source, "benchmarks/models/lorenz_multiplicative.yaml"),
                               "--data", record, "--filters", "optimal", "-q"], a.repeats)
    print("2. pfgen estimate over %d continuous steps of the 3-state Lorenz model (optimal filter, scores only): %.3f s"
          % (a.steps, seconds))
    seconds = command_seconds([pfgen, "fit", os.path.join(source, "examples/records/boarding_school.yaml"), "--data",
                               os.path.join(source, "examples/records/boarding_school.csv"), "--time-column", "day",
                               "--t0", "0", "--estimate", "beta,gamma", "--bounds", "beta=0.1:10,gamma=0.01:5", "-q"],
                              a.repeats)
    print("3. pfgen fit of the boarding-school record (14 days, SIR, beta and gamma): %.3f s" % seconds)
    stream(pfgen, source, a.work, a.stream_rows, a.repeats)
    sys.exit(0 if ok else 1)


main()
