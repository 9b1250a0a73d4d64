#include "pfgen_runtime/observation.hpp"

#include <cmath>
#include <cstdio>
#include <stdexcept>
#include <utility>

#include "pfgen_runtime/lane_pack.hpp"
#include "pfgen_support/whole_steps.hpp"

namespace pfgen_runtime {

LinearObservation::LinearObservation(Eigen::VectorXd A0, Eigen::MatrixXd A, Eigen::MatrixXd B)
    : p_(static_cast<std::size_t>(A.rows())), n_(static_cast<std::size_t>(A.cols())),
      r_(static_cast<std::size_t>(B.cols())), A0_(std::move(A0)), A_(std::move(A)), B_(std::move(B)), work_(p_) {
  if (p_ == 0 || n_ == 0) throw std::invalid_argument("observation: A must be p x n with p, n >= 1");
  if (A0_.size() != A_.rows() || B_.rows() != A_.rows())
    throw std::invalid_argument("observation: A0 must have p entries and B p rows");
}

LinearObservation::LinearObservation(std::size_t p, std::size_t n, std::size_t r, Coefficients coefficients)
    : p_(p), n_(n), r_(r), coefficients_(std::move(coefficients)), A0_(Eigen::VectorXd::Zero(p)),
      A_(Eigen::MatrixXd::Zero(p, n)), B_(Eigen::MatrixXd::Zero(p, r)), work_(p) {
  if (p_ == 0 || n_ == 0) throw std::invalid_argument("observation: p and n must be at least 1");
  if (!coefficients_) throw std::invalid_argument("observation: the coefficient callback is missing");
}

void LinearObservation::set_delay(double h) {
  if (!(h >= 0) || !std::isfinite(h)) throw std::invalid_argument("observation: the delay h must be finite and >= 0");
  if (h > 0 && rate_) throw std::invalid_argument("observation: a nonlinear rate with a delay is not supported");
  delay_ = h;
}

void LinearObservation::set_rate(Rate rate, BatchRate batch) {
  if (!rate) throw std::invalid_argument("observation: the rate function is missing");
  if (delay_ != 0) throw std::invalid_argument("observation: a nonlinear rate with a delay is not supported");
  rate_ = std::move(rate);
  batch_rate_ = std::move(batch);
  start_.resize(static_cast<Eigen::Index>(p_));
  lane_x_.resize(static_cast<Eigen::Index>(n_));
  lane_h_.resize(static_cast<Eigen::Index>(p_));
}

void LinearObservation::nonlinear_rate(double t, const double* x, double* h) const {
  if (!rate_) throw std::logic_error("observation: the rate is linear, A0 + A x");
  rate_(t, x, h);
}

void LinearObservation::nonlinear_rate_batch(double t, std::size_t count, const double* x, double* h) {
  if (!rate_) throw std::logic_error("observation: the rate is linear, A0 + A x");
  if (batch_rate_) return batch_rate_(t, count, x, h);
  for (std::size_t k = 0; k < count; ++k) {
    for (std::size_t i = 0; i < n_; ++i) lane_x_[static_cast<Eigen::Index>(i)] = x[i * count + k];
    rate_(t, lane_x_.data(), lane_h_.data());
    for (std::size_t a = 0; a < p_; ++a) h[a * count + k] = lane_h_[static_cast<Eigen::Index>(a)];
  }
}

std::size_t LinearObservation::delay_steps(double dt) const {
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

void LinearObservation::evaluate(double t) {
  if (!coefficients_) return;
  coefficients_(t, A0_, A_, B_);
  if (A0_.size() != static_cast<Eigen::Index>(p_) || A_.rows() != static_cast<Eigen::Index>(p_) ||
      A_.cols() != static_cast<Eigen::Index>(n_) || B_.rows() != static_cast<Eigen::Index>(p_) ||
      B_.cols() != static_cast<Eigen::Index>(r_))
    throw std::logic_error("observation: the coefficient callback resized A0, A or B");
}

void LinearObservation::increment(double t, double dt, const Eigen::Ref<const Eigen::VectorXd>& x_start,
                                  const Eigen::Ref<const Eigen::VectorXd>& x_end,
                                  const Eigen::Ref<const Eigen::VectorXd>& dW2, Eigen::Ref<Eigen::VectorXd> dy) {
  if (x_start.size() != static_cast<Eigen::Index>(n_) || x_end.size() != static_cast<Eigen::Index>(n_) ||
      dW2.size() != static_cast<Eigen::Index>(r_) || dy.size() != static_cast<Eigen::Index>(p_))
    throw std::invalid_argument("observation: x must have n entries, dW2 r and dy p");
  // Plain loops: p, n and r are small, where Eigen's dynamic-size products cost more than the
  // arithmetic.
  const Eigen::Index p = static_cast<Eigen::Index>(p_), n = static_cast<Eigen::Index>(n_),
                     r = static_cast<Eigen::Index>(r_);
  if (rate_) {
    // The same trapezoid, of h (a Ref to a const vector has unit stride: data() is x).
    rate_(t + dt, x_end.data(), work_.data());
    rate_(t, x_start.data(), start_.data());
    evaluate(t);
    for (Eigen::Index i = 0; i < p; ++i) {
      double value = (work_[i] + start_[i]) * (0.5 * dt);
      for (Eigen::Index j = 0; j < r; ++j) value += B_(i, j) * dW2[j];
      dy[i] = value;
    }
    return;
  }
  evaluate(t + dt);
  for (Eigen::Index i = 0; i < p; ++i) {
    double value = A0_[i];
    for (Eigen::Index j = 0; j < n; ++j) value += A_(i, j) * x_end[j];
    work_[i] = value;
  }
  evaluate(t);
  for (Eigen::Index i = 0; i < p; ++i) {
    double value = work_[i] + A0_[i];
    for (Eigen::Index j = 0; j < n; ++j) value += A_(i, j) * x_start[j];
    value *= 0.5 * dt;
    for (Eigen::Index j = 0; j < r; ++j) value += B_(i, j) * dW2[j];
    dy[i] = value;
  }
}

void LinearObservation::increment_lanes(double t, double dt, std::size_t count, const double* x_start,
                                        const double* x_end, const double* dW2, double* dy) {
  namespace lp = lane_pack;
  // increment()'s sums, term by term in its order, each over the lanes.
  lane_end_.resize(p_ * count);
  lane_start_.resize(p_ * count);
  double* end = lane_end_.data();
  double* start = lane_start_.data();
  const double half = 0.5 * dt;
  if (rate_) {
    nonlinear_rate_batch(t + dt, count, x_end, end);
    nonlinear_rate_batch(t, count, x_start, start);
    evaluate(t);
    for (std::size_t i = 0; i < p_; ++i)
      for (std::size_t k = 0; k < count; ++k) end[i * count + k] = (end[i * count + k] + start[i * count + k]) * half;
  } else {
    // increment()'s sums in its order, lane by lane: end = A0 + A x_end at t + dt, then += A0 +
    // A x_start at t, then * dt / 2.
    evaluate(t + dt);
    for (std::size_t i = 0; i < p_; ++i) {
      const auto row = static_cast<Eigen::Index>(i);
      lp::for_lanes(count, [&](std::size_t k, auto lanes) {
        auto rate = lp::splat(A0_[row], lanes);
        for (std::size_t j = 0; j < n_; ++j)
          rate = rate + lp::splat(A_(row, static_cast<Eigen::Index>(j)), lanes) * lp::load(x_end + j * count + k, lanes);
        lp::store(end + i * count + k, rate, lanes);
      });
    }
    evaluate(t);
    for (std::size_t i = 0; i < p_; ++i) {
      const auto row = static_cast<Eigen::Index>(i);
      lp::for_lanes(count, [&](std::size_t k, auto lanes) {
        auto rate = lp::load(end + i * count + k, lanes) + lp::splat(A0_[row], lanes);
        for (std::size_t j = 0; j < n_; ++j)
          rate = rate + lp::splat(A_(row, static_cast<Eigen::Index>(j)), lanes) * lp::load(x_start + j * count + k, lanes);
        lp::store(end + i * count + k, rate * lp::splat(half, lanes), lanes);
      });
    }
  }
  for (std::size_t i = 0; i < p_; ++i)
    lp::for_lanes(count, [&](std::size_t k, auto lanes) {
      auto increment = lp::load(end + i * count + k, lanes);
      for (std::size_t j = 0; j < r_; ++j)
        increment = increment + lp::splat(B_(static_cast<Eigen::Index>(i), static_cast<Eigen::Index>(j)), lanes) *
                                    lp::load(dW2 + j * count + k, lanes);
      lp::store(dy + i * count + k, increment, lanes);
    });
}

void LinearObservation::coefficients(double t, Eigen::VectorXd& A0, Eigen::MatrixXd& A, Eigen::MatrixXd& B) {
  evaluate(t);
  A0 = A0_;
  A = A_;
  B = B_;
}

Eigen::VectorXd LinearObservation::rate(double t, const Eigen::Ref<const Eigen::VectorXd>& x) {
  if (rate_) {
    Eigen::VectorXd h(static_cast<Eigen::Index>(p_));
    rate_(t, x.data(), h.data());
    return h;
  }
  evaluate(t);
  return A0_ + A_ * x;
}

}  // namespace pfgen_runtime
