#!/usr/bin/python3
"""Independent check of the sampled moment filters' update through a polynomial c (cd-closure3, cd-closure4).

pfgen derives the update from the joint moments of z = (x - m, d), d = c(x) - E[c] - E[J_c] (x - m), and contracts
them with Abar = [I - K C, -K]. This script gets the same numbers by another road, in exact rational arithmetic
(SymPy), at points whose higher moments are not Gaussian, and compares them with `pfgen eval`:

  1. the closed law's central moments E[e^g] = g! [s^g] exp(K(s)), K(s) the cumulant generating function with
     kappa_2 = P, kappa_3 = M3, kappa_4 = M4 - (P_ij P_lq + P_il P_jq + P_iq P_jl) (order 4 only) and every
     cumulant above the order zero, the exponential truncated at the highest degree the update reads;
  2. h = E[c], S = Cov(c) + Uv Uv^T, K = Cov(x, c) S^-1, all under that law;
  3. the moments of x+ - m+ = u - K v with u = e - K (c - h) computed directly as E[u_i u_j ...] (no z, no
     contraction), plus the Gaussian noise w = -K v's terms: P+ = E[u u^T] + Q, M3+ = E[u u u], and
     M4+ = E[u u u u] + the six U Q terms + the three Q Q pairings (U = E[u u^T], Q = K Uv Uv^T K^T).

Usage: check_sampled_polynomial_update.py --pfgen PATH.  Exit status 0: all agree; 1: a mismatch or pfgen failed.
"""

import argparse
import itertools
import json
import math
import os
import subprocess
import sys

import sympy as sp

ROOT = os.path.dirname(os.path.dirname(os.path.dirname(os.path.abspath(__file__))))
R = sp.Rational


def closed_moments(n, P, M3, M4, order, degree):
    """E[e^g] for |g| <= degree under the law whose cumulants above `order` are zero."""
    s = sp.symbols("s0:%d" % n)
    K = sum(R(1, 2) * P[i][j] * s[i] * s[j] for i in range(n) for j in range(n))
    for t in itertools.product(range(n), repeat=3):
        K += R(1, 6) * M3[tuple(sorted(t))] * s[t[0]] * s[t[1]] * s[t[2]]
    if order >= 4:
        for i, j, l, q in itertools.product(range(n), repeat=4):
            k4 = M4[tuple(sorted((i, j, l, q)))] - (P[i][j] * P[l][q] + P[i][l] * P[j][q] + P[i][q] * P[j][l])
            K += R(1, 24) * k4 * s[i] * s[j] * s[l] * s[q]
    tau = sp.Symbol("tau")
    series = sp.series(sp.exp(sp.expand(K.subs({si: tau * si for si in s}, simultaneous=True))), tau, 0, degree + 1)
    poly = sp.Poly(sp.expand(series.removeO().subs(tau, 1)), *s)

    def moment(g):
        coefficient = poly.coeff_monomial(sp.Mul(*[s[i] ** g[i] for i in range(n)]))
        return coefficient * math.prod(math.factorial(gi) for gi in g)

    return moment


def reference(n, m, P, M3, M4, order, c, Uv):
    x, e = sp.symbols("x0:%d" % n), sp.symbols("e0:%d" % n)
    degree = order * max(sp.Poly(ca, *x).total_degree() for ca in c)
    moment = closed_moments(n, P, M3, M4, order, degree)

    def E(expression):
        return sum(co * moment(g) for g, co in sp.Poly(sp.expand(expression), *e).terms())

    shifted = [sp.expand(ca.subs({x[i]: m[i] + e[i] for i in range(n)}, simultaneous=True)) for ca in c]
    h = [E(ca) for ca in shifted]
    centred = [ca - ha for ca, ha in zip(shifted, h)]
    p = len(c)
    noise = sp.Matrix(Uv) * sp.Matrix(Uv).T
    S = sp.Matrix(p, p, lambda a, b: E(centred[a] * centred[b])) + noise
    K = sp.Matrix(n, p, lambda i, a: E(e[i] * centred[a])) * S.inv()
    u = [sp.expand(e[i] - sum(K[i, a] * centred[a] for a in range(p))) for i in range(n)]
    Q = K * noise * K.T
    U = sp.Matrix(n, n, lambda i, j: E(u[i] * u[j]))
    higher = []
    for k in range(3, order + 1):
        for i, j, l, *rest in itertools.combinations_with_replacement(range(n), k):
            value = E(u[i] * u[j] * u[l] * (u[rest[0]] if rest else 1))
            if rest:
                q = rest[0]
                value += (U[i, j] * Q[l, q] + U[i, l] * Q[j, q] + U[i, q] * Q[j, l] + U[j, l] * Q[i, q]
                          + U[j, q] * Q[i, l] + U[l, q] * Q[i, j] + Q[i, j] * Q[l, q] + Q[i, l] * Q[j, q]
                          + Q[i, q] * Q[j, l])
            higher.append(value)
    return {"S": S, "K": K, "P": U + Q, "higher": higher}


def decimal(v):
    """An exact decimal string of a rational whose denominator divides a power of 10."""
    v = sp.Rational(v)
    for k in range(12):
        if (v * 10 ** k).q == 1:
            return str(sp.Float(v, 30)).rstrip("0").rstrip(".") if k else str(v)
    raise ValueError("not a short decimal: %s" % v)


def points():
    """(model, n, c, Uv, m, P, M3, M4 builder): the two test models at points with non-Gaussian M3 and M4."""
    x = sp.symbols("x0:2")
    two_m, two_P = [R(4, 10), R(-3, 10)], [[R(5, 10), R(1, 10)], [R(1, 10), R(4, 10)]]
    two_M3 = {(0, 0, 0): R(6, 100), (0, 0, 1): R(-2, 100), (0, 1, 1): R(3, 100), (1, 1, 1): R(-5, 100)}
    two_M4 = {}
    for t in itertools.combinations_with_replacement(range(2), 4):
        i, j, l, q = t
        two_M4[t] = (two_P[i][j] * two_P[l][q] + two_P[i][l] * two_P[j][q] + two_P[i][q] * two_P[j][l]
                     + R(1, 100) * (1 + sum(t)))
    yield ("tests/data/sampled_polynomial_two_outputs.yaml", 2, [x[0] ** 2 + x[1] ** 2, x[0] * x[1] + R(1, 2) * x[0]],
           [[R(2, 10), 0], [R(1, 10), R(3, 10)]], two_m, two_P, two_M3, two_M4)
    yield ("tests/data/sampled_square_sensor.yaml", 1, [x[0] ** 2], [[R(3, 10)]], [R(7, 10)], [[R(3, 10)]],
           {(0, 0, 0): R(5, 100)}, {(0, 0, 0, 0): R(4, 10)})


def name(t):
    return "M%d_%s" % (len(t), "".join(str(i + 1) for i in t))


def main():
    parser = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    parser.add_argument("--pfgen", required=True)
    args = parser.parse_args()
    failures = checked = 0
    for model, n, c, Uv, m, P, M3, M4 in points():
        for order in (3, 4):
            kind = "cd-closure%d" % order
            command = [args.pfgen, "eval", os.path.join(ROOT, model), "--filter", kind,
                       "--m", ",".join(decimal(v) for v in m),
                       "--P", ";".join(",".join(decimal(v) for v in row) for row in P)]
            for t, v in sorted(M3.items()):
                command += ["--moment", "%s=%s" % (name(t), decimal(v))]
            if order == 4:
                for t, v in sorted(M4.items()):
                    command += ["--moment", "%s=%s" % (name(t), decimal(v))]
            run = subprocess.run(command, capture_output=True, text=True)
            if run.returncode != 0:
                print("FAIL %s %s: pfgen eval failed: %s" % (model, kind, run.stderr.strip()))
                failures += 1
                continue
            got = json.loads(run.stdout)
            want = reference(n, m, P, M3, M4, order, c, Uv)
            pairs = [("S", got["update"]["innovation_covariance"], want["S"].tolist()),
                     ("K", got["update"]["gain"], want["K"].tolist()),
                     ("P_after_update", got["P_after_update"], want["P"].tolist()),
                     ("moments_after_update", [got["moments_after_update"]], [want["higher"]])]
            for label, value, expected in pairs:
                for row, expected_row in zip(value, expected):
                    for a, b in zip(row, expected_row):
                        checked += 1
                        b = float(b)
                        if abs(a - b) > 1e-12 + 1e-10 * abs(b):
                            print("FAIL %s %s %s: pfgen %r, reference %r" % (model, kind, label, a, b))
                            failures += 1
    print("%d values checked, %d mismatches" % (checked, failures))
    return 1 if failures or checked == 0 else 0


if __name__ == "__main__":
    sys.exit(main())
