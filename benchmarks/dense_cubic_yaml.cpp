// Writes the dense cubic benchmark model of size n as a pfgen model file:
// every monomial up to degree 3 in each drift component, linear multiplicative
// diffusion g = diag(c_i0 + sum_k c_ik x_k), one observation per state
// (A = B = identity, A0 = 0).
//
// The system is tests/support/dense_cubic_system.hpp's, the one bench_derive and
// the tests use: coefficients k/10 with k in [-9, 9] \ {0}, written as decimals,
// which pfgen reads as exact rationals.
//
// The model files in benchmarks/models/ are committed; regenerate them with
//   build/benchmarks/dense_cubic_yaml 4 > benchmarks/models/dense_cubic_4.yaml
//   build/benchmarks/dense_cubic_yaml 8 > benchmarks/models/dense_cubic_8.yaml
#include <cstdio>
#include <cstdlib>
#include <string>
#include <vector>

#include "support/dense_cubic_system.hpp"  // tests/support, shared with bench_derive and the tests

namespace {

std::string decimal(int tenths) {
  std::string text = tenths < 0 ? "-" : "";
  int a = std::abs(tenths);
  return text + std::to_string(a / 10) + "." + std::to_string(a % 10);
}

// "c*x1^2*x3" with the coefficient first; the constant monomial is just "c".
std::string term(int tenths, const std::vector<std::size_t>& monomial) {
  std::string text = decimal(std::abs(tenths));
  for (std::size_t k = 0; k < monomial.size();) {
    std::size_t e = 1;
    while (k + e < monomial.size() && monomial[k + e] == monomial[k]) ++e;
    text += "*x" + std::to_string(monomial[k] + 1) + (e > 1 ? "^" + std::to_string(e) : "");
    k += e;
  }
  return text;
}

std::string polynomial(const std::vector<int>& tenths, const std::vector<std::vector<std::size_t>>& monomials) {
  std::string text;
  for (std::size_t t = 0; t < tenths.size(); ++t) {
    if (t == 0) text += tenths[t] < 0 ? "-" : "";
    else text += tenths[t] < 0 ? " - " : " + ";
    text += term(tenths[t], monomials[t]);
  }
  return text;
}

}  // namespace

int main(int argc, char** argv) {
  if (argc != 2 || std::atoi(argv[1]) < 1) {
    std::fprintf(stderr, "usage: dense_cubic_yaml N\n");
    return 2;
  }
  const std::size_t n = static_cast<std::size_t>(std::atoi(argv[1]));
  const pfgen_test::DenseCubicSystem system = pfgen_test::dense_cubic_system(n);
  const std::vector<std::vector<std::size_t>>& monomials = system.monomials;
  std::vector<std::vector<std::size_t>> linear{{}};
  for (std::size_t k = 0; k < n; ++k) linear.push_back({k});

  std::vector<std::string> drift, diffusion;
  for (std::size_t i = 0; i < n; ++i) {
    drift.push_back(polynomial(system.drift_tenths[i], monomials));
    diffusion.push_back(polynomial(system.diffusion_tenths[i], linear));
  }

  auto row = [n](std::size_t i, const std::string& diagonal) {
    std::string text = "[";
    for (std::size_t k = 0; k < n; ++k) text += (k ? ", \"" : "\"") + (k == i ? diagonal : std::string("0")) + "\"";
    return text + "]";
  };
  std::printf("# Dense cubic benchmark model, n = %zu: written by benchmarks/dense_cubic_yaml.cpp, do not edit.\n", n);
  std::printf("# Every monomial up to degree 3 in each drift component (%zu terms), coefficients k/10\n",
              monomials.size());
  std::printf("# (the same as bench_derive's dense_cubic_model(%zu)); g = diag(c_i0 + sum_k c_ik x_k); A = B = I.\n",
              n);
  std::printf("name: dense_cubic_%zu\n", n);
  std::printf("states: [");
  for (std::size_t k = 0; k < n; ++k) std::printf("%sx%zu", k ? ", " : "", k + 1);
  std::printf("]\ndrift:\n");
  for (const auto& f : drift) std::printf("  - \"%s\"\n", f.c_str());
  std::printf("diffusion:\n");
  for (std::size_t i = 0; i < n; ++i) std::printf("  - %s\n", row(i, diffusion[i]).c_str());
  std::printf("observation:\n  A0: [");
  for (std::size_t k = 0; k < n; ++k) std::printf("%s\"0\"", k ? ", " : "");
  std::printf("]\n  A:\n");
  for (std::size_t i = 0; i < n; ++i) std::printf("    - %s\n", row(i, "1").c_str());
  std::printf("  B:\n");
  for (std::size_t i = 0; i < n; ++i) std::printf("    - %s\n", row(i, "1").c_str());
  return 0;
}
