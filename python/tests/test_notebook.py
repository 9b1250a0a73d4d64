"""What a notebook user reaches for: the summary as a pandas table, the --plot panels as a
matplotlib Figure, a progress line while simulate runs, and an import error that names the
interpreter the module was built for. pandas and matplotlib are optional: without them the call
that needs one says which Debian package gives it."""
import io
import os
import re
import subprocess
import sys

import numpy as np
import pytest

import pfgen

QUADRATIC = "examples/basin2006_quadratic.yaml"
VAN_DER_POL = "examples/van_der_pol.yaml"


@pytest.fixture(scope="module")
def van_der_pol():
    """Two states, four filters and the particle reference."""
    return pfgen.simulate(pfgen.Model.load(VAN_DER_POL), runs=6, T=2, reference=100, threads=2, record_points=40)


def test_the_summary_as_a_pandas_table(van_der_pol):
    frame = van_der_pol.to_pandas()
    assert frame.index.names == ["filter", "state"]
    filters = ["optimal", "additive", "ekf-additive", "ekf", "reference"]
    assert list(frame.index) == [(f, x) for f in filters for x in ("x1", "x2")]
    assert list(frame.columns) == list(van_der_pol.summary["optimal"])
    for name in filters:
        for i, state in enumerate(("x1", "x2")):
            row = frame.loc[(name, state)]
            assert row["completed"] == van_der_pol.summary[name]["completed"] == 6
            assert row["rms"] == van_der_pol.summary[name]["rms"][i]
    assert frame.loc[("ekf", "x2"), "reference_distance"] == van_der_pol.summary["ekf"]["reference_distance"][1]
    # The reference has no distance to itself: NaN, not a number of another row.
    assert np.isnan(frame.loc[("reference", "x1"), "reference_distance"])


def test_the_series_as_a_pandas_table(van_der_pol):
    frame = van_der_pol.to_pandas("series")
    assert frame.index.name == "t"
    np.testing.assert_array_equal(frame.index.to_numpy(), van_der_pol.t)
    assert list(frame.columns) == [name for name in van_der_pol.series if name != "t"]
    np.testing.assert_array_equal(frame["optimal_err_x2"].to_numpy(), van_der_pol.series["optimal_err_x2"])
    with pytest.raises(pfgen.Error, match="table is 'summary' or 'series'"):
        van_der_pol.to_pandas("table")


def test_the_plot_has_the_commands_panels(van_der_pol):
    figure = van_der_pol.plot()
    assert figure._suptitle.get_text() == "van_der_pol: estimation errors x - m"
    axes = figure.axes
    assert [a.get_title() for a in axes] == ["x1: run 0", "x1: median over 6 runs, 5-95 % band",
                                             "x2: run 0", "x2: median over 6 runs, 5-95 % band"]
    filters = ["optimal", "additive", "ekf-additive", "ekf"]
    series, t = van_der_pol.series, van_der_pol.t
    for i, x in enumerate(("x1", "x2")):
        shown, bands = axes[2 * i], axes[2 * i + 1]
        assert shown.get_ylabel() == f"{x} - m" and shown.get_xlabel() == "t"
        lines = shown.get_lines()
        assert [line.get_label() for line in lines] == filters + ["reference (N=100)"]
        for line, column in zip(lines, [f"{f}_err_{x}" for f in filters] + [f"reference_err_{x}"]):
            np.testing.assert_array_equal(line.get_xdata(), t)
            np.testing.assert_array_equal(line.get_ydata(), series[column])
        # Each filter its own colour, dash and width, the first widest; the reference black, dashed.
        assert len({(line.get_color(), str(line.get_linestyle())) for line in lines}) == 5
        assert [line.get_linewidth() for line in lines[:4]] == sorted((line.get_linewidth() for line in lines[:4]), reverse=True)
        assert lines[4].get_color() == "#000000" and lines[4].get_linestyle() == "--"
        # The first filter's band filled; the others' as their two edges; then the medians.
        (band,) = bands.collections
        assert band.get_label() == "optimal 5-95 %"
        path = band.get_paths()[0].vertices
        assert np.isclose(path[:, 1].max(), series[f"optimal_err_{x}_q95"].max())
        assert np.isclose(path[:, 1].min(), series[f"optimal_err_{x}_q05"].min())
        labels = [line.get_label() for line in bands.get_lines()]
        edges = [label for f in filters[1:] for label in (f"{f} 5-95 %", "_child")]
        assert [re.sub(r"_child\d+", "_child", label) for label in labels] == edges + filters
        for line, f in zip(bands.get_lines()[-4:], filters):
            np.testing.assert_array_equal(line.get_ydata(), series[f"{f}_err_{x}_q50"])
    # It renders (Agg), as a PNG.
    png = io.BytesIO()
    figure.savefig(png, format="png")
    assert png.getvalue().startswith(b"\x89PNG\r\n\x1a\n")


def test_the_plot_clipped_as_plot_ylim(van_der_pol):
    axes = van_der_pol.plot(ylim=0.5).axes
    assert axes[0].get_title() == "x1: run 0 (clipped at +-0.5)"
    assert all(a.get_ylim() == (-0.5, 0.5) for a in axes)
    for bad in (-1, float("inf"), "x"):
        with pytest.raises(pfgen.Error, match="--plot-ylim"):
            van_der_pol.plot(ylim=bad)


def test_without_pandas_or_matplotlib_the_error_names_the_package(van_der_pol, monkeypatch):
    # A module set to None in sys.modules cannot be imported, as on a machine without it.
    monkeypatch.setitem(sys.modules, "pandas", None)
    with pytest.raises(ImportError, match=r"Simulation.to_pandas needs pandas.*apt-get install python3-pandas"):
        van_der_pol.to_pandas()
    monkeypatch.setitem(sys.modules, "matplotlib", None)
    monkeypatch.setitem(sys.modules, "matplotlib.figure", None)
    with pytest.raises(ImportError, match=r"Simulation.plot needs matplotlib.*apt-get install python3-matplotlib"):
        van_der_pol.plot()
    # Everything else works without them.
    assert van_der_pol.summary["optimal"]["completed"] == 6
    assert pfgen.simulate(pfgen.Model.load(QUADRATIC), runs=1, T=0.1, filters="ekf").runs == 1


PROGRESS = re.compile(r"\rsimulate \[([#.]{40})\] (\d+)/(\d+) runs, \d+ s elapsed, ~\d+ s left ")
CLEARED = "\r" + " " * 108 + "\r"  # the command's: the bar's width, 60 and the label's blanked


def progress_draws(text, runs):
    """The draws of a progress line, checked to be the command's, and what follows them."""
    draws = PROGRESS.findall(text)
    assert draws, repr(text)
    done = [int(d) for _, d, _ in draws]
    assert all(int(total) == runs for _, _, total in draws)
    assert done == sorted(done) and 1 <= done[0] and done[-1] <= runs
    for bar, d, _ in draws:
        assert bar.count("#") == int(d) * 40 // runs
    return PROGRESS.sub("", text)


def test_progress_is_the_commands_line(capsys):
    model = pfgen.Model.load(QUADRATIC)
    quiet = pfgen.simulate(model, runs=24, T=1, filters=["optimal", "ekf"], threads=2)
    assert capsys.readouterr() == ("", "")  # off by default
    stream = io.StringIO()
    shown = pfgen.simulate(model, runs=24, T=1, filters=["optimal", "ekf"], threads=2, progress=stream)
    assert progress_draws(stream.getvalue(), 24) == CLEARED  # drawn, then cleared, as on a terminal
    assert shown.report == quiet.report and shown.csv == quiet.csv
    assert capsys.readouterr() == ("", "")
    pfgen.simulate(model, runs=5, T=1, filters=["optimal"], progress=True)
    out, err = capsys.readouterr()
    assert out == "" and progress_draws(err, 5) == CLEARED
    with pytest.raises(pfgen.Error, match="progress: expected True, False or a text stream, got 'yes'"):
        pfgen.simulate(model, runs=5, T=1, progress="yes")


def test_progress_of_a_refused_simulation_writes_nothing():
    stream = io.StringIO()
    with pytest.raises(pfgen.Error, match="--runs"):
        pfgen.simulate(pfgen.Model.load(QUADRATIC), runs=0, progress=stream)
    assert stream.getvalue() == ""


def test_the_import_error_names_the_interpreter_it_was_built_for():
    from pfgen import _built_for
    # The tests run with the interpreter the module was built for (python/CMakeLists.txt).
    assert os.path.samefile(_built_for.INTERPRETER, sys.executable)
    done = subprocess.run([sys.executable, "-c", "import sys; sys.modules['numpy'] = None; import pfgen"],
                          capture_output=True, text=True)
    assert done.returncode != 0
    last = done.stderr.strip().splitlines()[-1]
    assert last.startswith("ImportError: pfgen cannot be imported: import of numpy halted"), last
    assert f"It was built for this interpreter, {_built_for.INTERPRETER};" in last and "python3-numpy" in last
    # Another interpreter (pyenv's python3, earlier on PATH) is told which one to run.
    hint = pfgen._import_hint
    saved = _built_for.INTERPRETER
    try:
        _built_for.INTERPRETER = "/usr/bin/python3-elsewhere"
        message = hint(ModuleNotFoundError("No module named 'numpy'"))
    finally:
        _built_for.INTERPRETER = saved
    assert message.startswith(f"pfgen cannot be imported by {sys.executable} (Python ")
    assert ("No module named 'numpy'. pfgen was built for /usr/bin/python3-elsewhere (Python "
            f"{_built_for.VERSION}), for which the set-up installs numpy: run that interpreter "
            "(/usr/bin/python3-elsewhere script.py)") in message
