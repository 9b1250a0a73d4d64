#pragma once
// The exact optimal filter of a time-discretised scalar linear model with a delayed observation:
// the reference against which the delayed filter kinds are measured (docs/reproductions/basin-rodriguez-gonzalez-martinez-zuniga-2004.md).
//
// The model, on the grid t_k = k dt with the delay h = D dt:
//   x_{k+1} = F x_k + w_k,        F = e^{a dt},  w_k ~ N(0, Q),  Q = σ² (e^{2a dt} − 1)/(2a)
//                                 (σ² dt at a = 0): dx = a x dt + σ dW1 sampled exactly;
//   dy_k = y(t_{k+1}) − y(t_k) = c0 x_{k−D} + c1 x_{k+1−D} + v_k,   v_k ~ N(0, dt),
// with (c0, c1) = (dt, 0) for the left-point rule and (dt/2, dt/2) for the trapezoid that the
// runtime's truth uses for ∫ x(s − h) ds; x_j = x_0 for j < 0 (the pre-history of docs/theory.md
// §2.6) and x_0 ~ N(m0, P0).
//
// Every dy_k is linear in the augmented state z = (x_{k+1}, x_k, ..., x_{k−D}) with Gaussian
// noise, so the Kalman filter on z is the conditional mean given dy_0..dy_k exactly, not an
// approximation: the reference the continuous-time delay filters approach as dt → 0 only if they
// are optimal. Its covariance (and so its gain) does not depend on the data, so one
// AugmentedKalmanGain serves any number of runs; AugmentedKalman pairs it with one run's mean.
#include <cstddef>
#include <cstdint>
#include <vector>

namespace pfgen_test {

enum class DelayedObservationRule { left_point, trapezoid };

struct DelayedLinearModel {
  double a = -1.0, sigma = 1.0;  // dx = a x dt + sigma dW1
  double dt = 0.01;
  std::size_t D = 0;  // delay steps: h = D dt
  double m0 = 0.0, P0 = 1.0;
  DelayedObservationRule rule = DelayedObservationRule::trapezoid;

  double F() const;  // e^{a dt}
  double Q() const;  // the exact variance of w_k
  double c0() const;  // weight of x_{k−D} in dy_k
  double c1() const;  // weight of x_{k+1−D} in dy_k
  std::size_t augmented_size() const { return D + 2; }
};

// The covariance recursion of the augmented state: predict (shift in x_{k+1} = F x_k + w_k,
// drop the oldest entry), then update with the scalar dy_k.
class AugmentedKalmanGain {
 public:
  explicit AugmentedKalmanGain(const DelayedLinearModel& model);
  // From step k to k + 1: after it, gain() is K_k (for the predicted state) and variance() is
  // Var[x_{k+1} | dy_0..dy_k].
  void advance();
  const std::vector<double>& gain() const { return gain_; }
  double variance() const { return P_[0]; }
  // The full covariance, row-major L × L with L = model.augmented_size() (for the tests).
  const std::vector<double>& covariance() const { return P_; }
  const DelayedLinearModel& model() const { return model_; }

 private:
  DelayedLinearModel model_;
  std::size_t L_;
  std::vector<double> P_, predicted_, gain_;
};

// One run's augmented mean, advanced with the gains of an AugmentedKalmanGain that has just
// advanced to the same step (so many runs share one covariance recursion).
class AugmentedMean {
 public:
  explicit AugmentedMean(const DelayedLinearModel& model);
  void advance(const AugmentedKalmanGain& gain, double dy) { advance(gain.gain(), dy); }
  // The same with a gain K_k kept from an earlier AugmentedKalmanGain::advance().
  void advance(const std::vector<double>& gain, double dy);
  double mean() const { return z_[0]; }  // E[x_{k+1} | dy_0..dy_k]

 private:
  DelayedLinearModel model_;
  std::vector<double> z_, predicted_;
};

// Both together, for a single run.
class AugmentedKalman {
 public:
  explicit AugmentedKalman(const DelayedLinearModel& model) : gain_(model), mean_(model) {}
  void step(double dy) {
    gain_.advance();
    mean_.advance(gain_, dy);
  }
  double mean() const { return mean_.mean(); }
  double variance() const { return gain_.variance(); }
  const AugmentedKalmanGain& gain() const { return gain_; }

 private:
  AugmentedKalmanGain gain_;
  AugmentedMean mean_;
};

// One truth of the model above and its observation increments: x[k] = x_k for k = 0..steps and
// dy[k] = dy_k for k = 0..steps−1, drawn from pfgen_runtime::RandomStream(seed, run, ·)
// (x_0 from the initial-state substream, w from the truth's, v from the observation's).
struct DelayedLinearPath {
  std::vector<double> x, dy;
};
DelayedLinearPath simulate_delayed_linear(const DelayedLinearModel& model, std::size_t steps, std::uint64_t seed,
                                          std::uint64_t run);

}  // namespace pfgen_test
