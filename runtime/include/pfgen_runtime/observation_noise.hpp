#pragma once
// The noise axis of an observation (observation.hpp composes it): B(t) (p x r) of continuous
// increments' B dW2, or Uv(t) (p x q) of samples' Uv v.
#include <cstddef>
#include <functional>

#include <Eigen/Core>

namespace pfgen_runtime {

// The noise factor of an observation at time t: constant, or from a callback (a pure function of
// t, evaluated once per t).
class ObservationNoise {
 public:
  // Fills the factor (p x r, arriving sized) at t.
  using Factor = std::function<void(double t, Eigen::MatrixXd& factor)>;
  // std::invalid_argument unless p, r >= 1 (and the callback is set).
  explicit ObservationNoise(Eigen::MatrixXd factor);
  ObservationNoise(std::size_t p, std::size_t r, Factor factor);
  std::size_t p() const { return static_cast<std::size_t>(factor_.rows()); }
  std::size_t r() const { return static_cast<std::size_t>(factor_.cols()); }
  const Eigen::MatrixXd& at(double t);

 private:
  Factor fill_;  // empty for a constant factor
  Eigen::MatrixXd factor_;
  double evaluated_t_ = 0;
  bool evaluated_ = false;
};

}  // namespace pfgen_runtime
