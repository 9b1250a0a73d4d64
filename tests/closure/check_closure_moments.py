#!/usr/bin/python3
"""Independent check of pfgen's moment-closure filters (optimal = order 2, closure3, closure4).

pfgen derives the closure-k filter by a Stein-type recursion on central moments. This script gets
the same equations by another road, in exact rational arithmetic (SymPy), and compares them with
`pfgen eval` at a few deterministic points:

  1. cumulants from the filter state: kappa_1 = m, kappa_2 = P, kappa_3 = M3,
     kappa_4 = M4 - (P_ij P_lq + P_il P_jq + P_iq P_jl); every cumulant of order > k is zero;
  2. raw moments E[x^beta] = beta! [s^beta] exp(K(s)), K(s) = sum_{1<=|a|<=k} kappa_a s^a / a!,
     the exponential taken as a power series in s truncated at total degree N (below), exactly;
  3. the Kushner-Stratonovich equations of the raw moments M_beta = E[x^beta], 1 <= |beta| <= k:
        drift_beta = E[L x^beta],   L phi = f . grad phi + 1/2 tr(G Hess phi),
        gain_beta  = (E[x^beta h] - E[x^beta] E[h])^T R^-1        (a p-vector),
     every expectation closed by step 2;
  4. each state variable z (m_i, P_ij, M3_ijl, M4_ijlq) is a polynomial F_z of the raw moments
     (the binomial expansion of E[(x - m)^alpha] with m_i = M_{e_i}); Ito's formula, with
     d<nu> = R dt:
        gain_z  = sum_b dF_z/dM_b gain_b
        drift_z = sum_b dF_z/dM_b drift_b + 1/2 sum_{b,c} d2F_z/dM_b dM_c gain_b R gain_c^T.

Order of the raw moments needed (N). Step 3 takes, for |beta| <= k,
  E[f . grad x^beta]      degree |beta| - 1 + deg f,
  E[tr(G Hess x^beta)]    degree |beta| - 2 + deg G        (deg G = 2 deg g when g is given),
  E[x^beta h]             degree |beta| + deg h,
and step 4 takes nothing more (it uses only the drifts and gains of step 3), so
  N = k + max(deg f - 1, deg G - 2, deg h, 0).
The truncated series exp(K) is computed once per point up to degree N and all moments are read
from it (cubic sensor, k = 4: N = 7; the 2-state models, k = 4: N = 6).

Usage:
  check_closure_moments.py --pfgen PATH [--orders 2,3,4]      every model, every order
  check_closure_moments.py --pfgen PATH --kind optimal         order 2 only (closure3/closure4 too)
  check_closure_moments.py --pfgen PATH --model FILE --order K [--points 1] [--verbose]
  check_closure_moments.py --self-test                          the script's own sanity tests
Exit status: 0 all agree; 1 a mismatch, or pfgen failed (e.g. it does not know the kind yet).
"""

import argparse
import itertools
import json
import math
import os
import random
import subprocess
import sys
import time

import sympy as sp
import yaml
from sympy.parsing.sympy_parser import (convert_xor, parse_expr, rationalize,
                                        standard_transformations)
from sympy.polys.domains import QQ
from sympy.polys.rings import ring

HERE = os.path.dirname(os.path.abspath(__file__))
ROOT = os.path.dirname(os.path.dirname(HERE))
DEFAULT_MODELS = [
    "examples/polynomial/cubic_sensor.yaml",
    "examples/basin2006_quadratic.yaml",
    "examples/reference/double_well.yaml",
    "examples/polynomial/van_der_pol_energy.yaml",
    "tests/closure/two_sensor_multiplicative.yaml",
]
KIND_OF_ORDER = {2: "optimal", 3: "closure3", 4: "closure4"}
ORDER_OF_KIND = {v: k for k, v in KIND_OF_ORDER.items()}
POINTS = 3
RTOL = 1e-9
ATOL = 1e-12
PRECISION = 40  # digits of the final evalf of the exact reference values

FUNCTIONS = {name: getattr(sp, name) for name in (
    "sin", "cos", "tan", "exp", "log", "sinh", "cosh", "tanh", "asin", "acos", "atan", "atan2",
    "asinh", "acosh", "atanh", "sqrt")}
FUNCTIONS.update({"abs": sp.Abs, "tgamma": sp.gamma, "lgamma": sp.loggamma, "pow": sp.Pow,
                  "Pi": sp.pi, "Euler": sp.EulerGamma, "Catalan": sp.Catalan})
TRANSFORMS = standard_transformations + (convert_xor, rationalize)


# ----------------------------------------------------------------------------------------------
# Model
# ----------------------------------------------------------------------------------------------
class Model:
    """f (n), G (n x n), h (p), R (p x p) as SymPy expressions in the states X and the time T,
    with the parameters' default values substituted (exact rationals)."""

    def __init__(self, name, n, f, G, h, R, h_given):
        self.name, self.n = name, n
        self.X = sp.symbols("X1:%d" % (n + 1)) if n > 1 else (sp.Symbol("X1"),)
        self.T = sp.Symbol("T")
        self.f, self.G, self.h, self.R = f, G, h, R
        self.p = len(h)
        self.Rinv = R.inv()
        self.h_given = h_given  # observation written as `h:` (pfgen's polynomial observation)
        self.nonlinear_h = h_given and self.deg(h) > 1

    def deg(self, exprs):
        d = 0
        for e in exprs:
            e = sp.expand(e)
            if e != 0:
                d = max(d, sp.Poly(e, *self.X).total_degree())
        return d


def _parse(text, names, where):
    text = str(text).strip()
    expr = parse_expr(text, local_dict=dict(names), transformations=TRANSFORMS)
    allowed = {v for v in names.values() if isinstance(v, sp.Symbol)}
    bad = expr.free_symbols - allowed
    if bad:
        raise SystemExit("%s: unknown names %s in '%s'" % (where, sorted(map(str, bad)), text))
    return sp.sympify(expr)


def load_model(path):
    with open(path) as fh:
        doc = yaml.load(fh, Loader=yaml.BaseLoader)  # every scalar a string: numbers stay exact
    states = list(doc["states"])
    n = len(states)
    X = sp.symbols("X1:%d" % (n + 1)) if n > 1 else (sp.Symbol("X1"),)
    T = sp.Symbol("T")
    names = dict(FUNCTIONS)
    for pname, pval in (doc.get("parameters") or {}).items():
        names[pname] = _parse(pval, FUNCTIONS, "%s: parameter %s" % (path, pname))
    names[doc.get("time", "t")] = T
    for i, s in enumerate(states):
        names[s] = X[i]
    f = [_parse(e, names, "%s: drift" % path) for e in doc["drift"]]
    if "diffusion" in doc:
        g = sp.Matrix([[_parse(e, names, "%s: diffusion" % path) for e in row]
                       for row in doc["diffusion"]])
        G = (g * g.T).applyfunc(sp.expand)
        if doc.get("noise", "ito") == "stratonovich":  # Ito drift f + 1/2 sum_jk g_jk dg_ik/dx_j
            f = [f[i] + sp.Rational(1, 2) * sum(g[j, k] * sp.diff(g[i, k], X[j])
                                                for j in range(n) for k in range(g.shape[1]))
                 for i in range(n)]
    else:
        if doc.get("noise", "ito") != "ito":
            raise SystemExit("%s: stratonovich noise needs diffusion:" % path)
        G = sp.Matrix([[_parse(e, names, "%s: diffusion_covariance" % path) for e in row]
                       for row in doc["diffusion_covariance"]])
    obs = doc["observation"]
    if "h" in obs:
        h = [_parse(e, names, "%s: observation h" % path) for e in obs["h"]]
        h_given = True
    else:
        A = [[_parse(e, names, "%s: observation A" % path) for e in row] for row in obs["A"]]
        p = len(A)
        A0 = [_parse(e, names, "%s: observation A0" % path) for e in obs.get("A0", ["0"] * p)]
        h = [A0[r] + sum(A[r][j] * X[j] for j in range(n)) for r in range(p)]
        h_given = False
    if "delay" in obs or "sampled" in obs:
        raise SystemExit("%s: delayed and sampled observations are not checked here" % path)
    B = sp.Matrix([[_parse(e, names, "%s: observation B" % path) for e in row] for row in obs["B"]])
    R = (B * B.T).applyfunc(sp.simplify)
    if R.free_symbols:
        raise SystemExit("%s: this check needs B constant" % path)
    model = Model(doc.get("name", os.path.basename(path)), n, [sp.expand(e) for e in f], G,
                  [sp.expand(e) for e in h], R, h_given)
    return model


# ----------------------------------------------------------------------------------------------
# Multi-indices, names
# ----------------------------------------------------------------------------------------------
def multi_indices(n, order):
    """All alpha in N^n with |alpha| = order."""
    for c in itertools.combinations_with_replacement(range(n), order):
        a = [0] * n
        for i in c:
            a[i] += 1
        yield tuple(a)


def index_tuple(alpha):
    """(1,2) -> (0,1,1): the sorted 0-based index list of a multi-index."""
    return tuple(i for i, a in enumerate(alpha) for _ in range(a))


def alpha_of(indices, n):
    a = [0] * n
    for i in indices:
        a[i] += 1
    return tuple(a)


def moment_name(indices, n):
    """M3_112 (1-based, sorted); separated by '_' from n >= 10."""
    order = len(indices)
    parts = [str(i + 1) for i in sorted(indices)]
    return "M%d_%s" % (order, ("_" if n >= 10 else "").join(parts))


def mfact(alpha):
    r = 1
    for a in alpha:
        r *= math.factorial(a)
    return r


# ----------------------------------------------------------------------------------------------
# Step 1-2: cumulants -> raw moments by the truncated exponential of the CGF
# ----------------------------------------------------------------------------------------------
def cumulants(n, k, m, P, M3, M4):
    """kappa[alpha] for 1 <= |alpha| <= k. m list, P matrix, M3/M4 dicts of sorted 0-based index
    tuples -> value (exact)."""
    kap = {}
    for i in range(n):
        kap[alpha_of((i,), n)] = m[i]
    if k >= 2:
        for i, j in itertools.combinations_with_replacement(range(n), 2):
            kap[alpha_of((i, j), n)] = P[i][j]
    if k >= 3:
        for idx in itertools.combinations_with_replacement(range(n), 3):
            kap[alpha_of(idx, n)] = M3[idx]
    if k >= 4:
        for idx in itertools.combinations_with_replacement(range(n), 4):
            i, j, l, q = idx
            kap[alpha_of(idx, n)] = M4[idx] - (P[i][j] * P[l][q] + P[i][l] * P[j][q]
                                               + P[i][q] * P[j][l])
    if k > 4:
        raise ValueError("order > 4 not supported")
    return kap


def raw_moments_series(n, kap, N):
    """{beta: E[x^beta]} for |beta| <= N: beta! times the coefficient of s^beta in the power
    series exp(K(s)), K = sum kappa_a s^a / a!, truncated at total degree N (exact, over QQ)."""
    Rg, *s = ring(",".join("s%d" % (i + 1) for i in range(n)), QQ)
    K = Rg(0)
    for a, v in kap.items():
        term = Rg(QQ(int(sp.Rational(v).p), int(sp.Rational(v).q)) / mfact(a))
        for i, ai in enumerate(a):
            term *= s[i] ** ai
        K += term

    def trunc(poly):
        return Rg({mon: c for mon, c in poly.items() if sum(mon) <= N})

    # exp(K) = sum_j K^j / j!; K has no constant term, so K^j starts at degree j <= N.
    E = Rg(1)
    Kj = Rg(1)
    for j in range(1, N + 1):
        Kj = trunc(Kj * K)
        if not Kj:
            break
        E += Kj * QQ(1, math.factorial(j))
    coeffs = dict(E.items())
    raw = {}
    for order in range(N + 1):
        for beta in multi_indices(n, order):
            c = coeffs.get(tuple(beta), QQ(0))
            raw[beta] = sp.Rational(int(c.numerator), int(c.denominator)) * mfact(beta)
    return raw


# ----------------------------------------------------------------------------------------------
# Step 3-4: raw-moment KS equations, then Ito's formula to the central moments
# ----------------------------------------------------------------------------------------------
class Reference:
    """Everything that depends on (model, k) only; evaluate(point) gives the numbers."""

    def __init__(self, model, k):
        self.model, self.k = model, k
        n, X = model.n, model.X
        self.N = k + max(model.deg(model.f) - 1, model.deg(list(model.G)) - 2, model.deg(model.h), 0)
        self.betas = [b for o in range(1, k + 1) for b in multi_indices(n, o)]
        # Step 3's polynomials: L x^beta and x^beta h_r, in X (coefficients in T).
        self.L = {}
        self.phih = {}
        for beta in self.betas:
            phi = sp.Mul(*[X[i] ** beta[i] for i in range(n)])
            Lphi = sum(model.f[i] * sp.diff(phi, X[i]) for i in range(n))
            Lphi += sp.Rational(1, 2) * sum(model.G[i, j] * sp.diff(phi, X[i], X[j])
                                            for i in range(n) for j in range(n))
            self.L[beta] = sp.expand(Lphi)
            self.phih[beta] = [sp.expand(phi * hr) for hr in model.h]
        # Step 4's symbolic F_z of the raw-moment symbols.
        self.Msym = {b: sp.Symbol("M_" + "_".join(map(str, b))) for b in self.betas}
        zero = tuple([0] * n)
        e = [tuple(1 if j == i else 0 for j in range(n)) for i in range(n)]

        def Msym(b):
            return sp.Integer(1) if b == zero else self.Msym[b]

        def central(alpha):
            """E[(x - m)^alpha] = sum_{gamma <= alpha} prod C(alpha_i, gamma_i) M_gamma (-m)^(alpha-gamma)."""
            out = 0
            for gamma in itertools.product(*[range(a + 1) for a in alpha]):
                c = 1
                for a, g in zip(alpha, gamma):
                    c *= math.comb(a, g)
                mpow = sp.Mul(*[(-self.Msym[e[i]]) ** (alpha[i] - gamma[i]) for i in range(n)])
                out += c * Msym(tuple(gamma)) * mpow
            return sp.expand(out)

        # State variables: (key, label, F)
        self.vars = []
        for i in range(n):
            self.vars.append((("m", i), self.Msym[e[i]]))
        for i in range(n):
            for j in range(n):
                self.vars.append((("P", i, j), central(alpha_of((i, j), n))))
        self.moment_names = []
        for order in range(3, k + 1):
            for idx in itertools.combinations_with_replacement(range(n), order):
                name = moment_name(idx, n)
                self.moment_names.append(name)
                self.vars.append((("M", name), central(alpha_of(idx, n))))
        syms = [self.Msym[b] for b in self.betas]
        self.grad = {}
        self.hess = {}
        for key, F in self.vars:
            self.grad[key] = [(b, sp.diff(F, self.Msym[b])) for b in self.betas]
            self.grad[key] = [(b, d) for b, d in self.grad[key] if d != 0]
            hs = []
            for bi, b in enumerate(self.betas):
                for c in self.betas[bi:]:
                    d2 = sp.diff(F, self.Msym[b], self.Msym[c])
                    if d2 != 0:
                        hs.append((b, c, d2 if b == c else 2 * d2))  # symmetric pair counted twice
            self.hess[key] = hs
        del syms

    def expect(self, expr, raw, tval):
        expr = expr.subs(self.model.T, tval)
        if expr == 0:
            return sp.Integer(0)
        poly = sp.Poly(expr, *self.model.X)
        return sp.expand(sum(c * raw[mon] for mon, c in poly.terms()))

    def evaluate(self, point):
        model, n, k = self.model, self.model.n, self.k
        tval = point["t"]
        kap = cumulants(n, k, point["m"], point["P"], point.get("M3"), point.get("M4"))
        raw = raw_moments_series(n, kap, self.N)
        Eh = [self.expect(hr, raw, tval) for hr in model.h]
        drift, gain = {}, {}
        for beta in self.betas:
            drift[beta] = self.expect(self.L[beta], raw, tval)
            cov = sp.Matrix([[self.expect(self.phih[beta][r], raw, tval) - raw[beta] * Eh[r]
                              for r in range(model.p)]])
            gain[beta] = cov * model.Rinv  # row vector: (cov)^T R^-1 as R is symmetric
        subs = {self.Msym[b]: raw[b] for b in self.betas}
        qv = {}

        def covar(b, c):
            if (b, c) not in qv:
                qv[(b, c)] = (gain[b] * model.R * gain[c].T)[0, 0]
            return qv[(b, c)]

        out = {}
        for key, F in self.vars:
            g = sp.zeros(1, model.p)
            d = sp.Integer(0)
            for b, dF in self.grad[key]:
                v = dF.subs(subs)
                g += v * gain[b]
                d += v * drift[b]
            for b, c, d2 in self.hess[key]:
                d += sp.Rational(1, 2) * d2.subs(subs) * covar(b, c)
            out[key] = (d, g)
        num = lambda v: float(sp.N(v, PRECISION))
        res = {
            "m_drift": [num(out[("m", i)][0]) for i in range(n)],
            "gain": [[num(out[("m", i)][1][r]) for r in range(model.p)] for i in range(n)],
            "P_drift": [[num(out[("P", i, j)][0]) for j in range(n)] for i in range(n)],
            # P_gain is [p][n][n], one n x n matrix per observation, as pfgen eval prints it
            # today (docs/guide/commands.md; polynomial_evaluation.cpp), not [n][n][p].
            "P_gain": [[[num(out[("P", i, j)][1][r]) for j in range(n)] for i in range(n)]
                       for r in range(model.p)],
            "predicted_observation": [num(v) for v in Eh],
        }
        if k >= 3:
            res["moments"] = list(self.moment_names)
            res["moment_drift"] = [num(out[("M", nm)][0]) for nm in self.moment_names]
            res["moment_gain"] = [[num(out[("M", nm)][1][r]) for r in range(model.p)]
                                  for nm in self.moment_names]
        res["_exact"] = out
        res["_raw"] = raw
        return res


# ----------------------------------------------------------------------------------------------
# Points
# ----------------------------------------------------------------------------------------------
def gaussian_m4(P, idx):
    i, j, l, q = idx
    return P[i][j] * P[l][q] + P[i][l] * P[j][q] + P[i][q] * P[j][l]


def draw_point(model_name, n, k, index):
    """Deterministic (seeded by model, order and index) point with exact decimal entries:
    m in [-0.8, 0.8]; P = L L^T, L lower triangular with diagonal in [0.5, 1.1] (P positive
    definite); M3 entries in [-0.3, 0.3]; M4 = Gaussian value for P + a perturbation in
    [-0.2, 0.2]; t in [0, 3]."""
    rng = random.Random("%s/order%d/point%d" % (model_name, k, index))
    R = sp.Rational
    m = [R(rng.randint(-80, 80), 100) for _ in range(n)]
    L = [[R(rng.randint(5, 11), 10) if i == j else (R(rng.randint(-5, 5), 10) if j < i else 0)
          for j in range(n)] for i in range(n)]
    P = [[sum(L[i][a] * L[j][a] for a in range(n)) for j in range(n)] for i in range(n)]
    pt = {"m": m, "P": P, "t": R(rng.randint(0, 30), 10)}
    if k >= 3:
        pt["M3"] = {idx: R(rng.randint(-30, 30), 100)
                    for idx in itertools.combinations_with_replacement(range(n), 3)}
    if k >= 4:
        pt["M4"] = {idx: gaussian_m4(P, idx) + R(rng.randint(-20, 20), 100)
                    for idx in itertools.combinations_with_replacement(range(n), 4)}
    return pt


def dec(r):
    """Exact decimal text of a rational whose denominator divides a power of 10."""
    r = sp.Rational(r)
    for d in range(0, 40):
        if (10 ** d) % r.q == 0:
            break
    else:
        raise ValueError("%s has no terminating decimal" % r)
    v = r.p * (10 ** d // r.q)
    sign = "-" if v < 0 else ""
    v = abs(v)
    ip, fp = divmod(v, 10 ** d)
    if d == 0 or fp == 0:
        return sign + str(ip)
    return sign + str(ip) + "." + str(fp).rjust(d, "0").rstrip("0")


def pfgen_args(model_path, kind, pt, n):
    args = ["eval", "--filter", kind,
            "--m=" + ",".join(dec(v) for v in pt["m"]),
            "--P=" + ";".join(",".join(dec(v) for v in row) for row in pt["P"]),
            "--t=" + dec(pt["t"])]
    for key in ("M3", "M4"):
        for idx, v in sorted(pt.get(key, {}).items()):
            args.append("--moment=%s=%s" % (moment_name(idx, n), dec(v)))
    return args + [model_path]


# ----------------------------------------------------------------------------------------------
# Comparison
# ----------------------------------------------------------------------------------------------
def flatten(v, path=()):
    if isinstance(v, list):
        for i, x in enumerate(v):
            yield from flatten(x, path + (i,))
    else:
        yield path, v


def compare(ref, got, model, k):
    """List of (key, entry, pfgen, reference) mismatches; and the largest relative error."""
    bad = []
    worst = 0.0
    keys = ["m_drift", "gain", "P_drift"]
    if k >= 3 or model.nonlinear_h:
        keys.append("P_gain")
    if model.nonlinear_h:
        keys.append("predicted_observation")
    if k >= 3:
        keys += ["moment_drift", "moment_gain"]
    for opt in ("P_gain", "predicted_observation"):
        if opt in got and opt not in keys:
            keys.append(opt)
    refv = dict(ref)
    if k >= 3:
        if "moments" not in got:
            bad.append(("moments", "", "missing", ref["moments"]))
            return bad, worst
        names = got["moments"]
        if sorted(names) != sorted(ref["moments"]):
            bad.append(("moments", "", names, ref["moments"]))
            return bad, worst
        pos = {nm: i for i, nm in enumerate(ref["moments"])}
        refv["moment_drift"] = [ref["moment_drift"][pos[nm]] for nm in names]
        refv["moment_gain"] = [ref["moment_gain"][pos[nm]] for nm in names]
    for key in keys:
        if key not in got:
            bad.append((key, "", "missing", "present"))
            continue
        r = list(flatten(refv[key]))
        g = list(flatten(got[key]))
        if [p for p, _ in r] != [p for p, _ in g]:
            bad.append((key, "shape", json.dumps(got[key]), json.dumps(refv[key])))
            continue
        for (path, rv), (_, gv) in zip(r, g):
            if not isinstance(gv, (int, float)) or gv is None:
                bad.append((key, path, gv, rv))
                continue
            diff = abs(gv - rv)
            scale = max(abs(gv), abs(rv))
            ok = diff <= RTOL * scale or diff <= ATOL
            if scale > 0 and diff > ATOL:
                worst = max(worst, diff / scale)
            if not ok:
                label = path
                if key in ("moment_drift", "moment_gain"):
                    label = (got["moments"][path[0]],) + path[1:]
                bad.append((key, label, gv, rv))
    return bad, worst


def fmt_entry(path):
    if path == "" or path == "shape":
        return str(path)
    return "[" + "][".join(str(p) for p in path) + "]"


def run_one(pfgen, model_path, model, ref, k, index, verbose):
    """Returns (status, line); status 0 ok, 1 mismatch, 2 pfgen failed."""
    kind = KIND_OF_ORDER[k]
    pt = draw_point(model.name, model.n, k, index)
    args = pfgen_args(model_path, kind, pt, model.n)
    refres = ref.evaluate(pt)
    where = "%s order %d (%s) point %d" % (model.name, k, kind, index + 1)
    proc = subprocess.run([pfgen] + args, capture_output=True, text=True)
    cmd = " ".join([pfgen] + ["'%s'" % a if ";" in a else a for a in args])
    if verbose:
        print("  command:", cmd)
        print("  reference:", json.dumps({a: b for a, b in refres.items()
                                          if not a.startswith("_")}))
    if proc.returncode != 0:
        msg = proc.stderr.strip().splitlines()
        hint = ""
        if k >= 3:
            hint = (" (does this pfgen implement the filter kind '%s' with --moment yet?)" % kind)
        return 2, ("FAIL %s: pfgen eval exited %d%s: %s\n     command: %s"
                   % (where, proc.returncode, hint, msg[-1] if msg else "", cmd))
    try:
        got = json.loads(proc.stdout)
    except json.JSONDecodeError as exc:
        return 2, "FAIL %s: pfgen's output is not JSON (%s)\n     command: %s" % (where, exc, cmd)
    if verbose:
        print("  pfgen:", json.dumps(got))
    bad, worst = compare(refres, got, model, k)
    if bad:
        lines = ["MISMATCH %s: %d entries differ" % (where, len(bad))]
        for key, path, gv, rv in bad[:20]:
            lines.append("     %s%s: pfgen %s, reference %s" % (key, fmt_entry(path), gv, rv))
        lines.append("     command: %s" % cmd)
        return 1, "\n".join(lines)
    return 0, "ok   %s: agree (largest relative difference %.1e)" % (where, worst)


# ----------------------------------------------------------------------------------------------
# Self-test: the algorithm's own pieces against independent formulas
# ----------------------------------------------------------------------------------------------
def raw_moments_recursion(n, kap, N):
    """Moment-cumulant recursion M_{beta+e_i} = sum_{gamma<=beta} C(beta,gamma) kappa_{gamma+e_i}
    M_{beta-gamma} (dM/ds_i = dK/ds_i M), independent of the series code."""
    zero = tuple([0] * n)
    M = {zero: sp.Integer(1)}
    for order in range(1, N + 1):
        for alpha in multi_indices(n, order):
            i = next(j for j in range(n) if alpha[j] > 0)
            beta = tuple(a - (1 if j == i else 0) for j, a in enumerate(alpha))
            tot = 0
            for gamma in itertools.product(*[range(b + 1) for b in beta]):
                c = 1
                for b, g in zip(beta, gamma):
                    c *= math.comb(b, g)
                ga = tuple(g + (1 if j == i else 0) for j, g in enumerate(gamma))
                kv = kap.get(ga, 0)
                if kv:
                    tot += c * kv * M[tuple(b - g for b, g in zip(beta, gamma))]
            M[alpha] = tot
    return M


def isserlis_raw(n, m, P, beta):
    """E[x^beta] for x ~ N(m, P): binomial expansion around m, central moments by Isserlis
    (sum over perfect matchings)."""
    def central(idx):
        if not idx:
            return sp.Integer(1)
        if len(idx) % 2:
            return sp.Integer(0)
        first, rest = idx[0], idx[1:]
        return sum(P[first][rest[j]] * central(rest[:j] + rest[j + 1:]) for j in range(len(rest)))
    tot = 0
    for gamma in itertools.product(*[range(b + 1) for b in beta]):
        c = 1
        for b, g in zip(beta, gamma):
            c *= math.comb(b, g)
        mp = sp.Mul(*[m[i] ** (beta[i] - gamma[i]) for i in range(n)])
        tot += c * mp * central(index_tuple(gamma))
    return tot


def self_test():
    t0 = time.time()
    fails = []
    n = 2
    # 1. series vs the moment-cumulant recursion, non-Gaussian cumulants up to order 4, N = 7.
    pt = draw_point("selftest", n, 4, 0)
    kap = cumulants(n, 4, pt["m"], pt["P"], pt["M3"], pt["M4"])
    a = raw_moments_series(n, kap, 7)
    b = raw_moments_recursion(n, kap, 7)
    d = [beta for beta in a if sp.simplify(a[beta] - b[beta]) != 0]
    if d:
        fails.append("series vs recursion differ at %s" % d[:5])
    # 1b. Round trip: the central moments of the series' raw moments are the state's m, P, M3, M4
    #     (checks step 1's cumulants, kappa_4 in particular); with M3 = 0 and M4 Gaussian
    #     the order-4 series is the Gaussian one (Isserlis, below).
    for idx in [(0,), (1,)] + list(itertools.combinations_with_replacement(range(n), 2)) + \
            list(itertools.combinations_with_replacement(range(n), 3)) + \
            list(itertools.combinations_with_replacement(range(n), 4)):
        alpha = alpha_of(idx, n)
        cm = 0
        for gamma in itertools.product(*[range(x + 1) for x in alpha]):
            c = 1
            for x, g in zip(alpha, gamma):
                c *= math.comb(x, g)
            cm += c * a[tuple(gamma)] * sp.Mul(*[(-pt["m"][i]) ** (alpha[i] - gamma[i])
                                                  for i in range(n)])
        if len(idx) == 1:
            cm, want = a[alpha], pt["m"][idx[0]]
        elif len(idx) == 2:
            want = pt["P"][idx[0]][idx[1]]
        else:
            want = pt["M%d" % len(idx)][idx]
        if cm != want:
            fails.append("round trip: central moment %s is %s, the state has %s" % (idx, cm, want))
    gm4 = {idx: gaussian_m4(pt["P"], idx) for idx in pt["M4"]}
    zero3 = {idx: 0 for idx in pt["M3"]}
    a4 = raw_moments_series(n, cumulants(n, 4, pt["m"], pt["P"], zero3, gm4), 6)
    d = [beta for beta in a4 if a4[beta] != isserlis_raw(n, pt["m"], pt["P"], beta)]
    if d:
        fails.append("order-4 series with Gaussian M3, M4 vs Isserlis differ at %s" % d[:5])
    # 2. Gaussian (k = 2): series vs Isserlis, exactly.
    kap2 = cumulants(n, 2, pt["m"], pt["P"], None, None)
    a2 = raw_moments_series(n, kap2, 6)
    d = [beta for beta in a2 if a2[beta] != isserlis_raw(n, pt["m"], pt["P"], beta)]
    if d:
        fails.append("Gaussian series vs Isserlis differ at %s" % d[:5])
    # 3. Gaussian: series vs a Monte Carlo (fixed seed), orders <= 4, within 5 standard errors.
    try:
        import numpy as np
        rng = np.random.default_rng(1)
        Pm = np.array([[float(v) for v in row] for row in pt["P"]])
        xs = rng.multivariate_normal([float(v) for v in pt["m"]], Pm, size=400000)
        for order in range(1, 5):
            for beta in multi_indices(n, order):
                vals = np.prod(xs ** np.array(beta), axis=1)
                se = vals.std() / math.sqrt(len(vals))
                if abs(vals.mean() - float(a2[beta])) > 5 * se + 1e-12:
                    fails.append("Monte Carlo E[x^%s] = %.5f +- %.5f, series %.5f"
                                 % (beta, vals.mean(), se, float(a2[beta])))
    except ImportError:
        pass
    # 4. Linear model dx = A x dt + g dW, dy = C x dt + B dV: at order 3 the M3 drift is
    #    sum over the three indices of (A - K C) acting on M3 (K = P C^T R^-1), and the M3 gain is
    #    kappa_4 contracted with C^T R^-1, zero at order 3; at order 4 it is that contraction.
    X = sp.symbols("X1:3")
    A = sp.Matrix([[sp.Rational(-1, 2), 1], [sp.Rational(-3, 10), sp.Rational(-1, 5)]])
    C = sp.Matrix([[1, sp.Rational(1, 2)], [0, 2]])
    Bm = sp.Matrix([[sp.Rational(1, 2), 0], [sp.Rational(1, 10), sp.Rational(3, 10)]])
    gm = sp.Matrix([[sp.Rational(2, 5), 0], [sp.Rational(1, 5), sp.Rational(1, 3)]])
    xv = sp.Matrix(X)
    lin = Model("linear", 2, list(A * xv), gm * gm.T, list(C * xv), Bm * Bm.T, True)
    lin.X = X
    for k in (3, 4):
        ref = Reference(lin, k)
        pt = draw_point("selftest-linear", 2, k, 0)
        res = ref.evaluate(pt)
        P = sp.Matrix(pt["P"])
        K = P * C.T * lin.Rinv
        AK = A - K * C
        CR = C.T * lin.Rinv
        kap = cumulants(2, 4, pt["m"], pt["P"], pt["M3"], pt.get("M4", {
            idx: gaussian_m4(pt["P"], idx) for idx in itertools.combinations_with_replacement(range(2), 4)}))
        for idx in itertools.combinations_with_replacement(range(2), 3):
            name = moment_name(idx, 2)
            expect = 0
            for pos in range(3):
                for a_ in range(2):
                    other = list(idx)
                    other[pos] = a_
                    expect += AK[idx[pos], a_] * pt["M3"][tuple(sorted(other))]
            dgot, ggot = res["_exact"][("M", name)]
            if sp.simplify(dgot - expect) != 0:
                fails.append("linear order %d: drift of %s is %s, expected %s" % (k, name, dgot, expect))
            for r in range(2):
                eg = sum(kap.get(alpha_of(idx + (q,), 2), 0) * CR[q, r] for q in range(2)) if k == 4 else 0
                if sp.simplify(ggot[r] - eg) != 0:
                    fails.append("linear order %d: gain of %s [%d] is %s, expected %s"
                                 % (k, name, r, ggot[r], eg))
    # 5. k = 2 closed forms of the optimal filter on the linear model: m drift A m,
    #    gain P C^T R^-1, P drift A P + P A^T + G - K R K^T.
    ref = Reference(lin, 2)
    pt = draw_point("selftest-linear", 2, 2, 0)
    res = ref.evaluate(pt)
    P = sp.Matrix(pt["P"])
    K = P * C.T * lin.Rinv
    Pd = A * P + P * A.T + lin.G - K * lin.R * K.T
    for i in range(2):
        if sp.simplify(res["_exact"][("m", i)][0] - (A * sp.Matrix(pt["m"]))[i]) != 0:
            fails.append("linear order 2: m drift")
        for r in range(2):
            if sp.simplify(res["_exact"][("m", i)][1][r] - K[i, r]) != 0:
                fails.append("linear order 2: gain")
        for j in range(2):
            if sp.simplify(res["_exact"][("P", i, j)][0] - Pd[i, j]) != 0:
                fails.append("linear order 2: P drift [%d][%d]" % (i, j))
    # 6. A second derivation of steps 3-4 on the test models at orders 3 and 4: Ito-Wentzell on
    #    Phi_alpha(m) = E[(x - m)^alpha] (the KS equation at a fixed m) composed with m_t:
    #      gain_alpha  = E[e^alpha (h - E h)] R^-1 - sum_i alpha_i mu_{alpha-e_i} K_i
    #      drift_alpha = E[L (x-m)^alpha] - sum_i alpha_i mu_{alpha-e_i} E[f_i]
    #                    + 1/2 sum_ij alpha_i (alpha_j - d_ij) mu_{alpha-e_i-e_j} K_i R K_j^T
    #                    - sum_i alpha_i E[e^{alpha-e_i} (h - E h)] K_i^T,
    #    K_i = E[e_i (h - E h)] R^-1, every expectation from the same closed raw moments.
    #    It shares only the cumulant series (checked above) with the main computation.
    for path in DEFAULT_MODELS:
        model = load_model(os.path.join(ROOT, path))
        for k in (3, 4):
            ref = Reference(model, k)
            pt = draw_point("selftest-" + model.name, model.n, k, 1)
            res = ref.evaluate(pt)
            raw = res["_raw"]
            X, nn, tval = model.X, model.n, pt["t"]
            mv = pt["m"]
            E = lambda expr: ref.expect(sp.expand(expr), raw, tval)
            e = [X[i] - mv[i] for i in range(nn)]
            Eh = [E(hr) for hr in model.h]
            hc = [model.h[r] - Eh[r] for r in range(model.p)]

            def ealpha(alpha):
                return sp.Mul(*[e[i] ** alpha[i] for i in range(nn)])

            def mu(alpha):
                return E(ealpha(alpha)) if min(alpha) >= 0 else 0

            def cov_row(expr):
                return sp.Matrix([[E(expr * hc[r]) for r in range(model.p)]]) * model.Rinv

            Krow = [cov_row(e[i]) for i in range(nn)]
            unit = lambda i: tuple(1 if j == i else 0 for j in range(nn))
            sub = lambda a, b: tuple(x - y for x, y in zip(a, b))
            targets = [(("P", i, j), alpha_of((i, j), nn)) for i in range(nn) for j in range(nn)]
            targets += [(("M", nm), alpha_of(idx, nn)) for nm, idx in
                        ((moment_name(idx, nn), idx) for o in range(3, k + 1)
                         for idx in itertools.combinations_with_replacement(range(nn), o))]
            for key, alpha in targets:
                phi = ealpha(alpha)
                Lphi = sum(model.f[i] * sp.diff(phi, X[i]) for i in range(nn))
                Lphi += sp.Rational(1, 2) * sum(model.G[i, j] * sp.diff(phi, X[i], X[j])
                                                for i in range(nn) for j in range(nn))
                drift = E(Lphi)
                gain = cov_row(phi)
                for i in range(nn):
                    if alpha[i] == 0:
                        continue
                    ai = sub(alpha, unit(i))
                    drift -= alpha[i] * mu(ai) * E(model.f[i])
                    drift -= alpha[i] * (cov_row(ealpha(ai)) * model.R * Krow[i].T)[0, 0]
                    gain -= alpha[i] * mu(ai) * Krow[i]
                    for j in range(nn):
                        c = alpha[i] * (alpha[j] - (1 if i == j else 0))
                        if c:
                            drift += sp.Rational(1, 2) * c * mu(sub(ai, unit(j))) * \
                                (Krow[i] * model.R * Krow[j].T)[0, 0]
                d0, g0 = res["_exact"][key]
                if sp.simplify(sp.expand(d0 - drift)) != 0 or any(
                        sp.simplify(sp.expand(g0[r] - gain[r])) != 0 for r in range(model.p)):
                    fails.append("%s order %d: %s differs from the Ito-Wentzell derivation"
                                 % (model.name, k, key))
    for f_ in fails:
        print("SELF-TEST FAIL:", f_)
    print("%s self-test: series = moment-cumulant recursion (order 7), round trip to m, P, M3, M4, Gaussian = Isserlis and "
          "Monte Carlo, linear model's M3 drift/gain, Kalman-Bucy at order 2, "
          "Ito-Wentzell derivation of orders 3-4 on the test models (%.1f s)"
          % ("FAIL" if fails else "ok  ", time.time() - t0))
    return not fails


# ----------------------------------------------------------------------------------------------
def main():
    ap = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    ap.add_argument("--pfgen", help="path of the pfgen binary")
    ap.add_argument("--orders", default="2,3,4",
                    help="closure orders, comma-separated (2 = optimal, 3 = closure3, 4 = closure4)")
    ap.add_argument("--kind", choices=sorted(ORDER_OF_KIND), help="one filter kind (sets --orders)")
    ap.add_argument("--model", help="one model file (default: the five test models)")
    ap.add_argument("--order", type=int, help="one order (with --model)")
    ap.add_argument("--points", type=int, default=POINTS, help="points per model and order")
    ap.add_argument("--verbose", action="store_true", help="print the commands and both results")
    ap.add_argument("--self-test", action="store_true", help="run only the self-test")
    ap.add_argument("--no-self-test", action="store_true", help="skip the self-test")
    a = ap.parse_args()
    t0 = time.time()
    if a.self_test:
        return 0 if self_test() else 1
    if not a.pfgen:
        ap.error("--pfgen PATH is required")
    pfgen = os.path.abspath(a.pfgen)
    if not os.access(pfgen, os.X_OK):
        print("FAIL: %s is not an executable pfgen" % pfgen)
        return 1
    orders = [int(o) for o in a.orders.split(",")]
    if a.kind:
        orders = [ORDER_OF_KIND[a.kind]]
    if a.order:
        orders = [a.order]
    for k in orders:
        if k not in KIND_OF_ORDER:
            ap.error("orders are 2, 3 or 4")
    models = [a.model] if a.model else [os.path.join(ROOT, p) for p in DEFAULT_MODELS]
    status = 0
    if not a.no_self_test and not self_test():
        status = 1
    counts = {0: 0, 1: 0, 2: 0}
    for path in models:
        model = load_model(path)
        for k in orders:
            ref = Reference(model, k)
            for index in range(a.points):
                st, line = run_one(pfgen, path, model, ref, k, index, a.verbose)
                counts[st] += 1
                print(line, flush=True)
                status = max(status, 1 if st else 0)
    print("%d agree, %d mismatch, %d pfgen failures (%.1f s)"
          % (counts[0], counts[1], counts[2], time.time() - t0))
    return status


if __name__ == "__main__":
    sys.exit(main())
