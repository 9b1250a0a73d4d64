// Strong convergence order of the truth schemes against SDEs with known solutions:
// geometric Brownian motion dx = lambda x dt + mu x dW (x(T) = x0 exp((lambda - mu^2/2) T + mu W(T))),
// and a two-state linear system with two commuting, non-diagonal noise matrices.
// The strong error E|X_N - x(T)| is measured at several dt on the same Brownian paths (coarse
// increments are sums of the finest), and the order is the least-squares slope of
// log(error) against log(dt).
#include <catch2/catch.hpp>

#include <algorithm>
#include <cmath>
#include <functional>
#include <stdexcept>
#include <vector>

#include <Eigen/LU>

#include "pfgen_runtime/random.hpp"
#include "pfgen_runtime/schemes.hpp"

using namespace pfgen_runtime;

namespace {

double slope(const std::vector<double>& h, const std::vector<double>& e) {
  double sx = 0, sy = 0, sxx = 0, sxy = 0;
  const double k = static_cast<double>(h.size());
  for (std::size_t i = 0; i < h.size(); ++i) {
    const double x = std::log(h[i]), y = std::log(e[i]);
    sx += x;
    sy += y;
    sxx += x * x;
    sxy += x * y;
  }
  return (k * sxy - sx * sy) / (k * sxx - sx * sx);
}

using ExactSolution = std::function<Eigen::VectorXd(const Eigen::VectorXd& x0, const Eigen::VectorXd& W)>;

struct Convergence {
  std::vector<double> dt, error;
  double order = 0;
};

// Mean Euclidean error at T over `paths` Brownian paths, at dt = T / 2^levels[i].
Convergence strong_errors(SchemeKind kind, const SdeSystem& system, const ExactSolution& exact,
                          const Eigen::VectorXd& x0, double T, const std::vector<int>& levels, int paths,
                          std::uint64_t seed) {
  const int finest = *std::max_element(levels.begin(), levels.end());
  const long fine_steps = 1L << finest;
  const double fine_dt = T / static_cast<double>(fine_steps);
  const auto q = static_cast<Eigen::Index>(system.q);
  auto scheme = make_scheme(kind, system);
  Convergence result;
  result.error.assign(levels.size(), 0.0);
  Eigen::MatrixXd increments(q, fine_steps);
  Eigen::VectorXd dW(q), x(x0.size());
  for (int path = 0; path < paths; ++path) {
    RandomStream stream(seed, static_cast<std::uint64_t>(path));
    for (long k = 0; k < fine_steps; ++k) {
      stream.wiener_increment(fine_dt, dW);
      increments.col(k) = dW;
    }
    const Eigen::VectorXd reference = exact(x0, increments.rowwise().sum());
    for (std::size_t i = 0; i < levels.size(); ++i) {
      const long steps = 1L << levels[i], stride = fine_steps / steps;
      const double dt = T / static_cast<double>(steps);
      x = x0;
      for (long k = 0; k < steps; ++k) {
        dW = increments.middleCols(k * stride, stride).rowwise().sum();
        scheme->step(static_cast<double>(k) * dt, x, dt, dW);
      }
      result.error[i] += (x - reference).norm() / paths;
    }
  }
  for (int level : levels) result.dt.push_back(T / static_cast<double>(1L << level));
  result.order = slope(result.dt, result.error);
  return result;
}

// Geometric Brownian motion with lambda = 2, mu = 1 (Higham 2001's example), x0 = 1, T = 1.
constexpr double lambda = 2.0, mu = 1.0;

SdeSystem gbm() {
  SdeSystem system;
  system.n = 1;
  system.q = 1;
  system.drift = [](double, const double* x, double* f) { f[0] = lambda * x[0]; };
  system.diffusion = [](double, const double* x, double* g) { g[0] = mu * x[0]; };
  system.diffusion_jacobian = [](double, const double*, double* dg) { dg[0] = mu; };
  return system;
}

Eigen::VectorXd gbm_exact(const Eigen::VectorXd& x0, const Eigen::VectorXd& W) {
  return x0 * std::exp((lambda - 0.5 * mu * mu) * 1.0 + mu * W[0]);
}

// dx = A x dt + B1 x dW1 + B2 x dW2 with A, B1, B2 diagonal in the basis V (so they commute,
// and the noise is commutative though not diagonal): x(T) = V exp(D) V^-1 x0, where
// D_i = (a_i - (b1_i^2 + b2_i^2)/2) T + b1_i W1(T) + b2_i W2(T).
const Eigen::Matrix2d& basis() {
  static const Eigen::Matrix2d V = (Eigen::Matrix2d() << 2, 1, 1, 1).finished();
  return V;
}
const Eigen::Vector2d a(0.5, -0.3), b1(0.6, 0.2), b2(-0.3, 0.5);
Eigen::Matrix2d in_basis(const Eigen::Vector2d& d) { return basis() * d.asDiagonal() * basis().inverse(); }

SdeSystem commuting_linear() {
  SdeSystem system;
  system.n = 2;
  system.q = 2;
  const Eigen::Matrix2d A = in_basis(a), B1 = in_basis(b1), B2 = in_basis(b2);
  system.drift = [A](double, const double* x, double* f) {
    Eigen::Map<Eigen::Vector2d> out(f);
    out = A * Eigen::Map<const Eigen::Vector2d>(x);
  };
  system.diffusion = [B1, B2](double, const double* x, double* g) {
    const Eigen::Vector2d c1 = B1 * Eigen::Map<const Eigen::Vector2d>(x), c2 = B2 * Eigen::Map<const Eigen::Vector2d>(x);
    g[0] = c1[0];  // g is 2 x 2 row-major: g(i, j) = (B_j x)_i
    g[1] = c2[0];
    g[2] = c1[1];
    g[3] = c2[1];
  };
  system.diffusion_jacobian = [B1, B2](double, const double*, double* dg) {
    for (int i = 0; i < 2; ++i)
      for (int l = 0; l < 2; ++l) {
        dg[(i * 2 + 0) * 2 + l] = B1(i, l);
        dg[(i * 2 + 1) * 2 + l] = B2(i, l);
      }
  };
  return system;
}

Eigen::VectorXd commuting_exact(const Eigen::VectorXd& x0, const Eigen::VectorXd& W) {
  Eigen::Vector2d d;
  for (int i = 0; i < 2; ++i)
    d[i] = std::exp(a[i] - 0.5 * (b1[i] * b1[i] + b2[i] * b2[i]) + b1[i] * W[0] + b2[i] * W[1]);
  return basis() * d.asDiagonal() * basis().inverse() * x0;
}

}  // namespace

TEST_CASE("runtime: strong orders on geometric Brownian motion", "[runtime][convergence][statistical]") {
  const std::vector<int> levels = {5, 6, 7, 8, 9, 10};  // dt = 2^-5 ... 2^-10
  const Eigen::VectorXd x0 = Eigen::VectorXd::Constant(1, 1.0);
  const int paths = 4000;

  struct Expectation {
    SchemeKind kind;
    double low, high;
  };
  // Bands: 0.5 +- 0.1 and 1 +- 0.15, a few standard errors of the fitted slope at 4000 paths.
  for (const Expectation& expected : {Expectation{SchemeKind::euler_maruyama, 0.4, 0.6},
                                      Expectation{SchemeKind::tamed_euler, 0.4, 0.6},
                                      Expectation{SchemeKind::milstein, 0.85, 1.15},
                                      Expectation{SchemeKind::derivative_free_milstein, 0.85, 1.15}}) {
    const Convergence c = strong_errors(expected.kind, gbm(), gbm_exact, x0, 1.0, levels, paths, 11);
    INFO(to_string(expected.kind) << ": errors " << c.error[0] << " ... " << c.error.back() << ", order " << c.order);
    CHECK(c.order > expected.low);
    CHECK(c.order < expected.high);
    // Errors fall monotonically as dt halves.
    for (std::size_t i = 1; i < c.error.size(); ++i) CHECK(c.error[i] < c.error[i - 1]);
  }
}

TEST_CASE("runtime: strong order 1 with commutative non-diagonal noise", "[runtime][convergence][statistical]") {
  const SdeSystem system = commuting_linear();
  Eigen::VectorXd x0(2);
  x0 << 1.0, 0.5;
  // The noise is commutative, and the check tells a non-commutative one apart.
  CHECK(commutativity_defect(system, 0.0, x0) < 1e-12);
  SdeSystem skew = system;
  skew.diffusion = [](double, const double* x, double* g) {
    g[0] = x[1];  // B1 = [[0,1],[0,0]], B2 = [[0,0],[1,0]] do not commute
    g[1] = 0;
    g[2] = 0;
    g[3] = x[0];
  };
  skew.diffusion_jacobian = [](double, const double*, double* dg) {
    const double values[] = {0, 1, 0, 0, 0, 0, 1, 0};
    std::copy(std::begin(values), std::end(values), dg);
  };
  CHECK(commutativity_defect(skew, 0.0, x0) > 0.1);

  const std::vector<int> levels = {4, 5, 6, 7, 8, 9};
  for (SchemeKind kind : {SchemeKind::milstein, SchemeKind::derivative_free_milstein, SchemeKind::euler_maruyama}) {
    const Convergence c = strong_errors(kind, system, commuting_exact, x0, 1.0, levels, 2000, 12);
    INFO(to_string(kind) << ": errors " << c.error[0] << " ... " << c.error.back() << ", order " << c.order);
    if (kind == SchemeKind::euler_maruyama) {
      CHECK(c.order > 0.4);
      CHECK(c.order < 0.6);
    } else {
      CHECK(c.order > 0.85);
      CHECK(c.order < 1.15);
    }
  }
}

TEST_CASE("runtime: adaptive Euler's Brownian-bridge substeps follow the grid's Brownian path", "[runtime][convergence][statistical]") {
  // On a coarse grid (dt = 1/4) the adaptive scheme substeps to h ~ tolerance^2; its error against
  // the exact solution on the *grid's* W(T) must fall like the tolerance (strong order 1/2 in h).
  // A bridge that did not reproduce the grid increments would leave an O(1) error.
  const Eigen::VectorXd x0 = Eigen::VectorXd::Constant(1, 1.0);
  const double T = 1.0, dt = 0.25;
  const int paths = 2000;
  const std::vector<double> tolerances = {0.2, 0.1, 0.05, 0.025};
  std::vector<double> errors;
  for (double tolerance : tolerances) {
    AdaptiveEuler scheme(gbm(), AdaptiveEuler::Options{tolerance, 1.0, 40});
    double error = 0;
    Eigen::VectorXd dW(1), x(1);
    for (int path = 0; path < paths; ++path) {
      RandomStream stream(13, static_cast<std::uint64_t>(path));
      scheme.start_run(13, static_cast<std::uint64_t>(path));
      x = x0;
      double W = 0;
      for (int k = 0; k * dt < T; ++k) {
        stream.wiener_increment(dt, dW);
        W += dW[0];
        scheme.step(k * dt, x, dt, dW);
      }
      error += std::abs(x[0] - gbm_exact(x0, Eigen::VectorXd::Constant(1, W))[0]) / paths;
    }
    errors.push_back(error);
  }
  const double order = slope(tolerances, errors);
  INFO("errors " << errors[0] << " " << errors[1] << " " << errors[2] << " " << errors[3] << ", order in tolerance "
                 << order);
  CHECK(order > 0.8);
  CHECK(order < 1.2);
  CHECK(errors.back() < 0.1 * gbm_exact(x0, Eigen::VectorXd::Zero(1))[0]);
}

TEST_CASE("runtime: scheme names and preconditions and g from a covariance G", "[runtime][convergence][unit]") {
  for (SchemeKind kind : {SchemeKind::euler_maruyama, SchemeKind::milstein, SchemeKind::derivative_free_milstein,
                          SchemeKind::tamed_euler, SchemeKind::adaptive_euler}) {
    CHECK(scheme_kind_from_string(to_string(kind)) == kind);
    CHECK(make_scheme(kind, gbm())->name() == to_string(kind));
  }
  CHECK_THROWS_AS(scheme_kind_from_string("runge-kutta"), std::invalid_argument);
  SdeSystem no_jacobian = gbm();
  no_jacobian.diffusion_jacobian = nullptr;
  CHECK_THROWS_AS(Milstein(no_jacobian), std::invalid_argument);
  SdeSystem no_diffusion = gbm();
  no_diffusion.diffusion = nullptr;
  CHECK_THROWS_AS(EulerMaruyama(no_diffusion), std::invalid_argument);
  EulerMaruyama scheme(gbm());
  Eigen::VectorXd x = Eigen::VectorXd::Ones(1), wrong_dW = Eigen::VectorXd::Zero(2);
  CHECK_THROWS_AS(scheme.step(0.0, x, 0.1, wrong_dW), std::invalid_argument);

  // A model that gives only G = g g^T (here G(x) = x1^2 [[2, 1], [1, 2]] + I): the symmetric
  // square root reproduces G.
  const auto g = diffusion_from_covariance(2, [](double, const double* x, double* G) {
    const double s = x[0] * x[0];
    G[0] = 2 * s + 1;
    G[1] = s;
    G[2] = s;
    G[3] = 2 * s + 1;
  });
  const double point[] = {1.5, -0.3};
  Eigen::Matrix<double, 2, 2, Eigen::RowMajor> root;
  g(0.0, point, root.data());
  Eigen::Matrix2d expected;
  expected << 2 * 2.25 + 1, 2.25, 2.25, 2 * 2.25 + 1;
  CHECK((root * root.transpose() - expected).norm() < 1e-12);
  CHECK((root - root.transpose()).norm() < 1e-12);
}
