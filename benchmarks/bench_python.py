"""What calling pfgen through Python costs: the same work from the pfgen program and from the
Python module, measured side by side in one run (docs/benchmarks.md, "Python against the command").

    PYTHONPATH=build/python python3 benchmarks/bench_python.py [--build build] [--repeats 5]

Cases: deriving the dense cubic n = 10 model (its optimal filter as text), and simulating
Basin, Perez & Skliar 2006's example with its model file's settings (200 runs, T = 9.2,
dt = 1e-4, 5 filters) on every core, with the time series the module returns (the command's
CSV). For each case and repeat, in turn:
  command_s   the whole command, `pfgen derive MODEL` or `pfgen simulate MODEL -q -o FILE.csv`, as a
              process, its standard output discarded (program start, reading the model, the work,
              exit);
  python_s    the same work in a running Python: pfgen.Model.load(path).derive().text, or
              pfgen.simulate(pfgen.Model.load(path)) with its result's arrays;
and once, python_start_s: a new interpreter importing pfgen (numpy with it), which a script pays
once, whatever it then does. Medians over the repeats (after one warm-up of each, which also
compiles and caches simulate's plugin); ratio = python_s / command_s. The two outputs are
compared byte for byte first.
"""
import argparse
import os
import statistics
import subprocess
import sys
import tempfile
import time

import pfgen

ROOT = os.path.abspath(os.path.join(os.path.dirname(__file__), ".."))


def seconds(work):
    start = time.perf_counter()
    work()
    return time.perf_counter() - start


def run_quietly(command):
    subprocess.run(command, check=True, stdout=subprocess.DEVNULL, stderr=subprocess.DEVNULL)


def main():
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--build", default=os.path.join(ROOT, "build"))
    parser.add_argument("--repeats", type=int, default=5)
    args = parser.parse_args()
    program = os.path.join(args.build, "generator", "pfgen")
    dense_yaml = os.path.join(args.build, "benchmarks", "dense_cubic_yaml")
    work_dir = tempfile.TemporaryDirectory()  # removed when the script ends
    work = work_dir.name
    dense = os.path.join(work, "dense_cubic_10.yaml")
    with open(dense, "w") as f:
        subprocess.run([dense_yaml, "10"], check=True, stdout=f)
    quadratic = os.path.join(ROOT, "examples", "basin2006_quadratic.yaml")

    def derive_in_python():
        return pfgen.Model.load(dense).derive().text

    def simulate_in_python():
        result = pfgen.simulate(pfgen.Model.load(quadratic))
        return result.report, result.series

    cases = [
        ("derive dense cubic n = 10", [program, "derive", dense], derive_in_python),
        ("simulate quadratic example", [program, "simulate", quadratic, "-q", "-o", os.path.join(work, "runs.csv")],
         simulate_in_python),
    ]
    # The same output first: the text, and the simulation's table (the command adds nothing to it).
    derived = subprocess.run([program, "derive", dense], check=True, capture_output=True, text=True).stdout
    assert derived == derive_in_python(), "derive: the module's text differs from the command's"
    table = subprocess.run(cases[1][1], check=True, capture_output=True, text=True).stdout
    with open(os.path.join(work, "runs.csv")) as f:
        csv = f.read()
    result = pfgen.simulate(pfgen.Model.load(quadratic))
    assert table.startswith(result.report) and csv == result.csv, "simulate: the module's results differ from the command's"

    start = [seconds(lambda: run_quietly([sys.executable, "-c", "import pfgen"])) for _ in range(args.repeats)]
    print(f"python_start_s (a new interpreter importing pfgen): {statistics.median(start):.3f}")
    print(f"{'case':<28} {'command_s':>10} {'python_s':>10} {'ratio':>7}  {'command min..max':>17}  {'python min..max':>16}")
    for name, command, in_python in cases:
        run_quietly(command)
        in_python()
        command_times, python_times = [], []
        for _ in range(args.repeats):  # interleaved, so that a slow spell of the machine hits both
            command_times.append(seconds(lambda: run_quietly(command)))
            python_times.append(seconds(in_python))
        c, p = statistics.median(command_times), statistics.median(python_times)
        print(f"{name:<28} {c:>10.3f} {p:>10.3f} {p / c:>6.2f}x  {min(command_times):>7.3f}..{max(command_times):<8.3f}"
              f"  {min(python_times):>6.3f}..{max(python_times):<8.3f}")


if __name__ == "__main__":
    main()
