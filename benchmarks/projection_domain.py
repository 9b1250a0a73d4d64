#!/usr/bin/env python3
"""Can a projection filter of order K follow a one-state model's prediction from a Gaussian?

A projection filter (Brigo, Hanzon & Le Gland 1999) carries a density of the exponential family

    p_theta(x) = exp(theta_1 x + theta_2 x^2 + ... + theta_K x^K - psi(theta)),

which is a law only while theta_K < 0 (K even). Between observations its parameters move by the
projection of the Fokker-Planck equation onto the family,

    dtheta/dt = G(theta)^-1 E_theta[L c],   c = (x, ..., x^K),   G = Cov_theta(c),

with L the generator f d/dx + (1/2) g g^T d^2/dx^2. At a Gaussian, theta_3 = ... = theta_K = 0:
the law sits on the boundary theta_K = 0 of the family. Where the prediction drives theta_K up
there, the projected density stops being a law at its first step, whatever the step: the filter
cannot start from a Gaussian prior. (A linear observation h, whose h and h^2 are in the family,
moves theta_1 and theta_2 only.)

This script evaluates dtheta/dt exactly (SymPy, rationals) for a one-state model file: at the
prior N(m0, P0), and over a grid of Gaussians N(m, P), counting where dtheta_K/dt > 0.

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
    up = [(m, P, projection_drift(x, drift, noise, K, m, P)[K - 1]) for m in means for P in variances]
    rising = [row for row in up if row[2] > 0]
    smallest = min(up, key=lambda row: row[2])
    print(f"over {len(up)} Gaussians (m = -3, -2.5, ..., 3; P = 0.01, 0.1, 0.3, 1, 3): dtheta_{K}/dt > 0 at "
          f"{len(rising)}, least {float(smallest[2]):.4g} at N({smallest[0]}, {smallest[1]})")
    if at_prior[K - 1] > 0:
        print(f"verdict: from the prior the projected density leaves the family at its first step "
              f"(theta_{K} rises above 0)")
    else:
        print(f"verdict: from the prior theta_{K} does not rise at the first step")


if __name__ == "__main__":
    main()
