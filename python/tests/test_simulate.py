"""simulate from Python is the command's simulate: the same table, CSV and numbers."""
import csv
import io
import math
import threading
import time

import numpy as np

import pytest

import pfgen

QUADRATIC = "examples/basin2006_quadratic.yaml"


def command_csv(text):
    rows = list(csv.reader(io.StringIO(text)))
    return rows[0], [[float(cell) if cell else math.nan for cell in row] for row in rows[1:]]


def test_simulate_is_the_commands(pfgen_command, work_dir):
    csv_path = work_dir / "runs.csv"
    done = pfgen_command.run("simulate", QUADRATIC, "--runs", "6", "--T", "2", "--dt", "0.001", "--seed", "7",
                             "--threads", "2", "--reference", "particles:200", "--x0", "prior",
                             "--record-points", "50", "-o", str(csv_path))
    result = pfgen.simulate(pfgen.Model.load(QUADRATIC), runs=6, T=2, dt=0.001, seed=7, threads=2, reference=200,
                            x0="prior", record_points=50)
    assert done.stdout == result.report + f"csv: {csv_path}\n"
    assert result.csv == csv_path.read_text()
    header, rows = command_csv(result.csv)
    assert list(result.series) == header
    for k, name in enumerate(header):
        np.testing.assert_array_equal(result.series[name], np.array([row[k] for row in rows]), err_msg=name)
    assert result.t[0] == 0 and result.t[-1] == 2
    # Each filter's RMS error per time and its NEES with the band, what one plots first.
    for name in ("optimal_err_x_rms", "optimal_nees", "optimal_nees_low", "optimal_nees_high"):
        assert name in result.series
    assert np.all(result.series["optimal_nees_low"] < result.series["optimal_nees_high"])
    assert np.all(np.isfinite(result.series["optimal_err_x_rms"]))
    assert result.runs == 6 and result.steps == 2000
    # The summary holds the table's numbers (which it prints in 4 digits).
    assert set(result.summary) == {"optimal", "ekf", "additive", "ekf-additive", "ekf-printed", "reference"}
    optimal = result.summary["optimal"]
    assert optimal["completed"] == 6 and optimal["diverged"] == 0
    row = next(line for line in result.report.splitlines() if line.split()[:2] == ["optimal", "x"])
    assert f"{optimal['rms'][0]:.4g}" == row.split()[2]
    assert optimal["reference_distance"].shape == (1,)
    # The reference's own Monte Carlo error, as the table prints it (4 digits), in its entry only.
    own = result.summary["reference"]["own_error"]
    assert own.shape == (1,) and optimal["own_error"].shape == (0,)
    reference_rows = [line.split() for line in result.report.splitlines() if line.split()[:2] == ["reference", "x"]]
    assert any(f"{own[0]:.4g}" in row for row in reference_rows)


def test_a_moment_filter_is_the_commands(pfgen_command):
    # closure3 leaves the realisable set in these runs (docs/theory.md §2.10): the summary counts the runs the
    # report lists under their own heading, among the diverged ones.
    done = pfgen_command.run("simulate", QUADRATIC, "--runs", "6", "--T", "4", "--filters", "optimal,closure3",
                             "--seed", "3", "--quiet")
    result = pfgen.simulate(pfgen.Model.load(QUADRATIC), runs=6, T=4, filters=["optimal", "closure3"], seed=3)
    assert result.report == done.stdout
    heading = next(k for k, line in enumerate(result.report.splitlines()) if "left the realisable set" in line)
    listed = result.report.splitlines()[heading + 1].split()
    assert listed[0] == "closure3:" and listed[2] == "runs"
    closure3 = result.summary["closure3"]
    assert 0 < closure3["unrealisable"] == int(listed[1]) <= closure3["diverged"]
    assert result.summary["optimal"]["unrealisable"] == 0


def test_thread_count_does_not_change_the_result():
    model = pfgen.Model.load(QUADRATIC)
    one = pfgen.simulate(model, runs=4, T=0.5, filters=["optimal", "ekf"], threads=1)
    two = model.simulate(runs=4, T=0.5, filters=["optimal", "ekf"], threads=2)
    assert one.csv == two.csv and one.report == two.report
    assert "model: basin2006_quadratic (examples/basin2006_quadratic.yaml)" in one.report


def test_batch_does_not_change_the_result():
    model = pfgen.Model.load(QUADRATIC)
    alone = pfgen.simulate(model, runs=9, T=0.5, filters=["optimal", "ekf"], threads=1, batch=1)
    side_by_side = pfgen.simulate(model, runs=9, T=0.5, filters=["optimal", "ekf"], threads=1)
    assert alone.csv == side_by_side.csv and alone.report == side_by_side.report
    for bad in (0, 1025, -1, 2.5):
        with pytest.raises(pfgen.Error, match="--batch"):
            pfgen.simulate(model, runs=2, T=0.1, batch=bad)


def test_stepping_is_the_commands(pfgen_command):
    done = pfgen_command.run("simulate", QUADRATIC, "--runs", "3", "--T", "1", "--filters", "optimal",
                             "--stepping", "generated", "--quiet")
    result = pfgen.simulate(pfgen.Model.load(QUADRATIC), runs=3, T=1, filters=["optimal"], stepping="generated")
    assert result.report == done.stdout
    assert "Stepping: generated" in result.report
    with pytest.raises(pfgen.Error, match="--stepping"):
        pfgen.simulate(pfgen.Model.load(QUADRATIC), runs=1, T=0.1, stepping="coarse")


def test_notes_are_kept(pfgen_command):
    result = pfgen.simulate(pfgen.Model.load(QUADRATIC), runs=2, T=1, filters=["optimal"])
    done = pfgen_command.run("simulate", QUADRATIC, "--runs", "2", "--T", "1", "--filters", "optimal", "--quiet")
    assert result.notes == done.stderr
    assert "report_times" in result.notes


def test_the_gil_is_released_while_it_runs():
    """Another Python thread keeps running while simulate runs."""
    model = pfgen.Model.load(QUADRATIC)
    pfgen.simulate(model, runs=1, T=0.1, filters=["optimal"])  # the plugin compiled and cached
    ticks = []
    done = threading.Event()

    def count():
        while not done.is_set():
            ticks.append(time.perf_counter())
            time.sleep(0.001)

    counter = threading.Thread(target=count)
    counter.start()
    start = time.perf_counter()
    pfgen.simulate(model, runs=200, T=2, threads=1)
    end = time.perf_counter()
    done.set()
    counter.join()
    during = [t for t in ticks if start < t < end]
    # Held, the GIL would let the counter tick at most a few times in a run of about a second.
    assert end - start > 0.2
    assert len(during) > 0.05 * (end - start) / 0.001, (len(during), end - start)


def test_parameters_are_set(pfgen_command):
    done = pfgen_command.run("simulate", "examples/van_der_pol.yaml", "--runs", "2", "--T", "1",
                             "--filters", "optimal", "--set", "mu=0.5", "--quiet")
    result = pfgen.simulate(pfgen.Model.load("examples/van_der_pol.yaml"), runs=2, T=1, filters=["optimal"],
                            parameters={"mu": 0.5})
    assert result.report == done.stdout


def test_other_threads_run_while_one_waits_for_pfgen():
    """A thread reading a model's kinds while another simulates waits without the GIL."""
    model = pfgen.Model.load(QUADRATIC)
    pfgen.simulate(model, runs=1, T=0.1, filters=["ekf"])
    ticks, done = [], threading.Event()

    def count():
        while not done.is_set():
            ticks.append(time.perf_counter())
            time.sleep(0.001)

    simulation = threading.Thread(target=lambda: pfgen.simulate(model, runs=300, T=2, threads=1, filters=["ekf"]))
    counter = threading.Thread(target=count)
    simulation.start()
    time.sleep(0.05)
    counter.start()
    start = time.perf_counter()
    kinds = model.kinds          # waits for the simulation
    pfgen.Model.load(QUADRATIC)  # a model made and dropped meanwhile
    end = time.perf_counter()
    simulation.join()
    done.set()
    counter.join()
    assert kinds[0] == "optimal"
    during = [t for t in ticks if start < t < end]
    assert end - start > 0.1 and len(during) > 0.05 * (end - start) / 0.001, (len(during), end - start)


def test_a_daemon_thread_in_pfgen_at_exit():
    """The interpreter exits cleanly while a daemon thread is inside a pfgen call."""
    import subprocess
    import sys
    script = ("import threading, time, pfgen\n"
              f"m = pfgen.Model.load({QUADRATIC!r})\n"
              "threading.Thread(target=lambda: [m.derive('optimal').text for _ in range(100000)], daemon=True).start()\n"
              "time.sleep(0.2)\n")
    for _ in range(3):
        done = subprocess.run([sys.executable, "-c", script], capture_output=True, text=True, timeout=60)
        assert done.returncode == 0, done.stderr


STIFF = """name: stiff
states: [x]
drift: ["-x^3"]
diffusion: [["1"]]
observation: {A: [["1"]], B: [["1e-4"]]}
initial: {x0: [3], m0: [0], P0: [[100]]}
simulation: {T: 1, dt: 0.1}
"""


def test_runs_stopped_as_too_stiff_are_counted_as_the_report_lists_them(pfgen_command, work_dir):
    # A prior variance of 100 against samples of noise 1e-4 at dt = 0.1: the first grid step would need more
    # sub-steps than simulate allows, in every run and for every filter.
    model = work_dir / "stiff.yaml"
    model.write_text(STIFF)
    done = pfgen_command.run("simulate", str(model), "--runs", "4", "--filters", "optimal,ekf", "--quiet",
                             "--cache-dir", str(work_dir / "cache"))
    result = pfgen.simulate(pfgen.Model.load(str(model)), runs=4, filters=["optimal", "ekf"],
                            cache_dir=str(work_dir / "cache"))
    assert result.report == done.stdout
    lines = result.report.splitlines()
    heading = next(k for k, line in enumerate(lines) if line.startswith("Runs stopped as too stiff for dt"))
    assert lines[heading + 1:heading + 3] == ["  optimal: 4 runs", "  ekf: 4 runs"]
    for name in ("optimal", "ekf"):
        summary = result.summary[name]
        assert (summary["too_stiff"], summary["diverged"], summary["undefined"], summary["unrealisable"]) == (4, 4, 0, 0)
