"""to_sympy gives the printed equations: Basin, Perez & Skliar 2006's equations (21)-(22) for
their quadratic example, and the text output's equations for every filter of another model."""
import re

import sympy

import pfgen


def test_quadratic_optimal_filter_is_equations_21_22():
    eq = pfgen.Model.load("examples/basin2006_quadratic.yaml").derive("optimal").to_sympy()
    m, P = sympy.symbols("m1 P11")
    tenth = sympy.Rational(1, 10)
    # (21): dm = 0.1 (m^2 + P) dt + P (dy - m dt)
    assert sympy.simplify(eq.m_drift[0] - tenth * (m**2 + P)) == 0
    assert sympy.simplify(eq.gain[0, 0] - P) == 0
    assert sympy.simplify(eq.predicted_observation[0] - m) == 0
    # (22): dP/dt = 0.4 P m + 0.03 P^2 + 0.06 P m^2 + 0.01 m^4 - P^2
    published = (sympy.Rational(4, 10) * P * m + sympy.Rational(3, 100) * P**2 + sympy.Rational(6, 100) * P * m**2
                 + sympy.Rational(1, 100) * m**4 - P**2)
    assert sympy.expand(eq.P_drift[0, 0] - published) == 0
    assert eq.symbols["m1"] == m


def text_equations(text):
    """dm_i and dP_ij drifts, and K_ij, from the text output (its '^' read as '**')."""
    out = {}
    for line in text.splitlines():
        match = re.match(r"^(dm\d+) = \((.*)\) dt \+", line) or re.match(r"^(dP\d+) = \((.*)\) dt$", line) \
            or re.match(r"^(K\d+_\d+) = (.*)$", line)
        if match:
            out[match.group(1)] = match.group(2).replace("^", "**")
    return out


def test_every_entry_equals_the_text_output():
    model = pfgen.Model.load("examples/van_der_pol.yaml")
    for kind in ["optimal", "ekf"]:
        filter_ = model.derive(kind)
        eq = filter_.to_sympy()
        printed = text_equations(filter_.text)
        parse = lambda s: sympy.sympify(s, locals=eq.symbols)
        n = 2
        for i in range(n):
            assert sympy.expand(eq.m_drift[i] - parse(printed[f"dm{i + 1}"])) == 0
            assert sympy.expand(eq.gain[i, 0] - parse(printed[f"K{i + 1}_1"])) == 0
            for j in range(i, n):
                assert sympy.expand(eq.P_drift[i, j] - parse(printed[f"dP{i + 1}{j + 1}"])) == 0
                assert eq.P_drift[i, j] == eq.P_drift[j, i]
        assert {"mu", "r", "s", "t"} <= set(eq.symbols)


def test_sampled_and_defined_filters():
    # A sampled filter has its prediction and no gain; the ukf's Cholesky entries are definitions.
    sampled = pfgen.Model.load("examples/paper003/example1_gamma0.yaml")
    eq = sampled.derive(sampled.default_kinds[0]).to_sympy()
    assert eq.gain.shape == (eq.m_drift.shape[0], 0)
    ukf = pfgen.Model.load("examples/basin2006_quadratic.yaml").derive("ukf").to_sympy()
    assert ukf.definitions and all(isinstance(name, str) for name in ukf.definitions)
    assert ukf.m_drift[0].free_symbols & {ukf.symbols[name] for name in ukf.definitions}


def test_a_parameter_named_like_a_python_keyword(tmp_path):
    path = tmp_path / "lambda.yaml"
    path.write_text("name: keywords\nstates: [x]\nparameters: {lambda: 0.5, E: 2, gamma: 3}\n"
                    "drift: [\"-lambda*x + gamma\"]\ndiffusion: [[\"E\"]]\nobservation: {A: [[1]], B: [[1]]}\n")
    eq = pfgen.Model.load(str(path)).derive("optimal").to_sympy()
    lam, gamma, m = sympy.Symbol("lambda"), sympy.Symbol("gamma"), sympy.Symbol("m1")
    assert sympy.expand(eq.m_drift[0] - (-lam * m + gamma)) == 0
    assert eq.symbols["E"] in eq.P_drift[0, 0].free_symbols


def test_the_cubic_sensor_as_the_design_equations():
    """A polynomial observation: dm = -a m dt + 3P(m^2 + P)/rho^2 dnu,
    dP = (-2aP + sigma^2 - 9P^2(m^2 + P)^2/rho^2) dt + 6mP^2/rho^2 dnu, dnu = dy - (m^3 + 3mP) dt."""
    eq = pfgen.Model.load("examples/polynomial/cubic_sensor.yaml").derive("optimal").to_sympy()
    m, P, a, sigma, rho = (eq.symbols[name] for name in ("m1", "P11", "a", "sigma", "rho"))
    assert sympy.expand(eq.m_drift[0] + a * m) == 0
    assert sympy.simplify(eq.gain[0, 0] - 3 * P * (m**2 + P) / rho**2) == 0
    assert sympy.simplify(eq.P_drift[0, 0] - (-2 * a * P + sigma**2 - 9 * P**2 * (m**2 + P)**2 / rho**2)) == 0
    assert sympy.expand(eq.predicted_observation[0] - (m**3 + 3 * m * P)) == 0
    assert len(eq.P_gain) == 1 and sympy.simplify(eq.P_gain[0][0, 0] - 6 * m * P**2 / rho**2) == 0
    assert pfgen.Model.load("examples/basin2006_quadratic.yaml").derive("optimal").to_sympy().P_gain == []


def test_a_parameter_named_e_beside_small_numbers(tmp_path):
    path = tmp_path / "e.yaml"
    path.write_text("name: small\nstates: [x]\nparameters: {e: 2}\ndrift: [\"-0.00001*e*x\"]\n"
                    "diffusion: [[\"0.001\"]]\nobservation: {A: [[1]], B: [[1]]}\n")
    eq = pfgen.Model.load(str(path)).derive("optimal").to_sympy()
    e, m = sympy.Symbol("e"), sympy.Symbol("m1")
    assert sympy.expand(eq.m_drift[0] + sympy.Rational(1, 100000) * e * m) == 0


def test_the_moment_filters_carry_their_moments():
    """closure3 and closure4 of the quadratic example (h = x, R = 1; tests/test_cli.cpp): dP's dy term is M3,
    dM3 = (0.3 (2 m M3 + M4 - P^2) + 0.03 (4 m^3 P + 6 m^2 M3 + 4 m M4 + 10 P M3) - 3 M3 P) dt + (M4 - 3 P^2) dnu,
    with M4 = 3 P^2 under closure3 (its fourth cumulant zero)."""
    model = pfgen.Model.load("examples/basin2006_quadratic.yaml")
    for kind in ("closure3", "closure4"):
        eq = model.derive(kind).to_sympy()
        m, P, M3 = (eq.symbols[name] for name in ("m1", "P11", "M3_111"))
        M4 = eq.symbols["M4_1111"] if kind == "closure4" else 3 * P**2
        tenth = sympy.Rational(1, 10)
        assert eq.moment_names == (["M3_111"] if kind == "closure3" else ["M3_111", "M4_1111"])
        assert eq.moment_drift.shape == (len(eq.moment_names), 1) and eq.moment_gain.shape == (len(eq.moment_names), 1)
        assert sympy.expand(eq.P_gain[0][0, 0] - M3) == 0
        drift = (3 * tenth * (2 * m * M3 + M4 - P**2)
                 + 3 * tenth**2 * (4 * m**3 * P + 6 * m**2 * M3 + 4 * m * M4 + 10 * P * M3) - 3 * M3 * P)
        assert sympy.expand(eq.moment_drift[0] - drift) == 0
        assert sympy.expand(eq.moment_gain[0, 0] - (M4 - 3 * P**2)) == 0
    optimal = model.derive("optimal").to_sympy()
    assert optimal.moment_names == [] and optimal.moment_drift.shape == (0, 1) and optimal.moment_gain.shape == (0, 1)
