#include "pfgen_runtime/observation_timing.hpp"

#include <cmath>
#include <cstdio>
#include <optional>
#include <stdexcept>

#include "pfgen_runtime/lane_pack.hpp"
#include "pfgen_support/whole_steps.hpp"

namespace pfgen_runtime {

namespace {

void check_delay(double h) {
  if (!(h >= 0) || !std::isfinite(h)) throw std::invalid_argument("observation: the delay h must be finite and >= 0");
}

}  // namespace

void Increments::set_delay(double h) {
  check_delay(h);
  delay_ = h;
}

std::size_t Increments::delay_steps(double dt) const {
  if (delay_ == 0) return 0;
  const double ratio = delay_ / dt, whole = std::round(ratio);
  char text[240];
  if (!(whole <= static_cast<double>(kMaxDelaySteps))) {
    std::snprintf(text, sizeof text, "the observation delay h = %.17g is more than %zu steps dt = %.17g (h/dt = %.17g)",
                  delay_, kMaxDelaySteps, dt, ratio);
    throw std::invalid_argument(text);
  }
  const std::optional<double> steps = pfgen_support::whole_steps(delay_, dt);
  if (!steps || *steps < 1) {
    std::snprintf(text, sizeof text, "the observation delay h = %.17g is not a whole number of steps dt = %.17g (h/dt = %.17g)",
                  delay_, dt, ratio);
    throw std::invalid_argument(text);
  }
  return static_cast<std::size_t>(*steps);
}

std::size_t Increments::steps_per_sample(double) const {
  throw std::invalid_argument("steps_per_sample: continuous increments have no samples");
}

// The rate's trapezoid, then + B(t)_ij dW2_j in j's order: B at the left end keeps the noise term
// Ito. Plain loops: p and r are small, where Eigen's dynamic-size products cost more than the
// arithmetic.
void Increments::increment(ObservationRate& rate, ObservationNoise& noise, double t, double dt, const double* x_start,
                           const double* x_end, const double* dW2, double* dy) const {
  rate.trapezoid(t, dt, x_start, x_end, dy);
  const Eigen::MatrixXd& B = noise.at(t);
  const Eigen::Index p = B.rows(), r = B.cols();
  for (Eigen::Index i = 0; i < p; ++i) {
    double value = dy[i];
    for (Eigen::Index j = 0; j < r; ++j) value += B(i, j) * dW2[j];
    dy[i] = value;
  }
}

void Increments::increment_lanes(ObservationRate& rate, ObservationNoise& noise, double t, double dt,
                                 std::size_t count, const double* x_start, const double* x_end, const double* dW2,
                                 double* dy) const {
  namespace lp = lane_pack;
  rate.trapezoid_lanes(t, dt, count, x_start, x_end, dy);
  const Eigen::MatrixXd& B = noise.at(t);
  const std::size_t p = static_cast<std::size_t>(B.rows()), r = static_cast<std::size_t>(B.cols());
  for (std::size_t i = 0; i < p; ++i)
    lp::for_lanes(count, [&](std::size_t k, auto lanes) {
      auto increment = lp::load(dy + i * count + k, lanes);
      for (std::size_t j = 0; j < r; ++j)
        increment = increment + lp::splat(B(static_cast<Eigen::Index>(i), static_cast<Eigen::Index>(j)), lanes) *
                                    lp::load(dW2 + j * count + k, lanes);
      lp::store(dy + i * count + k, increment, lanes);
    });
}

Samples::Samples(double period) : period_(period) {
  if (!(period > 0) || !std::isfinite(period))
    throw std::invalid_argument("observation: the sampling period must be finite and > 0");
}

void Samples::set_delay(double h) {
  check_delay(h);
  if (h > 0) throw std::invalid_argument("observation: a delay needs continuous observations, not samples");
}

std::size_t Samples::steps_per_sample(double dt) const {
  const std::optional<double> whole = pfgen_support::whole_steps(period_, dt);
  // A precondition of the API: `pfgen simulate` refuses such a dt before, naming the model's
  // period and the option to change, so this short message is for library users only.
  if (!whole || *whole < 1) {
    char text[120];
    std::snprintf(text, sizeof text, "steps_per_sample: period / dt = %.17g is not a whole number of steps >= 1",
                  period_ / dt);
    throw std::invalid_argument(text);
  }
  return static_cast<std::size_t>(*whole);
}

}  // namespace pfgen_runtime
