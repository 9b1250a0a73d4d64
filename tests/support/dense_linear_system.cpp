#include "support/dense_linear_system.hpp"

#include <cmath>
#include <cstdlib>
#include <random>

namespace pfgen_test {
namespace {

// k in [-9, 9] \ {0}: the sign first, then |k| (as dense_cubic_system).
int random_tenths(std::mt19937& rng) {
  std::uniform_int_distribution<int> k(1, 9);
  std::bernoulli_distribution negative(0.5);
  return negative(rng) ? -k(rng) : k(rng);
}

std::string decimal(int tenths) {
  std::string text = tenths < 0 ? "-" : "";
  int a = std::abs(tenths);
  return text + std::to_string(a / 10) + "." + std::to_string(a % 10);
}

std::string row(const std::vector<int>& tenths) {
  std::string text = "[";
  for (std::size_t k = 0; k < tenths.size(); ++k) text += (k ? ", " : "") + decimal(tenths[k]);
  return text + "]";
}

std::string matrix(const std::vector<std::vector<int>>& rows, const std::string& indent) {
  std::string text;
  for (const auto& r : rows) text += indent + "- " + row(r) + "\n";
  return text;
}

}  // namespace

DenseLinearSystem dense_linear_system(std::size_t n) {
  DenseLinearSystem s;
  s.n = n;
  s.p = 3;
  std::mt19937 rng(static_cast<unsigned>(2000 + n));
  s.a_tenths.assign(n, std::vector<int>(n, 0));
  for (std::size_t i = 0; i < n; ++i) {
    int off_diagonal = 0;
    for (std::size_t j = 0; j < n; ++j)
      if (j != i) {
        s.a_tenths[i][j] = random_tenths(rng);
        off_diagonal += std::abs(s.a_tenths[i][j]);
      }
    s.a_tenths[i][i] = -(10 + off_diagonal);
  }
  s.g_tenths.assign(n, std::vector<int>(n, 0));
  for (auto& r : s.g_tenths)
    for (int& v : r) v = random_tenths(rng);
  s.c_tenths.assign(s.p, std::vector<int>(n, 0));
  for (auto& r : s.c_tenths)
    for (int& v : r) v = random_tenths(rng);
  std::uniform_int_distribution<int> b(5, 15), m0(-9, 9);
  for (std::size_t r = 0; r < s.p; ++r) s.b_tenths.push_back(b(rng));
  for (std::size_t i = 0; i < n; ++i) s.m0_tenths.push_back(m0(rng));
  return s;
}

std::string dense_linear_yaml(const DenseLinearSystem& s) {
  const std::string n = std::to_string(s.n);
  std::string text = "# Dense linear benchmark model, n = " + n +
                     ": written by tests/support/dense_linear_system.cpp, do not edit.\n"
                     "# dx = A x dt + G dw, dy = C x dt + B dv; A dense and stable, G dense and constant.\n"
                     "name: dense_linear_" + n + "\nstates: [";
  for (std::size_t i = 0; i < s.n; ++i) text += (i ? ", x" : "x") + std::to_string(i + 1);
  text += "]\ndrift:\n";
  for (std::size_t i = 0; i < s.n; ++i) {
    std::string f;
    for (std::size_t j = 0; j < s.n; ++j) {
      const int a = s.a_tenths[i][j];
      f += (j == 0 ? (a < 0 ? "-" : "") : (a < 0 ? " - " : " + ")) + decimal(std::abs(a)) + "*x" + std::to_string(j + 1);
    }
    text += "  - \"" + f + "\"\n";
  }
  text += "diffusion:\n" + matrix(s.g_tenths, "  ");
  std::vector<std::vector<int>> b(s.p, std::vector<int>(s.p, 0));
  for (std::size_t r = 0; r < s.p; ++r) b[r][r] = s.b_tenths[r];
  text += "observation:\n  A0: " + row(std::vector<int>(s.p, 0)) + "\n  A:\n" + matrix(s.c_tenths, "    ") +
          "  B:\n" + matrix(b, "    ");
  std::vector<std::vector<int>> identity(s.n, std::vector<int>(s.n, 0));
  for (std::size_t i = 0; i < s.n; ++i) identity[i][i] = 10;
  text += "initial:\n  m0: " + row(s.m0_tenths) + "\n  P0:\n" + matrix(identity, "    ");
  return text;
}

std::vector<double> dense_linear_increments(const DenseLinearSystem& s, std::size_t steps, double dt, unsigned seed) {
  std::mt19937 rng(seed);
  std::normal_distribution<double> normal(0.0, 1.0);
  std::vector<double> x(s.n), w(s.n), next(s.n), dy;
  dy.reserve(steps * s.p);
  for (std::size_t i = 0; i < s.n; ++i) x[i] = s.m0_tenths[i] / 10.0;
  const double root_dt = std::sqrt(dt);
  for (std::size_t k = 0; k < steps; ++k) {
    for (std::size_t r = 0; r < s.p; ++r) {
      double cx = 0;
      for (std::size_t j = 0; j < s.n; ++j) cx += s.c_tenths[r][j] / 10.0 * x[j];
      dy.push_back(cx * dt + s.b_tenths[r] / 10.0 * root_dt * normal(rng));
    }
    for (double& v : w) v = normal(rng);
    for (std::size_t i = 0; i < s.n; ++i) {
      double drift = 0, noise = 0;
      for (std::size_t j = 0; j < s.n; ++j) {
        drift += s.a_tenths[i][j] / 10.0 * x[j];
        noise += s.g_tenths[i][j] / 10.0 * w[j];
      }
      next[i] = x[i] + drift * dt + noise * root_dt;
    }
    x.swap(next);
  }
  return dy;
}

}  // namespace pfgen_test
