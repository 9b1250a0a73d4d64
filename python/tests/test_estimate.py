"""estimate from Python is the command's estimate: the same report and CSV, the same numbers from
a file, a dict, a pandas DataFrame or a (times, values) pair, and the command's refusals."""
import csv
import io
import math

import numpy as np

import pytest

import pfgen

NILE, NILE_DATA = "examples/records/nile.yaml", "examples/records/nile.csv"
VDP, VDP_DATA = "examples/van_der_pol.yaml", "examples/records/van_der_pol_increments.csv"
WELL, WELL_DATA = "examples/reference/double_well.yaml", "tests/data/double_well_increments.csv"


def read_columns(path):
    """A record CSV as a dict of float columns (an empty cell NaN)."""
    rows = list(csv.reader(io.StringIO(open(path).read())))
    return {name: np.array([float(row[k]) if row[k] else math.nan for row in rows[1:]])
            for k, name in enumerate(rows[0])}


def without_wrote(stdout):
    return "".join(line for line in stdout.splitlines(keepends=True) if not line.startswith("Wrote "))


@pytest.mark.parametrize("model, data, time, filters", [
    (NILE, NILE_DATA, "year", None),
    (VDP, VDP_DATA, "t", ["optimal", "ekf"]),
    (WELL, WELL_DATA, "t", ["optimal", "closure3", "closure4"]),  # closure3 stops part way
])
def test_estimate_is_the_commands(pfgen_command, work_dir, model, data, time, filters):
    out = work_dir / "estimates.csv"
    arguments = ["estimate", model, "--data", data, "--time-column", time, "--full-covariance", "-o", str(out), "-q"]
    if filters:
        arguments.append("--filters=" + ",".join(filters))
    done = pfgen_command.run(*arguments)
    result = pfgen.estimate(pfgen.Model.load(model), data, filters=filters, time=time, full_covariance=True)
    assert result.report == without_wrote(done.stdout)
    assert result.csv == out.read_text()
    # The arrays are the CSV's columns.
    written = read_columns(out)
    assert list(result.series) == list(written)
    for name, values in written.items():
        np.testing.assert_array_equal(result.series[name], values, err_msg=name)
    states = pfgen.Model.load(model).state_names
    for name, run in result.filters.items():
        n, p = len(states), len(result.observation_columns)
        assert run.m.shape == (len(result.t), n) and run.P.shape == (len(result.t), n, n)
        assert run.innovation.shape == (len(result.t), p)
        np.testing.assert_array_equal(run.m[:, -1], written[f"{name}_m_{states[-1]}"])
        np.testing.assert_array_equal(np.sqrt(np.maximum(run.P[:, 0, 0], 0)), run.sd[:, 0])
        np.testing.assert_array_equal(run.P[:, 0, -1], run.P[:, -1, 0])
        scores = result.scores[name]
        if scores["stopped"]:  # its line says where instead of the scores
            assert f"{name:<16} stopped at {scores['stopped']}\n" in result.report
            continue
        assert f"{scores['log_likelihood']:.6f}" in result.report
        assert scores["verdict"] in result.report
        assert scores["consistent"] == (scores["band"][0] <= scores["mean_square"] <= scores["band"][1])
        assert len(scores["ljung_box"]) == p
    np.testing.assert_array_equal(result.t, written[time])


def test_a_filter_that_stops_is_marked_and_the_others_go_on():
    result = pfgen.estimate(pfgen.Model.load(WELL), WELL_DATA, filters=["optimal", "closure3", "closure4"])
    assert result.scores["closure3"]["stopped"].startswith(
        WELL_DATA + ":462: its moments left the realisable set at t = 4.6")
    assert result.scores["optimal"]["stopped"] is None and result.scores["closure4"]["stopped"] is None
    m = result.filters["closure3"].m
    assert np.isfinite(m[:460]).all() and np.isnan(m[460:]).all()  # the data's row 461 (t = 4.6) on
    assert np.isfinite(result.filters["closure4"].m).all()


def test_the_same_numbers_from_memory():
    model = pfgen.Model.load(NILE)
    columns = read_columns(NILE_DATA)
    from_file = pfgen.estimate(model, NILE_DATA, time="year")
    pair = pfgen.estimate(model, (columns["year"], columns["volume"]), time="year")
    from_dict = pfgen.estimate(model, columns, time="year")
    for result in (pair, from_dict):
        assert result.report.replace("Record <data>:", f"Record {NILE_DATA}:") == from_file.report
        np.testing.assert_equal(result.scores, from_file.scores)  # NaN (no increments' density) equal to NaN
        np.testing.assert_array_equal(result.filters["cd-optimal"].m, from_file.filters["cd-optimal"].m)
    # The pair's observation column is y1; the dict's keeps its name.
    assert pair.observation_columns == ["y1"] and from_dict.observation_columns == ["volume"]
    assert from_dict.csv == from_file.csv
    np.testing.assert_array_equal(pair.data[:, 0], columns["volume"])


def test_a_dataframe_and_missing_values():
    pandas = pytest.importorskip("pandas")
    model = pfgen.Model.load(NILE)
    frame = pandas.read_csv(NILE_DATA)
    from_file = pfgen.estimate(model, NILE_DATA, time="year")
    assert pfgen.estimate(model, frame, time="year").csv == from_file.csv
    # The time as the frame's index, named as `time`.
    assert pfgen.estimate(model, frame.set_index("year"), time="year").csv == from_file.csv
    # A missing sample (None in the frame) is predicted over: its innovation is empty, as in the file.
    frame.loc[3, "volume"] = None
    gap = pfgen.estimate(model, frame, time="year")
    assert math.isnan(gap.filters["cd-optimal"].innovation[3, 0])
    assert gap.scores["cd-optimal"]["count"] == 99


def test_filter_run_is_estimate_with_one_filter():
    model = pfgen.Model.load(VDP)
    run = model.derive("ekf").run(VDP_DATA)
    assert list(run.filters) == ["ekf"]
    assert run.report == pfgen.estimate(model, VDP_DATA, filters="ekf").report


def test_estimate_refuses_bad_arguments(pfgen_command):
    model = pfgen.Model.load(NILE)
    with pytest.raises(pfgen.Error) as refused:
        pfgen.estimate(model, NILE_DATA)
    assert str(refused.value) == pfgen_command.error_line("estimate", NILE, "--data", NILE_DATA, "-q")
    with pytest.raises(pfgen.Error, match=r"^error: --data: expected a CSV file's path, a dict of columns"):
        pfgen.estimate(model, 42)
    with pytest.raises(pfgen.Error, match=r"^error: --data: column 'volume': expected numbers"):
        pfgen.estimate(model, {"year": [1, 2], "volume": ["a", "b"]}, time="year")
    with pytest.raises(pfgen.Error, match=r"^error: --data: column 'volume' has 1 values, the first column 2"):
        pfgen.estimate(model, {"year": [1, 2], "volume": [3]}, time="year")
    with pytest.raises(pfgen.Error, match=r"^error: --data: complex values are not read: give real numbers"):
        pfgen.estimate(model, ([1871, 1872], np.array([1100 + 1j, 1200])), time="year")  # numpy would drop 1j
    with pytest.raises(pfgen.Error, match=r"^error: --data: 2 times need values of shape \(2, p\), got \(3, 1\)"):
        pfgen.estimate(model, ([1, 2], [1, 2, 3]))
    with pytest.raises(pfgen.Error, match=r"^error: <data> row 2: column 't': the time 1 does not come after"):
        pfgen.estimate(model, ([1, 1], [1, 2]))
    with pytest.raises(pfgen.Error, match=r"^error: --full-covariance: expected True or False"):
        pfgen.estimate(model, NILE_DATA, time="year", full_covariance="yes")
    with pytest.raises(pfgen.Error, match=r"^error: --substeps: 0 is not between 1 and 1000000"):
        pfgen.estimate(model, NILE_DATA, time="year", substeps=0)
    with pytest.raises(pfgen.Error) as refused:
        pfgen.estimate(model, NILE_DATA, time="year", filters="kalman")
    assert str(refused.value) == pfgen_command.error_line("estimate", NILE, "--data", NILE_DATA, "--time-column", "year",
                                                          "--filters", "kalman", "-q")
    with pytest.raises(TypeError, match="pfgen.estimate: expected a pfgen.Model"):
        pfgen.estimate(NILE, NILE_DATA)
