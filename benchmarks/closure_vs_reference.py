"""The moment filters (closure3, closure4) and the Gaussian-closure filters against the particle
reference, run by run (docs/reproductions/moment-filters.md).

    /usr/bin/python3 benchmarks/closure_vs_reference.py MODEL [--runs 200] [--particles 1000]
        [--dt DT] [--T T] [--jobs 2] [--cache DIR] [--pfgen build/generator/pfgen]

pfgen's report gives each filter's RMS error and its distance to the reference over the runs where
that filter reached T, so two filters' rows may cover different runs, and it has no paired
difference of mean-square errors. This script runs `pfgen simulate MODEL --runs 1 --seed s
--x0 prior --reference particles:N -o FILE.csv --stops-csv FILE` for s = 1..runs (each seed an
independent run whose truth is drawn from the filters' prior) and reads every run's time series
back, on `--record-points` equally spaced points of [0, T]. It prints:
  - the stops: in how many runs each filter stopped, by kind (`realisable`: a moment filter's
    moments left the realisable set; `diverged`: m or P passed simulate's bound), and the median stop
    time;
  - over the runs where every filter and the reference reached T (the survivors; a line saying so when
    there is none), per state: each filter's excess
    mean-square error MSE(x - m) - MSE(x - m_ref) and its distance RMS(m - m_ref), each with its
    standard error over runs (paired: the same runs and truths for every filter), and the
    reference's own Monte Carlo error (pfgen's, from a second independent set of N particles);
  - the target's test: closure4's excess minus half of optimal's, paired run by run (cd-closure4's
    and cd-optimal's for sampled observations: the baseline below);
  - for each filter that stopped: the baseline's excess on the runs where that filter stopped and
    where it did not, which shows whether the survivors are the easy runs (a line saying so when no
    filter stopped).
Each run's figures are kept in --cache (one JSON file per seed), so a second call with more runs
only runs the new seeds.
"""
import argparse
import concurrent.futures
import json
import math
import os
import subprocess
import sys
import tempfile
import time

import numpy as np

ROOT = os.path.abspath(os.path.join(os.path.dirname(__file__), ".."))
FILTERS = "optimal,ekf,ukf,closure3,closure4"


def baseline(filters):
    """The Gaussian closure the target compares with: cd-optimal for sampled observations."""
    return "cd-optimal" if "cd-optimal" in filters else "optimal"


def target(filters):
    """The order-4 moment filter of the target."""
    return "cd-closure4" if "cd-closure4" in filters else "closure4"


def parse_args():
    p = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    p.add_argument("model")
    p.add_argument("--pfgen", default=os.path.join(ROOT, "build", "generator", "pfgen"))
    p.add_argument("--filters", default=FILTERS)
    p.add_argument("--runs", type=int, default=200)
    p.add_argument("--particles", type=int, default=1000)
    p.add_argument("--dt", type=float)
    p.add_argument("--T", type=float)
    p.add_argument("--record-points", type=int, default=1001)
    p.add_argument("--jobs", type=int, default=2, help="pfgen processes side by side, one thread each")
    p.add_argument("--cache", help="directory of per-run results (default: a temporary one, removed at the end)")
    return p.parse_args()


def reference_own_error(report, states):
    """The reference rows' "m_ref's own error" column, per state (nan when absent)."""
    own = {}
    for line in report.splitlines():
        tok = line.split()
        if len(tok) >= 4 and tok[0] == "reference" and tok[1] in states and tok[2].isdigit():
            try:
                own[tok[1]] = float(tok[3])
            except ValueError:
                pass
    return {s: own.get(s, float("nan")) for s in states}


def one_run(args, filters, seed, workdir):
    csv_path = os.path.join(workdir, "run%d.csv" % seed)
    stops_path = os.path.join(workdir, "run%d.stops.csv" % seed)
    cmd = [args.pfgen, "simulate", args.model, "--filters", ",".join(filters), "--runs", "1",
           "--seed", str(seed), "--threads", "1", "--x0", "prior",
           "--reference", "particles:%d" % args.particles, "--record-points",
           str(args.record_points), "-o", csv_path, "--stops-csv", stops_path, "-q"]
    if args.dt is not None:
        cmd += ["--dt", repr(args.dt)]
    if args.T is not None:
        cmd += ["--T", repr(args.T)]
    start = time.monotonic()
    out = subprocess.run(cmd, capture_output=True, text=True)
    wall = time.monotonic() - start
    if out.returncode != 0:
        sys.exit("closure_vs_reference: %s failed:\n%s" % (" ".join(cmd), out.stderr))
    data = np.genfromtxt(csv_path, delimiter=",", names=True, deletechars="")  # keep "cd-optimal"
    states = [n[len("reference_m_"):] for n in data.dtype.names if n.startswith("reference_m_")]
    stops, psd_losses = {}, {}
    with open(stops_path) as f:
        next(f)
        for line in f:
            source, event, _, t = line.strip().split(",")
            if event == "psd_loss":  # recorded, but the filter goes on
                psd_losses[source] = float(t)
                continue
            kind = "realisable" if event == "unrealisable" else event
            stops[source] = {"kind": kind, "t": float(t)}
    rec = {"seed": seed, "wall_s": wall, "states": states, "stops": stops,
           "psd_losses": psd_losses, "own_error": reference_own_error(out.stdout, states), "mse": {}, "dist": {}}
    for s in states:
        x = data["truth_" + s]
        mref = data["reference_m_" + s]
        if "reference" not in stops and "truth" not in stops:
            rec["mse"].setdefault("reference", {})[s] = float(np.mean((x - mref) ** 2))
        for f in filters:
            if f in stops or "reference" in stops or "truth" in stops:
                continue
            m = data["%s_m_%s" % (f, s)]
            rec["mse"].setdefault(f, {})[s] = float(np.mean((x - m) ** 2))
            rec["dist"].setdefault(f, {})[s] = float(np.mean((m - mref) ** 2))
    # Every filter up to the run's first stop, so that no run is left out: the window [0, tau),
    # tau the earliest stop of any filter ([0, T] if none stopped; a stop at T itself, at the last
    # sample, leaves T out). A stop's time and the record's grid are computed apart (39 x 0.1 and
    # 390 x 0.01 differ in the last bit), so a grid point within rounding of tau is tau.
    t = data["t"]
    tau = min([v["t"] for v in stops.values()] + [float(t[-1])])
    keep = t < tau - 1e-9 * max(1.0, abs(tau)) if stops else np.ones_like(t, dtype=bool)
    rec["tau"] = tau
    rec["pre"] = {}
    if "reference" not in stops and "truth" not in stops and keep.any():
        for s in states:
            x, mref = data["truth_" + s][keep], data["reference_m_" + s][keep]
            rec["pre"].setdefault("reference", {})[s] = [float(np.mean((x - mref) ** 2)), 0.0]
            for f in filters:
                m = data["%s_m_%s" % (f, s)][keep]
                rec["pre"].setdefault(f, {})[s] = [float(np.mean((x - m) ** 2)),
                                                   float(np.mean((m - mref) ** 2))]
    os.remove(csv_path)
    os.remove(stops_path)
    return rec


def mean_se(values):
    v = np.asarray(values, dtype=float)
    if len(v) < 2:
        return float(v.mean()) if len(v) else float("nan"), float("nan")
    return float(v.mean()), float(v.std(ddof=1) / math.sqrt(len(v)))


def fmt(mean, se):
    return "%+.4g ± %.2g" % (mean, se)


def rms_fmt(ms_values):
    """RMS from per-run mean squares, its standard error by the delta method."""
    m, se = mean_se(ms_values)
    r = math.sqrt(max(m, 0.0))
    return "%.4g ± %.2g" % (r, se / (2 * r) if r > 0 else float("nan"))


def comparison_table(runs, filters, groups, mse, dist, with_reference):
    """Per group of states: each filter's excess MSE over the reference's and its distance, paired
    over `runs`; mse(r, f, s) and dist(r, f, s) read a run's mean squares."""
    print("%-10s %-6s %22s %20s %18s" % ("filter", "state", "excess MSE", "RMS(m - m_ref)",
                                        "excess / optimal's"))
    for label, ss in groups:
        def excess(r, f):
            return sum(mse(r, f, s) - mse(r, "reference", s) for s in ss)

        def distance(r, f):
            return sum(dist(r, f, s) for s in ss)

        base, top = baseline(filters), target(filters)
        opt = mean_se([excess(r, base) for r in runs])[0] if base in filters else None
        for f in filters:
            e = mean_se([excess(r, f) for r in runs])
            ratio = "%.2f" % (e[0] / opt) if opt else "-"
            print("%-10s %-6s %22s %20s %18s" % (f, label, fmt(*e),
                                                rms_fmt([distance(r, f) for r in runs]), ratio))
        if with_reference:
            ref_ms = mean_se([sum(mse(r, "reference", s) for s in ss) for r in runs])
            own = [sum(r["own_error"][s] ** 2 for s in ss) for r in runs]
            print("%-10s %-6s %22s %20s   (MSE(x - m_ref) = %.4g ± %.2g; m_ref's own error^2 %.2g)"
                  % ("reference", label, "", "", ref_ms[0], ref_ms[1], float(np.nanmean(own))))
        if base in filters and top in filters:
            half = mean_se([excess(r, top) - 0.5 * excess(r, base) for r in runs])
            halfd = mean_se([distance(r, top) - 0.5 * distance(r, base) for r in runs])
            print("%-10s %-6s target: %s's excess - %s's / 2 = %s (%.1f standard errors)"
                  "; in mean squared distance %s (%.1f)"
                  % ("", label, top, base, fmt(*half), half[0] / half[1] if half[1] > 0 else float("nan"),
                     fmt(*halfd), halfd[0] / halfd[1] if halfd[1] > 0 else float("nan")))
    print()


def main():
    args = parse_args()
    filters = args.filters.split(",")
    # Without --cache the runs' figures go to a temporary directory, removed when the script ends.
    own_cache = None if args.cache else tempfile.TemporaryDirectory(prefix="closure_vs_reference.")
    cache = args.cache or own_cache.name
    os.makedirs(cache, exist_ok=True)
    records = {}
    todo = []
    for seed in range(1, args.runs + 1):
        path = os.path.join(cache, "seed%d.json" % seed)
        if os.path.exists(path):
            with open(path) as f:
                records[seed] = json.load(f)
        else:
            todo.append(seed)
    started = time.monotonic()
    with tempfile.TemporaryDirectory() as workdir, \
            concurrent.futures.ThreadPoolExecutor(max_workers=args.jobs) as pool:
        for rec in pool.map(lambda s: one_run(args, filters, s, workdir), todo):
            with open(os.path.join(cache, "seed%d.json" % rec["seed"]), "w") as f:
                json.dump(rec, f)
            records[rec["seed"]] = rec
    wall = time.monotonic() - started
    runs = [records[s] for s in sorted(records)]
    states = runs[0]["states"]
    n = len(runs)

    print("%s: %d runs (seeds 1..%d), truths from the prior, reference particles:%d, "
          "%d points of [0, T]; %d new runs in %.0f s wall with %d jobs (%.1f s per run)"
          % (args.model, n, args.runs, args.particles, args.record_points, len(todo), wall,
             args.jobs, sum(r["wall_s"] for r in runs) / n))
    print()
    print("Stops (runs where the filter stopped before T; kind: realisable = moments left the "
          "realisable set, diverged = m or P passed simulate's bound; P not PSD: runs where P lost "
          "positive semi-definiteness, recorded, the filter going on):")
    print("%-10s %8s  %-28s %14s %10s" % ("source", "stopped", "kinds", "median stop t",
                                          "P not PSD"))
    for src in ["truth", "reference"] + filters:
        hit = [r["stops"][src] for r in runs if src in r["stops"]]
        kinds = {}
        for h in hit:
            kinds[h["kind"]] = kinds.get(h["kind"], 0) + 1
        kinds_s = ", ".join("%s %d" % kv for kv in sorted(kinds.items())) or "-"
        med = "%.3g" % float(np.median([h["t"] for h in hit])) if hit else "-"
        psd = sum(1 for r in runs if src in r.get("psd_losses", {}))
        print("%-10s %4d/%-3d  %-28s %14s %10d" % (src, len(hit), n, kinds_s, med, psd))
    print()

    groups = [(s, [s]) for s in states] + ([("sum", states)] if len(states) > 1 else [])
    common = [r for r in runs if all(f in r["dist"] for f in filters)]
    if common:
        print("Over the %d runs where every filter and the reference reached T (paired; excess = "
              "MSE(x - m) - MSE(x - m_ref), mean ± standard error over runs):" % len(common))
        comparison_table(common, filters, groups, lambda r, f, s: r["mse"][f][s],
                         lambda r, f, s: r["dist"][f][s], with_reference=True)
    else:
        print("No run where every filter and the reference reached T: no table of the survivors.")
        print()

    pre = [r for r in runs if len(r.get("pre", {})) == len(filters) + 1]
    if pre:
        print("Over all %d runs, each up to its first stop (tau = the earliest stop of any filter, "
              "else T; median tau %.3g; no run left out, early times weigh more):"
              % (len(pre), float(np.median([r["tau"] for r in pre]))))
        comparison_table(pre, filters, groups, lambda r, f, s: r["pre"][f][s][0],
                         lambda r, f, s: r["pre"][f][s][1], with_reference=False)

    usable = [r for r in runs if "truth" not in r["stops"] and "reference" not in r["stops"]]
    base = baseline(filters)
    compared = [f for f in filters if f != base and base in filters
                and any(f in r["stops"] and base in r["mse"] for r in usable)]
    if not compared:
        print("Are the survivors the easy runs? No filter stopped in a run the reference and the truth "
              "finished: no table.")
        return
    print("Are the survivors the easy runs? %s's excess MSE and the reference's MSE(x - m_ref) "
          "(summed over states) on the runs where a filter stopped and on those where it reached T; "
          "the filter's own excess on the latter:" % base)
    print("%-10s %24s %24s %26s %22s" % ("filter", "runs it stopped in", "runs it reached T",
                                         "its own excess there", "MSE(x - m_ref): s / r"))
    for f in compared:
        stopped = [r for r in usable if f in r["stops"] and base in r["mse"]]
        kept = [r for r in usable if f not in r["stops"] and base in r["mse"]]
        ex = lambda r, g: sum(r["mse"][g][s] - r["mse"]["reference"][s] for s in states)
        ref = lambda r: sum(r["mse"]["reference"][s] for s in states)
        a = mean_se([ex(r, base) for r in stopped])
        b = mean_se([ex(r, base) for r in kept])
        c = mean_se([ex(r, f) for r in kept])
        refs = "%.3g / %.3g" % (mean_se([ref(r) for r in stopped])[0],
                                mean_se([ref(r) for r in kept])[0] if kept else float("nan"))
        print("%-10s %24s %24s %26s %22s" % (f, "%d: %s" % (len(stopped), fmt(*a)),
                                             "%d: %s" % (len(kept), fmt(*b)), fmt(*c), refs))

if __name__ == "__main__":
    main()
