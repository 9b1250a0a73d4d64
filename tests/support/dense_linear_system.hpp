#pragma once
// The dense linear benchmark system of size n, as plain numbers: dx = A x dt + G dw,
// dy = C x dt + B dv, with a dense A, a dense constant G and p = 3 observations (B diagonal).
// For such a model pfgen's `optimal` filter is the Kalman-Bucy filter, so a hand-written
// fixed-size Eigen implementation of the same Heun step (handwritten_kalman_bucy.hpp) computes
// the same numbers; benchmarks/bench_handwritten times the two side by side and
// tests/test_handwritten_agreement.cpp checks them for n = 4. One definition for both; it depends
// on nothing but the standard library, so the benchmark's build-time model writer
// (benchmarks/dense_linear_yaml.cpp) compiles it without the test framework or GiNaC.
//
// Numbers are k/10 (exact decimals, which pfgen reads as exact rationals), from std::mt19937 seeded
// 2000 + n, drawn in this order: A's off-diagonal entries row by row (k in [-9, 9] \ {0}), G row by
// row (same range), C row by row (same range), B's diagonal (k in [5, 15]), m0 (k in [-9, 9]).
// A's diagonal is then -(1 + sum of the row's |off-diagonal|): rows diagonally dominant with a
// negative diagonal, so A is stable (Gershgorin) and 1000 steps stay bounded for every n.
// P0 = I. Changing any of this changes the published benchmark.
#include <cstddef>
#include <string>
#include <vector>

namespace pfgen_test {

struct DenseLinearSystem {
  std::size_t n = 0;
  std::size_t p = 0;
  std::vector<std::vector<int>> a_tenths;  // n x n
  std::vector<std::vector<int>> g_tenths;  // n x n, the diffusion G (W = G G^T)
  std::vector<std::vector<int>> c_tenths;  // p x n
  std::vector<int> b_tenths;               // p, B = diag(b)
  std::vector<int> m0_tenths;              // n; P0 = I
};

DenseLinearSystem dense_linear_system(std::size_t n);

// The system as a pfgen model file named dense_linear_<n> (states x1..xn).
std::string dense_linear_yaml(const DenseLinearSystem& system);

// A fixed sequence of `steps` observation increments dy (p each, flattened), from an Euler-Maruyama
// path of the system itself started at m0 with step dt, from std::mt19937 seeded `seed`: the
// filter inputs of the agreement check and the benchmark, realistic in size.
std::vector<double> dense_linear_increments(const DenseLinearSystem& system, std::size_t steps, double dt,
                                            unsigned seed);

}  // namespace pfgen_test
