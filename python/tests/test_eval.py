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
        assert model.derive(kind)._native.eval(0.25, m, P, {}, [], [], [], [], {}).json == done.stdout


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


def test_a_moment_filter_takes_its_moments_by_name(pfgen_command):
    # closure3 of the quadratic example at m = -1.5, P = 0.5, M3_111 = 0.2 (tests/test_cli.cpp's hand values):
    # dP = 0.2 (2 m P + M3) + 0.01 (m^4 + 6 m^2 P + 4 m M3 + 3 P^2) - P^2, dP's dy term M3, dM3's drift
    # 0.3 (2 m M3 + 2 P^2) + 0.03 (4 m^3 P + 6 m^2 M3 + 12 m P^2 + 10 P M3) - 3 M3 P and dy term 0.
    path = "examples/basin2006_quadratic.yaml"
    closure3 = pfgen.Model.load(path).derive("closure3")
    values = closure3.eval(0, [-1.5], [[0.5]], moments={"M3_111": 0.2})
    assert values["moments"] == ["M3_111"]
    np.testing.assert_allclose(values["P_drift"], [[-0.396375]], rtol=1e-14)
    np.testing.assert_allclose(values["P_gain"], [[[0.2]]], rtol=1e-14)
    np.testing.assert_allclose(values["moment_drift"], [-0.5565], rtol=1e-14)
    np.testing.assert_array_equal(values["moment_gain"], [[0]])
    done = pfgen_command.run("eval", path, "--filter", "closure3", "--m=-1.5", "--P", "0.5", "--moment", "M3_111=0.2")
    expected = json.loads(done.stdout)
    del expected["model"], expected["filter"], expected["moments"]
    assert_same({key: value for key, value in values.items() if key != "moments"}, expected, "closure3")
    # A moment left out takes its Gaussian value (M3 = 0): the moments are not ignored.
    np.testing.assert_allclose(closure3.eval(0, [-1.5], [[0.5]])["P_gain"], [[[0]]], atol=1e-15)


@pytest.mark.parametrize("path", example_models())
def test_a_moment_filters_eval_is_the_commands(path, pfgen_command):
    # Every example with the moment filters (but for ins16's 16 states, whose closure4 takes seconds), each
    # moment given a value of its own.
    model = pfgen.Model.load(path)
    n = len(model.state_names)
    kinds = [kind for kind in ("closure3", "closure4") if kind in model.kinds and n <= 4]
    for kind in kinds:
        filter_ = model.derive(kind)
        m, P = point(n)
        names = filter_.eval(0.25, m, P)["moments"]
        moments = {name: 0.01 * (k + 1) * (-1) ** k for k, name in enumerate(names)}
        args = ["eval", path, "--filter", kind, "--t", "0.25", "--m", text_list(m),
                "--P", ";".join(text_list(row) for row in P)]
        for name, value in moments.items():
            args += ["--moment", f"{name}={value!r}"]
        expected = json.loads(pfgen_command.run(*args).stdout)
        values = filter_.eval(0.25, m, P, moments=moments)
        assert values["moments"] == expected["moments"] == names
        del expected["model"], expected["filter"], expected["moments"]
        assert_same({key: value for key, value in values.items() if key != "moments"}, expected, f"{path} {kind}")


def test_a_moment_the_filter_does_not_carry_is_the_commands_error(pfgen_command):
    path = "examples/basin2006_quadratic.yaml"
    model = pfgen.Model.load(path)
    for kind, name in (("closure3", "M4_1111"), ("optimal", "M3_111")):
        line = pfgen_command.error_line("eval", path, "--filter", kind, "--m", "1", "--P", "1", "--moment", f"{name}=1")
        with pytest.raises(pfgen.Error) as refused:
            model.derive(kind).eval(0, [1], [[1]], moments={name: 1})
        assert str(refused.value) == line
    with pytest.raises(pfgen.Error, match=r"^error: --moment: expected a dict of moment names and numbers, got list$"):
        model.derive("closure3").eval(0, [1], [[1]], moments=[("M3_111", 1)])
    with pytest.raises(pfgen.Error, match=r"^error: --moment M3_111: 'x' is not a number$"):
        model.derive("closure3").eval(0, [1], [[1]], moments={"M3_111": "x"})
