#include "pfgen_runtime/observation.hpp"

#include <stdexcept>
#include <utility>

namespace pfgen_runtime {

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

Observation::Observation(std::unique_ptr<ObservationRate> rate, ObservationNoise noise,
                         std::unique_ptr<ObservationTiming> timing)
    : rate_(std::move(rate)), noise_(std::move(noise)), timing_(std::move(timing)) {
  if (!rate_) throw std::invalid_argument("observation: the rate is missing");
  if (noise_.p() != rate_->p()) throw std::invalid_argument("observation: the noise factor must have p rows");
}

Observation::Observation(Eigen::VectorXd A0, Eigen::MatrixXd A, Eigen::MatrixXd B)
    : Observation(std::make_unique<AffineRate>(std::move(A0), std::move(A)), ObservationNoise(std::move(B)),
                  std::make_unique<Increments>()) {}

Observation::Observation(std::size_t p, std::size_t n, std::size_t r, Coefficients coefficients)
    : Observation(affine_part(p, n, r, present(coefficients)), noise_part(p, n, r, coefficients),
                  std::make_unique<Increments>()) {}

Observation Observation::continuous(std::unique_ptr<ObservationRate> rate, ObservationNoise noise, double delay) {
  return Observation(std::move(rate), std::move(noise), std::make_unique<Increments>(delay));
}

Observation Observation::sampled(std::unique_ptr<ObservationRate> rate, ObservationNoise noise, double period) {
  return Observation(std::move(rate), std::move(noise), std::make_unique<Samples>(period));
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
    : rate_(other.rate_->clone()), noise_(other.noise_), timing_(other.timing_->clone()) {}

Observation& Observation::operator=(const Observation& other) {
  if (this != &other) *this = Observation(other);
  return *this;
}

void Observation::increment(double t, double dt, const Eigen::Ref<const Eigen::VectorXd>& x_start,
                            const Eigen::Ref<const Eigen::VectorXd>& x_end, const Eigen::Ref<const Eigen::VectorXd>& dW2,
                            Eigen::Ref<Eigen::VectorXd> dy) {
  if (x_start.size() != static_cast<Eigen::Index>(n()) || x_end.size() != static_cast<Eigen::Index>(n()) ||
      dW2.size() != static_cast<Eigen::Index>(increment_noise()) || dy.size() != static_cast<Eigen::Index>(p()))
    throw std::invalid_argument("observation: x must have n entries, dW2 r and dy p");
  // A Ref to a const vector has unit stride: data() is x.
  timing_->increment(*rate_, noise_, t, dt, x_start.data(), x_end.data(), dW2.data(), dy.data());
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
