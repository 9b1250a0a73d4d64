#pragma once
// The scalar linear test system of the runtime tests, whose optimal filter is Kalman-Bucy:
//   dx = -a x dt + s dW1,   dy = x dt + r dW2,
// with the stationary Riccati variance P_inf as the reference for filter errors.
#include <cmath>

#include <Eigen/Core>

#include "pfgen_runtime/observation.hpp"
#include "pfgen_runtime/sde_system.hpp"

namespace pfgen_test {

struct ScalarLinear {
  double a = 1.0, s = 0.8, r = 0.5, m0 = 0.0, P0 = 1.0;
  // The positive root of -2 a P + s^2 - P^2 / r^2 = 0.
  double P_inf() const { return r * r * (-a + std::sqrt(a * a + s * s / (r * r))); }
};

inline pfgen_runtime::SdeSystem scalar_linear_system(const ScalarLinear& model) {
  pfgen_runtime::SdeSystem system;
  system.n = 1;
  system.q = 1;
  system.drift = [a = model.a](double, const double* x, double* f) { f[0] = -a * x[0]; };
  system.diffusion = [s = model.s](double, const double*, double* g) { g[0] = s; };
  return system;
}

// dy = x dt + r dW2.
inline pfgen_runtime::Observation scalar_observation(double r) {
  return pfgen_runtime::Observation(Eigen::VectorXd::Zero(1), Eigen::MatrixXd::Ones(1, 1),
                                          Eigen::MatrixXd::Constant(1, 1, r));
}

}  // namespace pfgen_test
