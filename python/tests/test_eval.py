"""eval from Python gives the command's numbers: the same JSON, read into numpy arrays."""
import json

import numpy as np
import pytest

import pfgen
from conftest import example_models


def point(n):
    """A point away from every special case: distinct means, a full positive definite P."""
    m = [0.3 + 0.2 * i * (-1) ** i for i in range(n)]
    P = [[(0.5 + 0.1 * i if i == j else 0.05) for j in range(n)] for i in range(n)]
    return m, P


def assert_same(values, expected, where):
    """eval's arrays hold the JSON's numbers, in its nesting."""
    if isinstance(expected, dict):
        assert isinstance(values, dict) and set(values) == set(expected), where
        for key in expected:
            assert_same(values[key], expected[key], f"{where} {key}")
    else:
        assert isinstance(values, np.ndarray), where
        np.testing.assert_array_equal(values, np.array(expected, dtype=float), err_msg=where)


def text_list(values):
    return ",".join(repr(float(v)) for v in values)


@pytest.mark.parametrize("path", example_models())
def test_eval_is_the_commands(path, pfgen_command):
    model = pfgen.Model.load(path)
    m, P = point(len(model.state_names))
    for kind in model.default_kinds:
        args = ["eval", path, "--filter", kind, "--t", "0.25", "--m", text_list(m),
                "--P", ";".join(text_list(row) for row in P)]
        done = pfgen_command.run(*args, check=False)
        if done.returncode != 0:  # then Python refuses the point with the same message
            with pytest.raises(pfgen.Error) as refused:
                model.derive(kind).eval(0.25, m, P)
            assert "pfgen: " + str(refused.value) == done.stderr.strip()
            continue
        expected = json.loads(done.stdout)
        values = model.derive(kind).eval(0.25, np.array(m), np.array(P))
        del expected["model"], expected["filter"]
        assert_same(values, expected, f"{path} {kind}")
        assert model.derive(kind)._native.eval(0.25, m, P, {}, [], [], [], []).json == done.stdout


def test_parameters_by_keyword_are_set(pfgen_command):
    path = "examples/van_der_pol.yaml"
    optimal = pfgen.Model.load(path).derive("optimal")
    done = pfgen_command.run("eval", path, "--filter", "optimal", "--m", "1,-0.5", "--P", "0.2,0.01;0.01,0.3",
                             "--set", "mu=0.7", "--set", "r=0.25")
    expected = json.loads(done.stdout)
    values = optimal.eval(0, [1, -0.5], [[0.2, 0.01], [0.01, 0.3]], mu=0.7, r=0.25)
    np.testing.assert_array_equal(values["P_drift"], np.array(expected["P_drift"]))
    np.testing.assert_array_equal(values["gain"], np.array(expected["gain"]))
    # A new value changes the result: the keyword is not ignored.
    assert not np.array_equal(values["P_drift"], optimal.eval(0, [1, -0.5], [[0.2, 0.01], [0.01, 0.3]])["P_drift"])


def test_delayed_inputs(pfgen_command):
    path = "examples/delay_linear.yaml"
    model = pfgen.Model.load(path)
    kind = model.default_kinds[0]
    n = len(model.state_names)
    m, P = point(n)
    md = [v + 0.1 for v in m]
    done = pfgen_command.run("eval", path, "--filter", kind, "--m", text_list(m),
                             "--P", ";".join(text_list(row) for row in P), "--m-delayed", text_list(md))
    values = model.derive(kind).eval(0, m, P, m_delayed=md)
    expected = json.loads(done.stdout)
    del expected["model"], expected["filter"]
    assert_same(values, expected, path)
    np.testing.assert_array_equal(values["delayed_inputs"]["m_delayed"], np.array(md))


def test_a_parameter_named_like_an_argument(pfgen_command, work_dir):
    path = work_dir / "phi.yaml"
    path.write_text("name: phi_model\nstates: [x]\nparameters: {phi: 0.5, m: 2}\ndrift: [\"-phi*x\"]\n"
                    "diffusion: [[\"m\"]]\nobservation: {A: [[1]], B: [[1]]}\n")
    done = pfgen_command.run("eval", str(path), "--filter", "optimal", "--m", "1", "--P", "1", "--set", "phi=2",
                             "--set", "m=3")
    values = pfgen.Model.load(str(path)).derive("optimal").eval(0, [1], [[1]], parameters={"phi": 2, "m": 3})
    assert values["P_drift"].tolist() == json.loads(done.stdout)["P_drift"]
    assert values["m_drift"].tolist() == [-2]
