#!/usr/bin/env python3
"""pfgen against the peer a user would otherwise script: SymPy deriving, CSE-ing and printing the
same Gaussian-closure ("optimal") filter, measured side by side in one run (docs/benchmarks.md,
"SymPy as the peer").

For each model (a pfgen model file: polynomial drift, polynomial diffusion, continuous linear
observation dy = (A0 + A x) dt + B dW), the filter's derivatives() -- the drift of m, E[f], and the
upper triangle of P's drift, P E[J]^T + E[J] P + E[g g^T] - P A^T (B B^T)^-1 A P -- is written three
ways:

  pfgen              `pfgen codegen --language c --scalar double --filter optimal`;
  sympy-expanded     SymPy derives every output as an expanded polynomial in m and P (Gaussian
                     moments by Isserlis' theorem), then one sympy.cse over all outputs;
  sympy-structured   what a careful SymPy user writes: E[f], each E[J] entry and E[g g^T] derived
                     once, P's drift left in its Stein structure (P E[J]^T + E[J] P + E[g g^T] - K (A P),
                     K = P A^T (B B^T)^-1), integer powers as products, then one sympy.cse.

Columns: gen s (pfgen: the whole codegen command; SymPy: derivation, CSE and printing in this
process), ops (operators in the C function body, counted the same way for all three: + - * /, a
unary minus, and each call; a literal's own sign is not an operation), pfgen's own count after CSE
(`--stats`), compile s (gcc -O2 -c of the file), ns/call (median over repeats of a timed loop over
slightly different states), and whether the outputs agree with pfgen's to 1e-9 relative at a random
state with a positive definite P (an independent check of pfgen's derivation).

  benchmarks/bench_sympy_peer.py [--pfgen build/generator/pfgen]
      [--dense-cubic-yaml build/benchmarks/dense_cubic_yaml] [--sizes 2,4,6] [MODEL.yaml ...]
      [--repeats 7] [--min-time 0.2] [--cc gcc] [--work DIR] [--check]

--check: exit with status 1 when a SymPy variant's outputs disagree with pfgen's, or a model given by
name is skipped (the test suite runs it so on small models, as an independent check of pfgen's
derivation and of this script).

Needs python3-sympy and python3-yaml (Debian packages) and a C compiler.
"""
import argparse
import itertools
import os
import random
import re
import shutil
import subprocess
import sys
import tempfile
import time

import sympy as sp
import yaml
from sympy.printing.c import C99CodePrinter


class Unsupported(Exception):
    """A model this peer does not write (the reason goes in the table)."""


# --------------------------------------------------------------------------------------------
# The model


def parse(text, symbols):
    expression = sp.sympify(str(text).replace("^", "**"), locals=symbols)
    return expression


def load_model(path):
    with open(path) as handle:
        doc = yaml.safe_load(handle)
    states = [str(s) for s in doc["states"]]
    n = len(states)
    xs = sp.symbols(" ".join(states), real=True) if n > 1 else (sp.Symbol(states[0], real=True),)
    names = {s: x for s, x in zip(states, xs)}
    time_name = str(doc.get("time", "t"))
    if str(doc.get("noise", "ito")) != "ito":
        raise Unsupported(f"noise: {doc['noise']}")
    if "drift" not in doc or "diffusion" not in doc:
        raise Unsupported("no drift or no diffusion matrix")
    # Parameters stay symbols, read at run time as pfgen's code reads them (so neither side can fold them).
    parameters = {}
    for name, value in (doc.get("parameters") or {}).items():
        parameters[str(name)] = float(value)
        names[str(name)] = sp.Symbol(str(name), real=True)
    drift = [parse(f, names) for f in doc["drift"]]
    diffusion = sp.Matrix([[parse(g, names) for g in row] for row in doc["diffusion"]])
    observation = doc.get("observation") or {}
    if not all(key in observation for key in ("A", "B")) or set(observation) - {"A0", "A", "B"}:
        raise Unsupported("not a continuous linear observation (A0 + A x)")
    A = sp.Matrix([[parse(a, names) for a in row] for row in observation["A"]])
    B = sp.Matrix([[parse(b, names) for b in row] for row in observation["B"]])
    everything = list(drift) + list(diffusion) + list(A) + list(B)
    t = sp.Symbol(time_name)
    for e in everything:
        if e.has(t):
            raise Unsupported("time-varying coefficients")
        if not e.is_polynomial(*xs):
            raise Unsupported("a non-polynomial entry")
    if any(e.free_symbols - set(xs) - {names[p] for p in parameters} for e in everything):
        raise Unsupported("symbols other than the states and parameters")
    return {"name": str(doc["name"]), "xs": list(xs), "drift": drift, "diffusion": diffusion, "A": A, "B": B,
            "parameters": parameters}


# --------------------------------------------------------------------------------------------
# The derivation: Gaussian moments by Isserlis' theorem


def filter_symbols(n):
    """m1..mn and P's entries, named as pfgen names them (P12; P1_10 from n = 10)."""
    ms = [sp.Symbol(f"m{i + 1}", real=True) for i in range(n)]
    P = sp.zeros(n, n)
    upper = []
    for i in range(n):
        for j in range(i, n):
            name = f"P{i + 1}{j + 1}" if n < 10 else f"P{i + 1}_{j + 1}"
            s = sp.Symbol(name, real=True)
            P[i, j] = P[j, i] = s
            upper.append(s)
    return ms, P, upper


class GaussianMoments:
    """E[p(x)] for x ~ N(m, P): x = m + e, and E[e_i1 ... e_ik] by Isserlis (pairings), memoised."""

    def __init__(self, xs, ms, P):
        self.xs, self.ms, self.P = xs, ms, P
        self.es = [sp.Symbol(f"e{i}", real=True) for i in range(len(xs))]
        self.memo = {(): sp.Integer(1)}

    def central(self, indices):
        indices = tuple(sorted(indices))
        if len(indices) % 2:
            return sp.Integer(0)
        if indices not in self.memo:
            first, rest = indices[0], indices[1:]
            total = sp.Integer(0)
            for k in range(len(rest)):
                total += self.P[first, rest[k]] * self.central(rest[:k] + rest[k + 1:])
            self.memo[indices] = sp.expand(total)
        return self.memo[indices]

    def expectation(self, p):
        shifted = sp.expand(p.subs({x: m + e for x, m, e in zip(self.xs, self.ms, self.es)}, simultaneous=True))
        poly = sp.Poly(shifted, *self.es)
        total = sp.Integer(0)
        for exponents, coefficient in poly.terms():
            indices = tuple(itertools.chain.from_iterable([i] * k for i, k in enumerate(exponents)))
            total += coefficient * self.central(indices)
        return sp.expand(total)


def derive(model, structured):
    xs, n = model["xs"], len(model["xs"])
    ms, P, upper = filter_symbols(n)
    E = GaussianMoments(xs, ms, P)
    A, B = model["A"], model["B"]
    R_inv = (B * B.T).inv()
    m_drift = [E.expectation(f) for f in model["drift"]]
    J = sp.Matrix(n, n, lambda i, k: sp.diff(model["drift"][i], xs[k]))
    EJ = J.applyfunc(E.expectation)
    g = model["diffusion"]
    Egg = (g * g.T).applyfunc(E.expectation)
    if structured:
        K = P * A.T * R_inv
        drift_P = P * EJ.T + EJ * P + Egg - K * (A * P)
    else:
        drift_P = (P * EJ.T + EJ * P + Egg - P * A.T * R_inv * A * P).applyfunc(sp.expand)
    return ms + upper, m_drift + [drift_P[i, j] for i in range(n) for j in range(i, n)]


# --------------------------------------------------------------------------------------------
# Printing C


def c_function(name, inputs, outputs, parameters):
    """C99 `void name(const double* state, double* out)`: one sympy.cse over every output; the
    parameters are read from the array sympy_parameters, in the model's order."""
    # Rationals from the moments as doubles, integer powers as products (what a careful user does).
    from sympy.codegen.rewriting import create_expand_pow_optimization, optimize

    expand_pow = create_expand_pow_optimization(8)
    replacements, reduced = sp.cse(outputs, symbols=sp.numbered_symbols("tmp"))
    printer = C99CodePrinter({"precision": 17})

    def text(e):
        e = e.xreplace({r: sp.Float(r, 17) for r in e.atoms(sp.Rational) if not r.is_Integer})
        return printer.doprint(optimize(e, [expand_pow]))

    lines = [f"void {name}(const double* state, double* out) {{"]
    lines += [f"  const double {s} = state[{k}];" for k, s in enumerate(inputs)]
    lines += [f"  const double {p} = sympy_parameters[{k}];" for k, p in enumerate(parameters)]
    lines += [f"  const double {s} = {text(e)};" for s, e in replacements]
    lines += [f"  out[{k}] = {text(e)};" for k, e in enumerate(reduced)]
    lines.append("}")
    return "\n".join(lines) + "\n"


NUMBER = r"(?:\d+\.\d*|\.\d+|\d+)(?:[eE][+-]?\d+)?[fF]?"


LOOP = re.compile(r"^\s*for \(int (\w+) = (\w+)(?:, \w+ = 0)?; \1 < (\d+); [^)]*\)\s*(.*)$")


def statement_ops(line):
    """Operators in one C statement's right-hand side: + - * / (a unary minus too) and calls; a
    literal's own sign is not one, nor is an array index's arithmetic."""
    rhs = line.split("=", 1)[1]
    rhs = re.sub(r"\w+\[[^\]]*\]", "v", rhs)  # array elements, whatever their index
    rhs = re.sub(r"\w+->\w+", "v", rhs)  # a parameter record's field
    rhs = re.sub(r"\(\s*-\s*" + NUMBER + r"\s*\)", "c", rhs)  # a negative literal in parentheses
    rhs = re.sub(r"(?<![\w.])" + NUMBER, "c", rhs)
    return len(re.findall(r"[-+*/]", rhs)) + len(re.findall(r"\b(?:pow|sqrt|exp|log|sin|cos|tan)\s*\(", rhs))


def count_ops(body):
    """Operators in C statements (statement_ops), each statement inside pfgen's loops counted once per
    iteration: `for (int i = 0; i < R; ++i)` runs R times, and an inner `for (int j = i; j < N; ...)`
    under `for (int i = 0; i < N; ...)` N (N + 1) / 2 times in all."""
    total = 0
    outer = None  # (variable, bound) of a loop header whose body is the next line
    for line in body.splitlines():
        if line.strip().startswith("//"):
            continue
        trips = 1
        loop = LOOP.match(line)
        if loop:
            variable, start, bound, statement = loop.groups()
            bound = int(bound)
            if outer and start == outer[0]:  # for (j = i; j < N; ...) under for (i = 0; i < N; ...)
                if outer[1] != bound:
                    raise ValueError("unexpected loop nest: " + line)
                trips = bound * (bound + 1) // 2
            elif start.isdigit():
                trips = (bound - int(start)) * (outer[1] if outer else 1)
            else:
                raise ValueError("unexpected loop: " + line)
            if not statement.strip():
                outer = (variable, bound)
                continue
            line = statement
        outer = None
        if "=" in line:
            total += trips * statement_ops(line)
    return total


def function_body(c_text, name):
    """The body of function `name` and of the static parts it calls (pfgen's split functions)."""
    start = c_text.index(name + "(")
    body = c_text[c_text.index("{", start):]
    depth, end = 0, 0
    for k, ch in enumerate(body):
        depth += ch == "{"
        depth -= ch == "}"
        if depth == 0:
            end = k
            break
    own = body[: end + 1]
    parts = "".join(
        c_text[c_text.index("{", m.start()):c_text.index("\n}\n", m.start()) + 2]
        for m in re.finditer(r"static void (" + re.escape(name) + r"_part\d+)\(", c_text))
    return own + parts


# --------------------------------------------------------------------------------------------
# Timing and checking


HARNESS = r"""
#define _POSIX_C_SOURCE 199309L
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <time.h>
#include "%(pfgen_header)s"
#define STATE %(state_size)d
double sympy_parameters[] = {%(parameters)s};
void sympy_expanded(const double* state, double* out);
void sympy_structured(const double* state, double* out);
// Each function is called through a wrapper of the same shape, one call deeper for all three.
static %(params_type)s params;
static void pfgen_call(const double* state, double* out) { %(pfgen_function)s(0.0, state, &params, out); }
static void expanded_call(const double* state, double* out) { sympy_expanded(state, out); }
static void structured_call(const double* state, double* out) { sympy_structured(state, out); }
static double now(void) { struct timespec t; clock_gettime(CLOCK_MONOTONIC, &t); return t.tv_sec + 1e-9 * t.tv_nsec; }
typedef void (*fn)(const double*, double*);
static const double initial[STATE] = {%(state)s};
static double ns_per_call(fn f, double min_time) {
  double state[STATE], out[STATE], sink = 0;
  memcpy(state, initial, sizeof state);
  long calls = 0;
  double start = now(), elapsed;
  do {
    for (int k = 0; k < 1000; ++k) {
      state[0] = initial[0] + 1e-12 * (k & 7);
      f(state, out);
      sink += out[STATE - 1];
    }
    calls += 1000;
  } while ((elapsed = now() - start) < min_time);
  if (sink == 12345.678) puts("");
  return 1e9 * elapsed / calls;
}
static int cmp(const void* a, const void* b) { double x = *(const double*)a, y = *(const double*)b; return (x > y) - (x < y); }
int main(int argc, char** argv) {
  int repeats = atoi(argv[1]);
  double min_time = atof(argv[2]);
  %(default_params)s(&params);
  fn fs[3] = {pfgen_call, expanded_call, structured_call};
  double reference[STATE], out[STATE], worst[3] = {0, 0, 0};
  pfgen_call(initial, reference);
  for (int f = 1; f < 3; ++f) {
    fs[f](initial, out);
    for (int k = 0; k < STATE; ++k) {
      double scale = fabs(reference[k]) > 1 ? fabs(reference[k]) : 1;
      double d = fabs(out[k] - reference[k]) / scale;
      if (!(d <= worst[f])) worst[f] = d;
    }
  }
  for (int f = 0; f < 3; ++f) {
    double t[64];
    for (int r = 0; r < repeats && r < 64; ++r) t[r] = ns_per_call(fs[f], min_time);
    qsort(t, repeats, sizeof t[0], cmp);
    printf("%%d %%.2f %%.3g\n", f, t[repeats / 2], worst[f]);
  }
  return 0;
}
"""


def random_state(n, seed):
    rng = random.Random(seed)
    ms = [rng.uniform(-1, 1) for _ in range(n)]
    L = [[rng.uniform(-0.5, 0.5) if j <= i else 0.0 for j in range(n)] for i in range(n)]
    P = [[sum(L[i][k] * L[j][k] for k in range(n)) + (0.5 if i == j else 0.0) for j in range(n)] for i in range(n)]
    return ms + [P[i][j] for i in range(n) for j in range(i, n)]


def timed(command, **kwargs):
    start = time.perf_counter()
    result = subprocess.run(command, capture_output=True, text=True, **kwargs)
    return time.perf_counter() - start, result


def compile_seconds(cc, source, work):
    seconds, result = timed([cc, "-std=c99", "-O2", "-c", source, "-o", os.path.join(work, os.path.basename(source) + ".o")])
    if result.returncode:
        raise RuntimeError(f"{cc} failed on {source}: {result.stderr.strip().splitlines()[0]}")
    return seconds


def bench_model(path, args, work):
    model = load_model(path)
    name, n = model["name"], len(model["xs"])
    out = os.path.join(work, name)
    os.makedirs(out, exist_ok=True)

    # pfgen: the whole command, as a user runs it.
    gen_pfgen, result = timed([args.pfgen, "codegen", path, "--filter", "optimal", "--language", "c", "--scalar",
                               "double", "-o", out, "--stats"])
    if result.returncode:
        raise Unsupported("pfgen: " + result.stderr.strip().splitlines()[0])
    stats = re.search(r'"function": "derivatives", "naive": \{[^}]*\}, "cse": \{[^}]*"total": (\d+)', result.stdout)
    c_path = os.path.join(out, name, "optimal.c")
    with open(c_path) as handle:
        pfgen_c = handle.read()
    prefix = f"pfgen_models_{name}_optimal"
    inputs_pfgen = re.findall(r"const double (\w+) = state\[(\d+)\];", function_body(pfgen_c, prefix + "_derivatives"))
    order = [v for v, _ in sorted(set(inputs_pfgen), key=lambda p: int(p[1]))]

    rows = [("pfgen", gen_pfgen, count_ops(function_body(pfgen_c, prefix + "_derivatives")),
             int(stats.group(1)) if stats else None, compile_seconds(args.cc, c_path, out))]
    sources = []
    for variant in ("expanded", "structured"):
        start = time.perf_counter()
        inputs, outputs = derive(model, structured=variant == "structured")
        text = c_function(f"sympy_{variant}", [str(s) for s in inputs], outputs, list(model["parameters"]))
        gen = time.perf_counter() - start
        if [str(s) for s in inputs] != order[: len(inputs)] and len(order) == len(inputs):
            raise RuntimeError(f"{name}: SymPy's state order {inputs} is not pfgen's {order}")
        source = os.path.join(out, f"sympy_{variant}.c")
        with open(source, "w") as handle:
            handle.write("#include <math.h>\nextern double sympy_parameters[];\n" + text)
        sources.append(source)
        rows.append((f"sympy-{variant}", gen, count_ops(text), None, compile_seconds(args.cc, source, out)))

    state = random_state(n, 20261127)
    harness = os.path.join(out, "harness.c")
    with open(harness, "w") as handle:
        handle.write(HARNESS % {
            "pfgen_header": os.path.join(out, name, "optimal.h"), "state_size": len(state),
            "params_type": prefix + "_params", "default_params": prefix + "_default_params",
            "pfgen_function": prefix + "_derivatives", "state": ", ".join(repr(v) for v in state),
            "parameters": ", ".join(repr(v) for v in model["parameters"].values()) or "0"})
    binary = os.path.join(out, "harness")
    build = subprocess.run([args.cc, "-std=c99", "-O2", harness, c_path] + sources + ["-o", binary, "-lm"],
                           capture_output=True, text=True)
    if build.returncode:
        raise RuntimeError(f"harness build failed: {build.stderr.strip().splitlines()[0]}")
    timing = subprocess.run([binary, str(args.repeats), str(args.min_time)], capture_output=True, text=True, check=True)
    measured = {int(f): (float(ns), float(diff)) for f, ns, diff in (line.split() for line in timing.stdout.split("\n") if line)}
    return name, n, rows, measured


def main():
    parser = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    parser.add_argument("models", nargs="*")
    parser.add_argument("--pfgen", default="build/generator/pfgen")
    parser.add_argument("--dense-cubic-yaml", default="build/benchmarks/dense_cubic_yaml")
    parser.add_argument("--sizes", default="2,4,6", help="dense cubic sizes (empty: none)")
    parser.add_argument("--repeats", type=int, default=7)
    parser.add_argument("--min-time", type=float, default=0.2)
    parser.add_argument("--cc", default="gcc")
    parser.add_argument("--work")
    parser.add_argument("--check", action="store_true", help="fail on a disagreement or a skipped model")
    args = parser.parse_args()
    for tool in (args.pfgen,):
        if not os.access(tool, os.X_OK):
            sys.exit(f"bench_sympy_peer: no pfgen at '{tool}' (build it, or pass --pfgen)")
    if shutil.which(args.cc) is None:
        sys.exit(f"bench_sympy_peer: no C compiler '{args.cc}'")
    work = args.work or tempfile.mkdtemp(prefix="pfgen-sympy-")
    os.makedirs(work, exist_ok=True)
    models = []
    for size in [s for s in args.sizes.split(",") if s]:
        if not os.access(args.dense_cubic_yaml, os.X_OK):
            sys.exit(f"bench_sympy_peer: no dense_cubic_yaml at '{args.dense_cubic_yaml}' (-DPFGEN_BUILD_BENCHMARKS=ON)")
        path = os.path.join(work, f"dense_cubic_{size}.yaml")
        with open(path, "w") as handle:
            subprocess.run([args.dense_cubic_yaml, size], stdout=handle, check=True)
        models.append(path)
    models += args.models

    print(f"sympy {sp.__version__}, {args.cc} -O2, ns/call: median of {args.repeats} loops of at least {args.min_time} s")
    print("| model | n | tool | gen s | ops | pfgen's count | compile s | ns/call | x pfgen | agrees |")
    print("|---|---|---|---|---|---|---|---|---|---|")
    failed = False
    for path in models:
        try:
            name, n, rows, measured = bench_model(path, args, work)
        except Unsupported as reason:
            print(f"| {os.path.basename(path)} | | skipped: {reason} | | | | | | | |")
            failed = True
            continue
        base = measured[0][0]
        for k, (tool, gen, ops, own, compile_s) in enumerate(rows):
            ns, diff = measured[k]
            agrees = "-" if k == 0 else ("yes" if diff <= 1e-9 else f"NO ({diff:.2g})")
            failed = failed or agrees.startswith("NO")
            print(f"| {name} | {n} | {tool} | {gen:.3f} | {ops} | {own if own is not None else '-'} | {compile_s:.2f} | "
                  f"{ns:.1f} | {ns / base:.2f} | {agrees} |")
        sys.stdout.flush()
    if not args.work:
        shutil.rmtree(work)
    if args.check and failed:
        sys.exit("bench_sympy_peer: a model was skipped or a SymPy variant disagrees with pfgen")


if __name__ == "__main__":
    main()
