"""pfgen from Python: Basin, Perez & Skliar 2006's quadratic example derived, inspected,
evaluated, generated and simulated, in one process. From the source directory, after the build:

    PYTHONPATH=build/python python3 examples/python/quickstart.py

(docs/guide/python.md; in Jupyter, a cell ending in `optimal` shows its equations as LaTeX).
"""
import os

import sympy

import pfgen

here = os.path.dirname(os.path.abspath(__file__))
model = pfgen.Model.load(os.path.join(here, "..", "basin2006_quadratic.yaml"))
print("filters:", ", ".join(model.kinds))

# Derive: the text `pfgen derive` prints (also .latex, .json, and .to_sympy()).
optimal = model.derive("optimal")
print(optimal.text)

# Evaluate at t = 0, m = 0.5, P = 1, as `pfgen eval` does: numpy arrays.
values = optimal.eval(0, [0.5], [[1]])
print("m_drift", values["m_drift"], "gain", values["gain"].tolist(), "P_drift", values["P_drift"].tolist())

# The equations in SymPy, against the paper's (21)-(22).
eq = optimal.to_sympy()
m, P = eq.symbols["m1"], eq.symbols["P11"]
tenth = sympy.Rational(1, 10)
published_m = tenth * (m**2 + P)
published_P = (4 * tenth * P * m + sympy.Rational(3, 100) * P**2 + sympy.Rational(6, 100) * P * m**2
               + sympy.Rational(1, 100) * m**4 - P**2)
same = sympy.expand(eq.m_drift[0] - published_m) == 0 and sympy.expand(eq.P_drift[0, 0] - published_P) == 0
print("equal to equations (21)-(22):", same and eq.gain[0, 0] == P)

# Generate C99 code, in memory here (model.codegen("dir", ...) writes the files).
for path, text in model.codegen(kinds=["optimal"], language="c", scalar="float").items():
    print(f"{path}: {len(text.splitlines())} lines")

# Simulate 20 runs against the truth, with a particle reference of 200 particles.
result = pfgen.simulate(model, runs=20, T=2, seed=1, reference=200, x0="prior", filters=["optimal", "ekf"])
print(result.report)
rms = {name: float(s["rms"][0]) for name, s in result.summary.items()}
print("RMS over [0, 2]:", ", ".join(f"{name} {value:.3f}" for name, value in rms.items()))
print("series:", len(result.t), "times, columns", ", ".join(list(result.series)[:4]), "...")
