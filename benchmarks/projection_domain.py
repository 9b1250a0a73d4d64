#!/usr/bin/env python3
"""Can a projection filter of order K follow a one-state model's prediction from a Gaussian?

A projection filter (Brigo, Hanzon & Le Gland 1999) carries a density of the exponential family

    p_theta(x) = exp(theta_1 x + theta_2 x^2 + ... + theta_K x^K - psi(theta)),

which is a law only while theta_K < 0 (K even). Between observations its parameters move by the
projection of the Fokker-Planck equation onto the family,

    dtheta/dt = G(theta)^-1 E_theta[L c],   c = (x, ..., x^K),   G = Cov_theta(c),

with L the generator f d/dx + (1/2) g g^T d^2/dx^2. At a Gaussian, theta_3 = ... = theta_K = 0:
the law sits on the boundary theta_K = 0 of the family. Where the prediction drives theta_K up
there, the projected vector field points out of the family: no solution from a Gaussian prior
stays a law for any t > 0, whatever the step. (A linear observation h, whose h and h^2 are in the family,
moves theta_1 and theta_2 only.)

This script evaluates dtheta/dt exactly (SymPy, rationals) for a one-state model file: at the
prior N(m0, P0), and over a grid of Gaussians N(m, P), counting where it points out of the family
(the highest theta_j, j >= 3, that moves is odd, or even and rising); and checks
each dtheta_K/dt against a closed form found by a second route (Stein's identity in the Hermite
basis): E[f^(K-1)] / ((K-1)! P) + E[(g g^T)^(K-2)] / (2 (K-2)! P^2).

    /usr/bin/python3 benchmarks/projection_domain.py MODEL [--order K]
"""

import argparse
import sys

import sympy as sp
import yaml


def fail(message):
    print(f"projection_domain.py: {message}", file=sys.stderr)
    sys.exit(2)


def load_one_state_model(path):
    """The model's drift f and g g^T as SymPy polynomials in its state (parameters at their
    defaults, as exact rationals), and the prior's m0 and P0."""
    try:
        with open(path) as handle:
            doc = yaml.safe_load(handle)
    except (OSError, yaml.YAMLError) as error:
        fail(f"{path}: {error}")
    if not isinstance(doc, dict) or len(doc.get("states") or []) != 1:
        fail(f"{path}: field 'states': this check takes a model of one state")
    x = sp.Symbol(str(doc["states"][0]), real=True)
    names = {str(doc["states"][0]): x}
    for name, value in (doc.get("parameters") or {}).items():
        names[str(name)] = sp.Rational(str(value))

    def parse(field, text):
        try:
            value = sp.sympify(str(text).replace("^", "**"), locals=names, rational=True)
        except (sp.SympifyError, TypeError, SyntaxError) as error:
            fail(f"{path}: field '{field}': '{text}' is not an expression ({error})")
        if value.free_symbols - {x} or not value.is_polynomial(x):
            fail(f"{path}: field '{field}': '{text}' is not a polynomial in {x} with known parameters")
        return sp.expand(value)

    drift = parse("drift", doc["drift"][0])
    row = doc["diffusion"][0]
    noise = sp.expand(sum(parse("diffusion", g) ** 2 for g in row))
    initial = doc.get("initial") or {}
    m0 = sp.Rational(str(initial["m0"][0]))
    P0 = sp.Rational(str(initial["P0"][0][0]))
    return x, drift, noise, m0, P0


def gaussian_moments(m, P, top):
    """E[x^j] of N(m, P), j = 0..top: E[(m + e)^j] with E[e^(2i)] = (2i - 1)!! P^i."""
    out = []
    for j in range(top + 1):
        out.append(sum(sp.binomial(j, i) * m ** (j - i) * P ** (i // 2) * sp.factorial2(i - 1)
                       for i in range(0, j + 1, 2)))
    return out


def projection_drift(x, drift, noise, order, m, P):
    """dtheta/dt at N(m, P): G^-1 E[L c] with c_j = x^j, j = 1..order."""
    generator = [sp.expand(drift * j * x ** (j - 1) + noise * sp.Rational(j * (j - 1), 2) * x ** (j - 2))
                 for j in range(1, order + 1)]
    top = max(2 * order, max(sp.Poly(Lc, x).degree() for Lc in generator))
    M = gaussian_moments(m, P, top)

    def expect(polynomial):
        return sum(coefficient * M[degree] for (degree,), coefficient in sp.Poly(polynomial, x).terms())

    G = sp.Matrix(order, order, lambda i, j: M[i + j + 2] - M[i + 1] * M[j + 1])
    return G.LUsolve(sp.Matrix([expect(Lc) for Lc in generator]))


def points_out(velocity):
    """Whether a step from a Gaussian along `velocity` (dtheta/dt) leaves the laws: the highest
    theta_j (j >= 3) that moves is odd, or even and rising."""
    moving = [j for j in range(3, len(velocity) + 1) if velocity[j - 1] != 0]
    return bool(moving) and (moving[-1] % 2 == 1 or bool(velocity[moving[-1] - 1] > 0))


def top_drift_closed_form(x, drift, noise, order, m, P):
    """dtheta_K/dt at N(m, P) by a second route (Stein's identity in the Hermite basis):
    E[f^(K-1)] / ((K-1)! P) + E[(g g^T)^(K-2)] / (2 (K-2)! P^2), for the check of the first."""
    M = gaussian_moments(m, P, max(1, sp.Poly(drift, x).degree(), sp.Poly(noise, x).degree()))

    def expect(polynomial):
        polynomial = sp.expand(polynomial)
        if polynomial == 0:
            return sp.Integer(0)
        return sum(coefficient * M[degree] for (degree,), coefficient in sp.Poly(polynomial, x).terms())

    return (expect(sp.diff(drift, x, order - 1)) / (sp.factorial(order - 1) * P) +
            expect(sp.diff(noise, x, order - 2)) / (2 * sp.factorial(order - 2) * P ** 2))


def main():
    parser = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    parser.add_argument("model")
    parser.add_argument("--order", type=int, default=4, help="K, the family's highest power (even, 4 to 8)")
    args = parser.parse_args()
    if args.order not in (4, 6, 8):
        fail(f"--order {args.order}: the family's highest power must be 4, 6 or 8 (even, for a law)")
    x, drift, noise, m0, P0 = load_one_state_model(args.model)
    K = args.order
    print(f"{args.model}: f = {drift}, g g^T = {noise}; family exp(theta_1 x + ... + theta_{K} x^{K})")
    at_prior = projection_drift(x, drift, noise, K, m0, P0)
    print(f"at the prior N({m0}, {P0}): dtheta/dt = (" +
          ", ".join(f"{float(v):.4g}" for v in at_prior) + ")")
    means = [sp.Rational(k, 2) for k in range(-6, 7)]
    variances = [sp.Rational(1, 100), sp.Rational(1, 10), sp.Rational(3, 10), sp.Integer(1), sp.Integer(3)]
    grid = [(m, P, projection_drift(x, drift, noise, K, m, P)) for m in means for P in variances]
    up = [(m, P, velocity[K - 1]) for m, P, velocity in grid]
    differing = [row for row in up if row[2] != top_drift_closed_form(x, drift, noise, K, row[0], row[1])]
    out = sum(points_out(velocity) for _, _, velocity in grid)
    smallest = min(up, key=lambda row: row[2])
    print(f"over {len(up)} Gaussians (m = -3, -2.5, ..., 3; P = 0.01, 0.1, 0.3, 1, 3): the projection points out "
          f"of the family at {out}; dtheta_{K}/dt least {float(smallest[2]):.4g} at N({smallest[0]}, {smallest[1]})")
    print(f"closed form E[f^({K - 1})] / ({K - 1}! P) + E[(g g^T)^({K - 2})] / (2 ({K - 2})! P^2): "
          + ("equal at all " + str(len(up)) if not differing else f"DIFFERS at {len(differing)}"))
    if differing:
        sys.exit(1)
    if points_out(at_prior):
        print("verdict: at the prior the projection points out of the family (its highest moving theta rises "
              "above 0, or is odd): no solution from it stays a law")
    else:
        print("verdict: at the prior the projection stays in the family")


if __name__ == "__main__":
    main()
