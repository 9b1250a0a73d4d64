#!/usr/bin/python3
"""Cost of the moment filters (closure3, closure4) against the optimal filter, on the dense cubic models.

For n = 1..4 states (tests/support/dense_cubic_system.hpp's systems, written by dense_cubic_yaml: every
monomial up to degree 3 in each drift component, linear multiplicative noise g = diag(c_i0 + sum_k c_ik x_k),
A = B = I), and for each of optimal, closure3 and closure4:
  - equations: the filter's state variables (m, P and the central moments carried), one equation each;
  - terms: the terms of all its equations as `pfgen derive --format json` prints them (m's drift, the
    upper triangle of P's, the higher moments' drifts, and every gain entry);
  - derive_ms: the derivation's seconds (`pfgen derive --filter K --format json --timing`: the derive
    phase alone), median of REPEATS runs;
  - ops: operations of the generated code after common-subexpression elimination (`pfgen codegen
    --stats`: ops_cse, all functions of the filter);
  - ns/step: CPU ns per grid step of the generated C++ step() in `pfgen simulate --stepping generated`
    (one step() per grid step, the three filters in one plugin, one thread: RUNS runs, T = 0.2,
    dt = 1e-3, x0 = m0 = 0, P0 = 0.1 I: short, since the dense cubic truths blow up within a time
    unit), and how many runs each filter completed (a moment filter stops a run where its moments
    leave the realisable set).
Each ratio is the filter's value over the optimal filter's for the same n, measured in the same run.

Usage: benchmarks/bench_closure.py [BUILD_DIR] [REPEATS] [RUNS]   (defaults: build, 7, 100)
BUILD_DIR needs pfgen and dense_cubic_yaml (configure with -DPFGEN_BUILD_BENCHMARKS=ON).
"""
import json
import os
import re
import statistics
import subprocess
import sys
import tempfile

FILTERS = ["optimal", "closure3", "closure4"]
SIZES = [1, 2, 3, 4]


def count_terms(expression):
    """Terms of one printed polynomial: its top-level ' + ' and ' - ' separators, plus one ('0' has none)."""
    if expression.strip() == "0":
        return 0
    depth, terms = 0, 1
    for k, c in enumerate(expression):
        if c == "(":
            depth += 1
        elif c == ")":
            depth -= 1
        elif depth == 0 and c in "+-" and k > 0 and expression[k - 1] == " " and expression[k + 1 : k + 2] == " ":
            terms += 1
    return terms


def equation_terms(report):
    """All terms of a filter's equations in its JSON report."""
    n = sum(1 for v in report["variables"] if v.startswith("m"))
    total = sum(count_terms(e) for e in report["m_drift"])
    total += sum(count_terms(report["P_drift"][i][j]) for i in range(n) for j in range(i, n))
    total += sum(count_terms(e) for e in report.get("moment_drift", []))
    for key in ("gain", "moment_gain"):  # [i][r], [moment][r]
        total += sum(count_terms(e) for row in report.get(key, []) for e in row)
    if "P_gain" in report:  # [i][j][r], symmetric in i, j
        total += sum(count_terms(e) for i in range(n) for j in range(i, n) for e in report["P_gain"][i][j])
    return total


def run(command, **kwargs):
    return subprocess.run(command, check=True, capture_output=True, text=True, **kwargs)


def main():
    build = sys.argv[1] if len(sys.argv) > 1 else "build"
    repeats = int(sys.argv[2]) if len(sys.argv) > 2 else 7
    runs = int(sys.argv[3]) if len(sys.argv) > 3 else 100
    pfgen = os.path.join(build, "generator", "pfgen")
    writer = os.path.join(build, "benchmarks", "dense_cubic_yaml")
    for tool in (pfgen, writer):
        if not os.access(tool, os.X_OK):
            sys.exit(f"bench_closure: {tool} is missing (configure with -DPFGEN_BUILD_BENCHMARKS=ON, build pfgen and dense_cubic_yaml)")
    rows = []
    with tempfile.TemporaryDirectory() as work:
        for n in SIZES:
            model = os.path.join(work, f"dense_cubic_{n}.yaml")
            P0 = "[" + ", ".join("[" + ", ".join("0.1" if i == j else "0" for j in range(n)) + "]" for i in range(n)) + "]"
            with open(model, "w") as out:
                out.write(run([writer, str(n)]).stdout)
                zeros = ", ".join(["0"] * n)
                out.write(f"initial: {{x0: [{zeros}], m0: [{zeros}], P0: {P0}}}\n")
            # One simulation of the three filters: ns per step and completed runs.
            sim = run([pfgen, "simulate", model, "--filters", ",".join(FILTERS), "--runs", str(runs), "--T", "0.2",
                       "--dt", "0.001", "--threads", "1", "--seed", "1", "--stepping", "generated",
                       "--cache-dir", os.path.join(work, "cache")])
            ns = {m.group(1): float(m.group(2))
                  for m in re.finditer(r"^  (\S+): .* ns/step \(CPU ([0-9.]+) ns/step\)", sim.stderr, re.M)}
            counted = sim.stdout.split("Runs counted")[1].split("\n\n")[0]
            completed = {m.group(1): int(m.group(2)) for m in re.finditer(r"^(\S+)\s+(\d+)$", counted, re.M)}
            for kind in FILTERS:
                seconds = []
                for _ in range(repeats):
                    timing = os.path.join(work, "timing.json")
                    report = json.loads(run([pfgen, "derive", "--filter", kind, "--format", "json", "--timing", timing,
                                             model]).stdout)
                    with open(timing) as t:
                        seconds.append(json.load(t)["derive_seconds"])
                stats = json.loads(run([pfgen, "codegen", "--stats", "--filter", kind, model, "-o",
                                        os.path.join(work, "code")]).stdout.splitlines()[0])
                rows.append({"n": n, "filter": kind, "equations": len(report["variables"]),
                             "terms": equation_terms(report), "derive_ms": 1000 * statistics.median(seconds),
                             "ops": stats["ops_cse"], "ns": ns[kind], "completed": completed[kind]})
    print(f"| n | filter | equations | terms | ×opt | derive ms | ×opt | ops | ×opt | ns/step | ×opt | runs completed |")
    print("|---|---|---:|---:|---:|---:|---:|---:|---:|---:|---:|---:|")
    for row in rows:
        base = next(r for r in rows if r["n"] == row["n"] and r["filter"] == "optimal")
        ratio = lambda key: f"{row[key] / base[key]:.1f}"
        print(f"| {row['n']} | {row['filter']} | {row['equations']} | {row['terms']} | {ratio('terms')} "
              f"| {row['derive_ms']:.2f} | {ratio('derive_ms')} | {row['ops']} | {ratio('ops')} "
              f"| {row['ns']:.0f} | {ratio('ns')} | {row['completed']}/{runs} |")
    print(f"\n(derive: median of {repeats}; ns/step: CPU, {runs} runs of T = 0.2, dt = 1e-3, 1 thread, --stepping generated)")


if __name__ == "__main__":
    main()
