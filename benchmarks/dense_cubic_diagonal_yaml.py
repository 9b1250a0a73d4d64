#!/usr/bin/env python3
"""Writes a second dense cubic model of size n, unlike dense_cubic_yaml's in its numbers and its
noise: every monomial of degree <= 3 in each drift entry with a coefficient drawn from the
two-decimal numbers in [-0.99, 0.99] without 0 (seeded, so the file is the same on every run),
diagonal diffusion g_ii = a_i + b_i x_i, every state observed (A = B = I, A0 = 0).

    benchmarks/dense_cubic_diagonal_yaml.py N [SEED] > model.yaml

dense_cubic_yaml's coefficients are k/10, 18 values, so products such as 0.3 * P_12 recur across
the equations and the graph shares them; here they rarely do, which is the harder case for code
generation (docs/benchmarks.md, "Code generation at scale").
"""
import itertools
import random
import sys


def main():
    if len(sys.argv) not in (2, 3) or not sys.argv[1].isdigit() or int(sys.argv[1]) < 1:
        sys.exit("usage: dense_cubic_diagonal_yaml.py N [SEED]")
    n = int(sys.argv[1])
    rng = random.Random(int(sys.argv[2]) if len(sys.argv) == 3 else 7)
    xs = [f"x{i + 1}" for i in range(n)]
    monomials = [()]
    for degree in (1, 2, 3):
        monomials += list(itertools.combinations_with_replacement(range(n), degree))

    def monomial(m):
        return "*".join(xs[k] + (f"^{m.count(k)}" if m.count(k) > 1 else "") for k in sorted(set(m)))

    def coefficient():
        while True:
            c = rng.randint(-99, 99)
            if c:
                return c

    def polynomial(terms):
        text = ""
        for t, (c, m) in enumerate(terms):
            sign = ("-" if c < 0 else "") if t == 0 else (" - " if c < 0 else " + ")
            text += sign + f"{abs(c) / 100:.2f}" + ("*" + monomial(m) if m else "")
        return text

    def row(i, entry):
        return "[" + ", ".join(f'"{entry}"' if k == i else '"0"' for k in range(n)) + "]"

    print(f"# Dense cubic model, n = {n}, two-decimal coefficients, g_ii = a_i + b_i x_i: "
          "written by benchmarks/dense_cubic_diagonal_yaml.py, do not edit.")
    print(f"name: dense_cubic_diagonal_{n}")
    print("states: [" + ", ".join(xs) + "]")
    print("drift:")
    for _ in range(n):
        print(f'  - "{polynomial([(coefficient(), m) for m in monomials])}"')
    print("diffusion:")
    for i in range(n):
        print("  - " + row(i, polynomial([(coefficient(), ()), (coefficient(), (i,))])))
    print("observation:\n  A0: [" + ", ".join(['"0"'] * n) + "]")
    for name in ("A", "B"):
        print(f"  {name}:")
        for i in range(n):
            print("    - " + row(i, "1"))


if __name__ == "__main__":
    main()
