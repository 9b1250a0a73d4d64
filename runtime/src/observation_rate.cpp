#include "pfgen_runtime/observation_rate.hpp"

#include <stdexcept>
#include <utility>

#include "pfgen_runtime/lane_pack.hpp"

namespace pfgen_runtime {

ObservationRate::ObservationRate(std::size_t p, std::size_t n) : p_(p), n_(n) {
  if (p == 0 || n == 0) throw std::invalid_argument("observation: p and n must be at least 1");
}

AffineRate::AffineRate(Eigen::VectorXd A0, Eigen::MatrixXd A)
    : ObservationRate(static_cast<std::size_t>(A.rows()), static_cast<std::size_t>(A.cols())), A0_(std::move(A0)),
      A_(std::move(A)), evaluated_(true) {
  if (A0_.size() != A_.rows()) throw std::invalid_argument("observation: A0 must have p entries");
}

AffineRate::AffineRate(std::size_t p, std::size_t n, Coefficients coefficients)
    : ObservationRate(p, n), coefficients_(std::move(coefficients)), A0_(Eigen::VectorXd::Zero(p)),
      A_(Eigen::MatrixXd::Zero(p, n)) {
  if (!coefficients_) throw std::invalid_argument("observation: the coefficient callback is missing");
}

void AffineRate::evaluate(double t) {
  if (!coefficients_ || (evaluated_ && t == evaluated_t_)) return;
  coefficients_(t, A0_, A_);
  if (A0_.size() != static_cast<Eigen::Index>(p()) || A_.rows() != static_cast<Eigen::Index>(p()) ||
      A_.cols() != static_cast<Eigen::Index>(n()))
    throw std::logic_error("observation: the coefficient callback resized A0 or A");
  evaluated_t_ = t;
  evaluated_ = true;
}

// Plain loops: p and n are small, where Eigen's dynamic-size products cost more than the arithmetic.
void AffineRate::value(double t, const double* x, double* h) {
  evaluate(t);
  const auto p = static_cast<Eigen::Index>(this->p()), n = static_cast<Eigen::Index>(this->n());
  for (Eigen::Index i = 0; i < p; ++i) {
    double value = A0_[i];
    for (Eigen::Index j = 0; j < n; ++j) value += A_(i, j) * x[j];
    h[i] = value;
  }
}

namespace {

// A0 + A x over `width` lanes (a constant, so the compiler unrolls and packs the loops): per lane
// A0, then + A_ij x_j in j's order, value()'s sum.
template <std::size_t width>
void affine_lanes(const Eigen::VectorXd& A0, const Eigen::MatrixXd& A, std::size_t count, const double* x, double* h,
                  std::size_t first) {
  for (Eigen::Index a = 0; a < A.rows(); ++a) {
    double* __restrict out = h + static_cast<std::size_t>(a) * count + first;
    const double offset = A0[a];
    for (std::size_t k = 0; k < width; ++k) out[k] = offset;
    for (Eigen::Index j = 0; j < A.cols(); ++j) {
      const double coefficient = A(a, j);
      const double* __restrict xj = x + static_cast<std::size_t>(j) * count + first;
      for (std::size_t k = 0; k < width; ++k) out[k] += coefficient * xj[k];
    }
  }
}

}  // namespace

// 32 lanes at a time (the particle reference's block, every step: loops of unknown length cost it
// 4 %), then 8 (the Monte Carlo engine's batch of truths), then one by one.
void AffineRate::lanes(double t, std::size_t count, const double* x, double* h) {
  evaluate(t);
  std::size_t k = 0;
  for (; k + 32 <= count; k += 32) affine_lanes<32>(A0_, A_, count, x, h, k);
  for (; k + 8 <= count; k += 8) affine_lanes<8>(A0_, A_, count, x, h, k);
  for (; k < count; ++k) affine_lanes<1>(A0_, A_, count, x, h, k);
}

// (A0 + A x_end)(t + dt), then + A0(t) and each A(t)_ij x_start_j, then times dt / 2: the
// increment's sum as it has always been taken (not the sum of two rates, whose rounding differs).
void AffineRate::trapezoid(double t, double dt, const double* x_start, const double* x_end, double* out) {
  value(t + dt, x_end, out);
  evaluate(t);
  const auto p = static_cast<Eigen::Index>(this->p()), n = static_cast<Eigen::Index>(this->n());
  for (Eigen::Index i = 0; i < p; ++i) {
    double value = out[i] + A0_[i];
    for (Eigen::Index j = 0; j < n; ++j) value += A_(i, j) * x_start[j];
    value *= 0.5 * dt;
    out[i] = value;
  }
}

void AffineRate::trapezoid_lanes(double t, double dt, std::size_t count, const double* x_start, const double* x_end,
                                 double* out) {
  namespace lp = lane_pack;
  lanes(t + dt, count, x_end, out);
  evaluate(t);
  const double half = 0.5 * dt;
  for (std::size_t i = 0; i < p(); ++i) {
    const auto row = static_cast<Eigen::Index>(i);
    lp::for_lanes(count, [&](std::size_t k, auto lanes) {
      auto rate = lp::load(out + i * count + k, lanes) + lp::splat(A0_[row], lanes);
      for (std::size_t j = 0; j < n(); ++j)
        rate = rate + lp::splat(A_(row, static_cast<Eigen::Index>(j)), lanes) * lp::load(x_start + j * count + k, lanes);
      lp::store(out + i * count + k, rate * lp::splat(half, lanes), lanes);
    });
  }
}

FunctionRate::FunctionRate(std::size_t p, std::size_t n, Function function, BatchFunction batch)
    : ObservationRate(p, n), function_(std::move(function)), batch_(std::move(batch)),
      lane_x_(static_cast<Eigen::Index>(n)), lane_h_(static_cast<Eigen::Index>(p)) {
  if (!function_) throw std::invalid_argument("observation: the rate function is missing");
}

void FunctionRate::lanes(double t, std::size_t count, const double* x, double* h) {
  if (batch_) return batch_(t, count, x, h);
  for (std::size_t k = 0; k < count; ++k) {
    for (std::size_t i = 0; i < n(); ++i) lane_x_[static_cast<Eigen::Index>(i)] = x[i * count + k];
    function_(t, lane_x_.data(), lane_h_.data());
    for (std::size_t a = 0; a < p(); ++a) h[a * count + k] = lane_h_[static_cast<Eigen::Index>(a)];
  }
}

void FunctionRate::trapezoid(double t, double dt, const double* x_start, const double* x_end, double* out) {
  start_.resize(p());
  function_(t + dt, x_end, out);
  function_(t, x_start, start_.data());
  for (std::size_t i = 0; i < p(); ++i) out[i] = (out[i] + start_[i]) * (0.5 * dt);
}

void FunctionRate::trapezoid_lanes(double t, double dt, std::size_t count, const double* x_start, const double* x_end,
                                   double* out) {
  start_.resize(p() * count);
  double* start = start_.data();
  lanes(t + dt, count, x_end, out);
  lanes(t, count, x_start, start);
  const double half = 0.5 * dt;
  for (std::size_t i = 0; i < p() * count; ++i) out[i] = (out[i] + start[i]) * half;
}

}  // namespace pfgen_runtime
