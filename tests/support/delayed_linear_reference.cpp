#include "support/delayed_linear_reference.hpp"

#include <cmath>
#include <stdexcept>

#include "pfgen_runtime/random.hpp"

namespace pfgen_test {

double DelayedLinearModel::F() const { return std::exp(a * dt); }

double DelayedLinearModel::Q() const {
  // σ² ∫_0^dt e^{2as} ds; expm1 keeps it accurate for small a dt, and a = 0 is its limit.
  if (a == 0.0) return sigma * sigma * dt;
  return sigma * sigma * std::expm1(2.0 * a * dt) / (2.0 * a);
}

double DelayedLinearModel::c0() const { return rule == DelayedObservationRule::left_point ? dt : 0.5 * dt; }
double DelayedLinearModel::c1() const { return rule == DelayedObservationRule::left_point ? 0.0 : 0.5 * dt; }

AugmentedKalmanGain::AugmentedKalmanGain(const DelayedLinearModel& model)
    : model_(model), L_(model.augmented_size()), P_(L_ * L_, model.P0), predicted_(L_ * L_), gain_(L_) {
  if (!(model.dt > 0.0)) throw std::invalid_argument("delayed linear reference: dt must be positive");
  // Every entry of z is x_0 at the start (the pre-history), so P0 fills the whole matrix.
}

void AugmentedKalmanGain::advance() {
  const std::size_t L = L_, D = model_.D;
  const double F = model_.F();
  // Predict: z' = (F x_k + w_k, x_k, ..., x_{k−D}); the oldest entry x_{k−D−1} drops out.
  predicted_[0] = F * F * P_[0] + model_.Q();
  for (std::size_t j = 1; j < L; ++j) {
    predicted_[j] = F * P_[j - 1];
    predicted_[j * L] = predicted_[j];
  }
  for (std::size_t i = 1; i < L; ++i)
    for (std::size_t j = 1; j < L; ++j) predicted_[i * L + j] = P_[(i - 1) * L + (j - 1)];
  // Update with dy_k = H z' + v_k, H = c1 e_D + c0 e_{D+1}, Var v_k = dt.
  const double c0 = model_.c0(), c1 = model_.c1();
  for (std::size_t i = 0; i < L; ++i) gain_[i] = c0 * predicted_[i * L + D + 1] + c1 * predicted_[i * L + D];
  const double S = c0 * gain_[D + 1] + c1 * gain_[D] + model_.dt;
  for (std::size_t i = 0; i < L; ++i)
    for (std::size_t j = i; j < L; ++j) {
      const double value = predicted_[i * L + j] - gain_[i] * gain_[j] / S;
      P_[i * L + j] = value;
      P_[j * L + i] = value;
    }
  for (double& k : gain_) k /= S;
}

AugmentedMean::AugmentedMean(const DelayedLinearModel& model)
    : model_(model), z_(model.augmented_size(), model.m0), predicted_(model.augmented_size()) {}

void AugmentedMean::advance(const std::vector<double>& K, double dy) {
  const std::size_t L = z_.size(), D = model_.D;
  predicted_[0] = model_.F() * z_[0];
  for (std::size_t i = 1; i < L; ++i) predicted_[i] = z_[i - 1];
  const double innovation = dy - (model_.c0() * predicted_[D + 1] + model_.c1() * predicted_[D]);
  for (std::size_t i = 0; i < L; ++i) z_[i] = predicted_[i] + K[i] * innovation;
}

DelayedLinearPath simulate_delayed_linear(const DelayedLinearModel& model, std::size_t steps, std::uint64_t seed,
                                          std::uint64_t run) {
  pfgen_runtime::RandomStream initial(seed, run, pfgen_runtime::substream::initial_state);
  pfgen_runtime::RandomStream state_noise(seed, run, pfgen_runtime::substream::truth_noise);
  pfgen_runtime::RandomStream observation_noise(seed, run, pfgen_runtime::substream::observation_noise);
  DelayedLinearPath path;
  path.x.resize(steps + 1);
  path.dy.resize(steps);
  path.x[0] = model.m0 + std::sqrt(model.P0) * initial.normal();
  const double F = model.F(), sqrt_Q = std::sqrt(model.Q()), sqrt_dt = std::sqrt(model.dt);
  for (std::size_t k = 0; k < steps; ++k) path.x[k + 1] = F * path.x[k] + sqrt_Q * state_noise.normal();
  // x_j for j < 0 is x_0: index max(j, 0).
  const auto delayed = [&](std::size_t k_plus_one, std::size_t D) {
    return k_plus_one >= D ? path.x[k_plus_one - D] : path.x[0];
  };
  for (std::size_t k = 0; k < steps; ++k)
    path.dy[k] = model.c0() * delayed(k, model.D) + model.c1() * delayed(k + 1, model.D) +
                 sqrt_dt * observation_noise.normal();
  return path;
}

}  // namespace pfgen_test
