#pragma once
// The dense cubic test and benchmark system of size n, as plain numbers: every monomial up to
// degree 3 in each drift component, linear multiplicative diffusion g = diag(c_i0 + sum_k c_ik
// x_k), one observation per state (A = B = I, A0 = 0). One definition for tests/test_codegen_ops,
// benchmarks/bench_derive (through dense_cubic_model.hpp) and benchmarks/dense_cubic_yaml (which
// writes benchmarks/models/dense_cubic_{4,8}.yaml); it depends on nothing but the standard
// library, so the benchmarks compile it without the test framework or GiNaC.
//
// Coefficients are k/10 with k in [-9, 9] \ {0}, from std::mt19937 seeded 1000 + n, drawn per
// component i: the drift's coefficients in monomial order, then c_i0, c_i1 .. c_in. Monomials
// are in depth-first order 1, x1, x1^2, x1^3, x1^2 x2, ..., x1^2 xn, x1 x2, x1 x2^2, ...
// Changing any of this changes the committed benchmark models and the published benchmark.
#include <cstddef>
#include <vector>

namespace pfgen_test {

struct DenseCubicSystem {
  std::size_t n = 0;
  // Each drift monomial as its state indices (0-based, non-decreasing, with repetition; {} is 1).
  std::vector<std::vector<std::size_t>> monomials;
  std::vector<std::vector<int>> drift_tenths;      // [i][t]: coefficient of monomials[t] in f_i, times 10
  std::vector<std::vector<int>> diffusion_tenths;  // [i][0]: c_i0; [i][k + 1]: c_ik; times 10
};

DenseCubicSystem dense_cubic_system(std::size_t n);

}  // namespace pfgen_test
