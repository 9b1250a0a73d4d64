#include "pfgen_runtime/observation.hpp"

#include <cmath>
#include <cstdio>
#include <optional>
#include <stdexcept>
#include <utility>

#include "pfgen_runtime/lane_pack.hpp"
#include "pfgen_support/whole_steps.hpp"

namespace pfgen_runtime {

ObservationNoise::ObservationNoise(Eigen::MatrixXd factor) : factor_(std::move(factor)), evaluated_(true) {
  if (factor_.rows() == 0 || factor_.cols() == 0)
    throw std::invalid_argument("observation: the noise factor must be p x r with p, r >= 1");
}

ObservationNoise::ObservationNoise(std::size_t p, std::size_t r, Factor factor)
    : fill_(std::move(factor)), factor_(Eigen::MatrixXd::Zero(static_cast<Eigen::Index>(p), static_cast<Eigen::Index>(r))) {
  if (p == 0 || r == 0) throw std::invalid_argument("observation: the noise factor must be p x r with p, r >= 1");
  if (!fill_) throw std::invalid_argument("observation: the noise callback is missing");
}

const Eigen::MatrixXd& ObservationNoise::at(double t) {
  if (!fill_ || (evaluated_ && t == evaluated_t_)) return factor_;
  const Eigen::Index p = factor_.rows(), r = factor_.cols();
  fill_(t, factor_);
  if (factor_.rows() != p || factor_.cols() != r) throw std::logic_error("observation: the noise callback resized its factor");
  evaluated_t_ = t;
  evaluated_ = true;
  return factor_;
}

namespace {

// One callback filling A0, A and B (or C0, C and Uv) as the rate's coefficients and the noise's
// factor: each part keeps a copy with its own arrays for what it does not read.
template <class Fill>
std::unique_ptr<ObservationRate> affine_part(std::size_t p, std::size_t n, std::size_t r, Fill fill) {
  return std::make_unique<AffineRate>(
      p, n, [fill, B = Eigen::MatrixXd(p, r)](double t, Eigen::VectorXd& A0, Eigen::MatrixXd& A) mutable {
        fill(t, A0, A, B);
      });
}

template <class Fill>
ObservationNoise noise_part(std::size_t p, std::size_t n, std::size_t r, Fill fill) {
  return ObservationNoise(p, r, [fill, A0 = Eigen::VectorXd(p), A = Eigen::MatrixXd(p, n)](double t, Eigen::MatrixXd& B) mutable {
    fill(t, A0, A, B);
  });
}

template <class Callback>
const Callback& present(const Callback& callback) {
  if (!callback) throw std::invalid_argument("observation: the coefficient callback is missing");
  return callback;
}

}  // namespace

Observation::Observation(std::unique_ptr<ObservationRate> rate, ObservationNoise noise, double period, double delay)
    : rate_(std::move(rate)), noise_(std::move(noise)), period_(period) {
  if (!rate_) throw std::invalid_argument("observation: the rate is missing");
  if (noise_.p() != rate_->p()) throw std::invalid_argument("observation: the noise factor must have p rows");
  if (period != 0 && (!(period > 0) || !std::isfinite(period)))
    throw std::invalid_argument("observation: the sampling period must be finite and > 0");
  set_delay(delay);
}

Observation::Observation(Eigen::VectorXd A0, Eigen::MatrixXd A, Eigen::MatrixXd B)
    : Observation(std::make_unique<AffineRate>(std::move(A0), std::move(A)), ObservationNoise(std::move(B)), 0, 0) {}

Observation::Observation(std::size_t p, std::size_t n, std::size_t r, Coefficients coefficients)
    : Observation(affine_part(p, n, r, present(coefficients)), noise_part(p, n, r, coefficients), 0, 0) {}

Observation Observation::continuous(std::unique_ptr<ObservationRate> rate, ObservationNoise noise, double delay) {
  return Observation(std::move(rate), std::move(noise), 0, delay);
}

Observation Observation::sampled(std::unique_ptr<ObservationRate> rate, ObservationNoise noise, double period) {
  if (!(period > 0)) throw std::invalid_argument("observation: the sampling period must be finite and > 0");
  return Observation(std::move(rate), std::move(noise), period, 0);
}

Observation Observation::sampled(std::size_t p, std::size_t n, std::size_t q, double period,
                                 SampledCoefficients coefficients) {
  present(coefficients);
  // Row-major arrays to Eigen's column-major ones, value by value.
  auto fill = [coefficients, C0 = std::vector<double>(p), C = std::vector<double>(p * n),
               Uv = std::vector<double>(p * q)](double t, Eigen::VectorXd& a0, Eigen::MatrixXd& a,
                                                Eigen::MatrixXd& uv) mutable {
    coefficients(t, C0.data(), C.data(), Uv.data());
    const std::size_t n = static_cast<std::size_t>(a.cols()), q = static_cast<std::size_t>(uv.cols());
    for (std::size_t i = 0; i < C0.size(); ++i) {
      const auto row = static_cast<Eigen::Index>(i);
      a0[row] = C0[i];
      for (std::size_t j = 0; j < n; ++j) a(row, static_cast<Eigen::Index>(j)) = C[i * n + j];
      for (std::size_t j = 0; j < q; ++j) uv(row, static_cast<Eigen::Index>(j)) = Uv[i * q + j];
    }
  };
  if (p == 0 || n == 0 || q == 0) throw std::invalid_argument("observation: p, n and q must be at least 1");
  return sampled(affine_part(p, n, q, fill), noise_part(p, n, q, fill), period);
}

Observation::Observation(const Observation& other)
    : rate_(other.rate_->clone()), noise_(other.noise_), period_(other.period_), delay_(other.delay_) {}

Observation& Observation::operator=(const Observation& other) {
  if (this != &other) *this = Observation(other);
  return *this;
}

void Observation::set_delay(double h) {
  if (!(h >= 0) || !std::isfinite(h)) throw std::invalid_argument("observation: the delay h must be finite and >= 0");
  if (h > 0 && sampled()) throw std::invalid_argument("observation: a delay needs continuous observations, not samples");
  delay_ = h;
}

std::size_t Observation::delay_steps(double dt) const {
  if (delay_ == 0) return 0;
  const double ratio = delay_ / dt, whole = std::round(ratio);
  char text[240];
  if (!(whole <= static_cast<double>(max_delay_steps))) {
    std::snprintf(text, sizeof text, "the observation delay h = %.17g is more than %zu steps dt = %.17g (h/dt = %.17g)",
                  delay_, max_delay_steps, dt, ratio);
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

void Observation::increment(double t, double dt, const Eigen::Ref<const Eigen::VectorXd>& x_start,
                            const Eigen::Ref<const Eigen::VectorXd>& x_end, const Eigen::Ref<const Eigen::VectorXd>& dW2,
                            Eigen::Ref<Eigen::VectorXd> dy) {
  if (sampled()) return;
  if (x_start.size() != static_cast<Eigen::Index>(n()) || x_end.size() != static_cast<Eigen::Index>(n()) ||
      dW2.size() != static_cast<Eigen::Index>(r()) || dy.size() != static_cast<Eigen::Index>(p()))
    throw std::invalid_argument("observation: x must have n entries, dW2 r and dy p");
  rate_->trapezoid(t, dt, x_start.data(), x_end.data(), dy.data());
  const Eigen::MatrixXd& B = noise_.at(t);
  const auto p = static_cast<Eigen::Index>(this->p()), r = static_cast<Eigen::Index>(this->r());
  for (Eigen::Index i = 0; i < p; ++i) {
    double value = dy[i];
    for (Eigen::Index j = 0; j < r; ++j) value += B(i, j) * dW2[j];
    dy[i] = value;
  }
}

void Observation::increment_lanes(double t, double dt, std::size_t count, const double* x_start, const double* x_end,
                                  const double* dW2, double* dy) {
  namespace lp = lane_pack;
  if (sampled()) return;
  rate_->trapezoid_lanes(t, dt, count, x_start, x_end, dy);
  const Eigen::MatrixXd& B = noise_.at(t);
  for (std::size_t i = 0; i < p(); ++i)
    lp::for_lanes(count, [&](std::size_t k, auto lanes) {
      auto increment = lp::load(dy + i * count + k, lanes);
      for (std::size_t j = 0; j < r(); ++j)
        increment = increment + lp::splat(B(static_cast<Eigen::Index>(i), static_cast<Eigen::Index>(j)), lanes) *
                                    lp::load(dW2 + j * count + k, lanes);
      lp::store(dy + i * count + k, increment, lanes);
    });
}

std::size_t Observation::steps_per_sample(double dt) const {
  const std::optional<double> whole = sampled() ? pfgen_support::whole_steps(period_, dt) : std::nullopt;
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

void Observation::sample(double t, const double* x, const double* v, double* clean, double* noisy) {
  rate_->value(t, x, clean);
  const Eigen::MatrixXd& Uv = noise_.at(t);
  for (std::size_t i = 0; i < p(); ++i) {
    double value = clean[i];
    for (std::size_t j = 0; j < r(); ++j)
      value += Uv(static_cast<Eigen::Index>(i), static_cast<Eigen::Index>(j)) * v[j];
    noisy[i] = value;
  }
}

}  // namespace pfgen_runtime
