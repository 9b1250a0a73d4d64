#include "support/dense_cubic_system.hpp"

#include <random>

namespace pfgen_test {
namespace {

// k in [-9, 9] \ {0}: the sign first, then |k|.
int random_tenths(std::mt19937& rng) {
  std::uniform_int_distribution<int> k(1, 9);
  std::bernoulli_distribution negative(0.5);
  return negative(rng) ? -k(rng) : k(rng);
}

void monomials_up_to(std::size_t n, int degree, std::size_t first, const std::vector<std::size_t>& current,
                     std::vector<std::vector<std::size_t>>& out) {
  out.push_back(current);
  if (degree == 0) return;
  for (std::size_t k = first; k < n; ++k) {
    std::vector<std::size_t> next = current;
    next.push_back(k);
    monomials_up_to(n, degree - 1, k, next, out);
  }
}

}  // namespace

DenseCubicSystem dense_cubic_system(std::size_t n) {
  DenseCubicSystem system;
  system.n = n;
  monomials_up_to(n, 3, 0, {}, system.monomials);
  std::mt19937 rng(static_cast<unsigned>(1000 + n));
  for (std::size_t i = 0; i < n; ++i) {
    std::vector<int> f, g;
    for (std::size_t t = 0; t < system.monomials.size(); ++t) f.push_back(random_tenths(rng));
    for (std::size_t k = 0; k <= n; ++k) g.push_back(random_tenths(rng));
    system.drift_tenths.push_back(f);
    system.diffusion_tenths.push_back(g);
  }
  return system;
}

}  // namespace pfgen_test
