#pragma once
// An observation of the truth as three independent axes, composed (docs/theory.md §2.5, §2.6, §2.9):
// - its rate h(t, x), what it measures (observation_rate.hpp: AffineRate A0 + A x, or FunctionRate);
// - its noise factor (observation_noise.hpp), B(t) (p x r) of increments or Uv(t) (p x q) of samples;
// - its timing (observation_timing.hpp): Increments on the truth's grid, dy = h(t, x(t - delay)) dt
//   + B(t) dW2 with a delay h >= 0 (0: none), or Samples y_k = h(t_k, x(t_k)) + Uv(t_k) v_k at
//   t_k = t0 + k period.
// The truth (simulate_truth_into, the Monte Carlo engine's lanes), the samples (draw_samples), the
// particle reference and the engine's sampled metrics all call this one type; each axis answers
// its own questions. Not thread-safe (work arrays): copy per thread.
#include <cstddef>
#include <functional>
#include <memory>
#include <vector>

#include <Eigen/Core>

#include "pfgen_runtime/observation_noise.hpp"
#include "pfgen_runtime/observation_rate.hpp"
#include "pfgen_runtime/observation_timing.hpp"

namespace pfgen_runtime {

class Observation {
 public:
  // Continuous observations through A0 + A x: dy = (A0 + A x) dt + B dW2 with constant
  // coefficients, or time-varying ones filled at t (arriving sized p, p x n, p x r).
  using Coefficients = std::function<void(double t, Eigen::VectorXd& A0, Eigen::MatrixXd& A, Eigen::MatrixXd& B)>;
  Observation(Eigen::VectorXd A0, Eigen::MatrixXd A, Eigen::MatrixXd B);
  Observation(std::size_t p, std::size_t n, std::size_t r, Coefficients coefficients);
  // Continuous observations of any rate, dy = h(t, x(t - delay)) dt + B(t) dW2.
  static Observation continuous(std::unique_ptr<ObservationRate> rate, ObservationNoise noise, double delay = 0);
  // Samples y_k = h(t_k, x(t_k)) + Uv(t_k) v_k, t_k = t0 + k period (period finite and > 0).
  static Observation sampled(std::unique_ptr<ObservationRate> rate, ObservationNoise noise, double period);
  // Samples through C0 + C x, the coefficients filled row-major at t (C0: p, C: p x n, Uv: p x q).
  using SampledCoefficients = std::function<void(double t, double* C0, double* C, double* Uv)>;
  static Observation sampled(std::size_t p, std::size_t n, std::size_t q, double period,
                             SampledCoefficients coefficients);

  Observation(const Observation& other);
  Observation& operator=(const Observation& other);
  Observation(Observation&&) noexcept = default;
  Observation& operator=(Observation&&) noexcept = default;
  ~Observation() = default;

  std::size_t p() const { return rate_->p(); }
  std::size_t n() const { return rate_->n(); }
  std::size_t r() const { return noise_.r(); }  // noise columns: dW2's, or v's (q)
  ObservationRate& rate() { return *rate_; }
  const ObservationRate& rate() const { return *rate_; }
  const Eigen::MatrixXd& noise(double t) { return noise_.at(t); }

  // The timing (observation_timing.hpp): samples every period() (> 0), or continuous increments
  // (period() 0) with a delay.
  bool sampled() const { return period() > 0; }
  double period() const { return timing_->period(); }
  // Normals the truth's loop draws per grid step for the increments: r() when continuous, 0 for
  // samples (their noise comes after the truth, from the same stream: draw_samples).
  std::size_t increment_noise() const { return timing_->increment_noise(r()); }

  // The delay h >= 0 of continuous increments (0: none): dy over [t, t + dt] reads the truth at
  // t - h and t + dt - h, and x(s) = x(0) for s < 0. std::invalid_argument unless h is finite and
  // >= 0, or for samples.
  void set_delay(double h) { timing_->set_delay(h); }
  double delay() const { return timing_->delay(); }
  // h in steps of the grid: D = round(h / dt); std::invalid_argument when h / dt is not a whole
  // number (relative tolerance 1e-9) or D > max_delay_steps (the truth would keep nothing
  // longer, but a filter's history of D grid values would not fit).
  std::size_t delay_steps(double dt) const { return timing_->delay_steps(dt); }
  static constexpr std::size_t max_delay_steps = kMaxDelaySteps;

  // The increment over [t, t + dt] given the truth at both ends (with a delay the caller passes
  // x(t - h) and x(t + dt - h)) and dW2 (increment_noise() entries): the rate's trapezoid plus
  // B(t) dW2, B at the left end keeping the noise term Ito. Nothing for samples.
  void increment(double t, double dt, const Eigen::Ref<const Eigen::VectorXd>& x_start,
                 const Eigen::Ref<const Eigen::VectorXd>& x_end, const Eigen::Ref<const Eigen::VectorXd>& dW2,
                 Eigen::Ref<Eigen::VectorXd> dy);
  // increment() for `count` states side by side, entry-major (x[i * count + k], dW2[j * count + k],
  // dy[a * count + k]): lane k bit for bit increment()'s on state k.
  void increment_lanes(double t, double dt, std::size_t count, const double* x_start, const double* x_end,
                       const double* dW2, double* dy) {
    timing_->increment_lanes(*rate_, noise_, t, dt, count, x_start, x_end, dW2, dy);
  }

  // Grid steps per period: round(period / dt); std::invalid_argument when period / dt is not a
  // whole number (relative tolerance 1e-9) or the period is shorter than dt, or without samples.
  std::size_t steps_per_sample(double dt) const { return timing_->steps_per_sample(dt); }
  // The noise-free value h(t, x) and the sample, plus Uv v (v: r() normals), at t, into clean and
  // noisy (p).
  void sample(double t, const double* x, const double* v, double* clean, double* noisy);

 private:
  Observation(std::unique_ptr<ObservationRate> rate, ObservationNoise noise, std::unique_ptr<ObservationTiming> timing);
  std::unique_ptr<ObservationRate> rate_;
  ObservationNoise noise_;
  std::unique_ptr<ObservationTiming> timing_;
};

}  // namespace pfgen_runtime
