"""fit from Python is the command's fit: the same report and JSON, the estimates from a file or from
arrays, and the command's refusals."""
import json
import math

import numpy as np

import pytest

import pfgen

NILE, NILE_DATA = "examples/records/nile.yaml", "examples/records/nile.csv"
VDP, VDP_DATA = "examples/van_der_pol.yaml", "examples/records/van_der_pol_increments.csv"


def without_wrote(stdout):
    return "".join(line for line in stdout.splitlines(keepends=True) if not line.startswith("Wrote "))


def test_fit_is_the_commands_on_the_nile(pfgen_command, work_dir):
    out = work_dir / "fit.json"
    done = pfgen_command.run("fit", NILE, "--data", NILE_DATA, "--time-column", "year", "--estimate", "q,h",
                             "--bounds", "q=0:,h=0:", "--profile", "-o", str(out), "-q")
    fit = pfgen.fit(pfgen.Model.load(NILE), NILE_DATA, ["q", "h"], bounds={"q": (0, None), "h": (0, None)},
                    profile=True, time="year")
    assert fit.report == without_wrote(done.stdout)
    assert fit.json == out.read_text()
    written = json.loads(fit.json)
    assert fit.converged and written["converged"]
    assert fit.log_likelihood == written["log_likelihood"] and fit.aic == written["aic"]
    for entry in written["parameters"]:
        name = entry["name"]
        assert fit.estimates[name] == entry["estimate"] and fit.std_errors[name] == entry["std_error"]
        assert list(fit.wald[name]) == entry["wald"] and list(fit.profile[name]) == entry["profile"]
        assert fit.profile[name][0] < fit.estimates[name] < fit.profile[name][1]
    # Durbin and Koopman 2012's estimates, to the digits the guide gives.
    assert round(fit.estimates["h"]) == 15100 and round(fit.estimates["q"], 1) == 1468.5


def test_fit_is_the_commands_on_increments(pfgen_command):
    done = pfgen_command.run("fit", VDP, "--data", VDP_DATA, "--estimate", "mu", "--bounds", "mu=0:5", "-q")
    fit = pfgen.Model.load(VDP).fit(VDP_DATA, "mu", bounds={"mu": (0, 5)})
    assert fit.report == done.stdout
    assert math.isnan(fit.profile["mu"][0])  # not asked for
    assert fit.aic == pytest.approx(2 - 2 * fit.log_likelihood, rel=1e-15)


def test_fit_says_where_a_moment_filters_likelihood_ends():
    # closure4 on the double well's record: its likelihood ends where the moments leave the realisable set.
    model = pfgen.Model.load("examples/reference/double_well.yaml")
    data = "tests/data/double_well_increments.csv"
    fit = pfgen.fit(model, data, ["s", "c"], filter="closure4", profile=True)
    assert fit.at_edge and fit.note.startswith("the estimate is at the edge of where the filter runs")
    assert all(math.isnan(error) for error in fit.std_errors.values())
    assert fit.profile_fails_beyond["s"][0] and not fit.profile_fails_beyond["c"][0]
    written = json.loads(fit.json)
    assert written["at_edge_of_filter"] and written["note"] == fit.note
    for entry in written["parameters"]:
        assert tuple(entry.get("profile_filter_fails_beyond", [False, False])) == fit.profile_fails_beyond[entry["name"]]
    # The filters that cannot stop say nothing of it.
    nile = pfgen.fit(pfgen.Model.load(NILE), NILE_DATA, "h", bounds={"h": (0, None)}, time="year", profile=True)
    assert not nile.at_edge and nile.note == "" and nile.profile_fails_beyond == {"h": (False, False)}


def test_fit_from_arrays_is_the_files():
    model = pfgen.Model.load(NILE)
    data = np.genfromtxt(NILE_DATA, delimiter=",", names=True)
    from_file = pfgen.fit(model, NILE_DATA, "h", bounds={"h": (0, None)}, time="year")
    from_pair = pfgen.fit(model, (data["year"], data["volume"]), "h", bounds={"h": (0, None)}, time="year")
    assert from_pair.json == from_file.json
    assert from_pair.estimates == from_file.estimates


def test_fit_refuses_bad_arguments(pfgen_command):
    model = pfgen.Model.load(NILE)
    with pytest.raises(pfgen.Error) as refused:
        pfgen.fit(model, NILE_DATA, "q", bounds={"q": (0, 10)}, time="year")
    assert str(refused.value) == pfgen_command.error_line("fit", NILE, "--data", NILE_DATA, "--time-column", "year",
                                                          "--estimate", "q", "--bounds", "q=0:10", "-q")
    with pytest.raises(pfgen.Error) as refused:
        pfgen.fit(model, NILE_DATA, "sigma", time="year")
    assert str(refused.value) == pfgen_command.error_line("fit", NILE, "--data", NILE_DATA, "--time-column", "year",
                                                          "--estimate", "sigma", "-q")
    with pytest.raises(pfgen.Error, match=r"^error: --estimate: 3 is not a parameter's name"):
        pfgen.fit(model, NILE_DATA, ["q", 3], time="year")
    with pytest.raises(pfgen.Error, match=r"^error: --bounds q: expected a pair \(low, high\)"):
        pfgen.fit(model, NILE_DATA, "q", bounds={"q": 0}, time="year")
    with pytest.raises(pfgen.Error, match=r"^error: --bounds: expected a dict"):
        pfgen.fit(model, NILE_DATA, "q", bounds=[0, 1], time="year")
    with pytest.raises(pfgen.Error, match=r"^error: --starts: 'many' is not a whole number"):
        pfgen.fit(model, NILE_DATA, "q", starts="many", time="year")
    with pytest.raises(pfgen.Error, match=r"^error: --profile: expected True or False"):
        pfgen.fit(model, NILE_DATA, "q", profile=1, time="year")
    with pytest.raises(pfgen.Error, match=r"^error: --estimate: name at least one parameter"):
        pfgen.fit(model, NILE_DATA, [], time="year")
