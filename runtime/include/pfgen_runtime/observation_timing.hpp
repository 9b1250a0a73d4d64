#pragma once
// The timing axis of an observation (observation.hpp composes it with a rate and a noise factor):
// when the truth is observed. Two implementations:
// - Increments: continuously, dy over each step [t, t + dt] of the truth's grid,
//   dy = h(t, x(t - delay)) dt + B(t) dW2, made inside the truth's loop from its dW2 (docs/theory.md
//   §2.6 for the delay);
// - Samples: at t_k = t0 + k period, y_k = h(t_k, x(t_k)) + Uv(t_k) v_k, drawn after the truth
//   (draw_samples; docs/theory.md §2.5).
// Each answers for itself what the other has not (a sample has no increment, increments no
// period) instead of its callers asking which it is.
#include <cstddef>
#include <memory>

#include "pfgen_runtime/observation_noise.hpp"
#include "pfgen_runtime/observation_rate.hpp"

namespace pfgen_runtime {

class ObservationTiming {
 public:
  virtual ~ObservationTiming() = default;
  virtual std::unique_ptr<ObservationTiming> clone() const = 0;

  // The sampling period (0: continuous increments) and the delay h (0: none).
  virtual double period() const = 0;
  virtual double delay() const = 0;
  // std::invalid_argument unless h is finite and >= 0, or for samples with h > 0.
  virtual void set_delay(double h) = 0;
  // h in grid steps, D = round(h / dt) (0 without a delay); std::invalid_argument when h / dt is
  // not a whole number (relative tolerance 1e-9) or D > kMaxDelaySteps.
  virtual std::size_t delay_steps(double dt) const = 0;
  // Grid steps per period; std::invalid_argument unless period / dt is a whole number >= 1, or for
  // increments.
  virtual std::size_t steps_per_sample(double dt) const = 0;
  // Normals the truth's loop draws per grid step for its increments, of a noise factor with r
  // columns: r for increments, 0 for samples (their noise comes after the truth).
  virtual std::size_t increment_noise(std::size_t r) const = 0;
  // The increment over [t, t + dt] (see Observation::increment); nothing for samples.
  virtual void increment(ObservationRate& rate, ObservationNoise& noise, double t, double dt, const double* x_start,
                         const double* x_end, const double* dW2, double* dy) const = 0;
  virtual void increment_lanes(ObservationRate& rate, ObservationNoise& noise, double t, double dt, std::size_t count,
                               const double* x_start, const double* x_end, const double* dW2, double* dy) const = 0;
};

// The longest delay in grid steps: the truth would keep nothing longer, but a filter's history of
// D grid values would not fit.
inline constexpr std::size_t kMaxDelaySteps = 10000000;

class Increments final : public ObservationTiming {
 public:
  explicit Increments(double delay = 0) { set_delay(delay); }
  std::unique_ptr<ObservationTiming> clone() const override { return std::make_unique<Increments>(*this); }
  double period() const override { return 0; }
  double delay() const override { return delay_; }
  void set_delay(double h) override;
  std::size_t delay_steps(double dt) const override;
  std::size_t steps_per_sample(double dt) const override;
  std::size_t increment_noise(std::size_t r) const override { return r; }
  void increment(ObservationRate& rate, ObservationNoise& noise, double t, double dt, const double* x_start,
                 const double* x_end, const double* dW2, double* dy) const override;
  void increment_lanes(ObservationRate& rate, ObservationNoise& noise, double t, double dt, std::size_t count,
                       const double* x_start, const double* x_end, const double* dW2, double* dy) const override;

 private:
  double delay_ = 0;
};

class Samples final : public ObservationTiming {
 public:
  // std::invalid_argument unless the period is finite and > 0.
  explicit Samples(double period);
  std::unique_ptr<ObservationTiming> clone() const override { return std::make_unique<Samples>(*this); }
  double period() const override { return period_; }
  double delay() const override { return 0; }
  void set_delay(double h) override;
  std::size_t delay_steps(double) const override { return 0; }
  std::size_t steps_per_sample(double dt) const override;
  std::size_t increment_noise(std::size_t) const override { return 0; }
  void increment(ObservationRate&, ObservationNoise&, double, double, const double*, const double*, const double*,
                 double*) const override {}
  void increment_lanes(ObservationRate&, ObservationNoise&, double, double, std::size_t, const double*, const double*,
                       const double*, double*) const override {}

 private:
  double period_;
};

}  // namespace pfgen_runtime
