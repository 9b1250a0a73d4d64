#include "pfgen_runtime/record_run.hpp"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <stdexcept>

#include "pfgen_runtime/guards.hpp"

namespace pfgen_runtime {
namespace {

constexpr double kLogTwoPi = 1.8378770664093454836;
constexpr double kMaxSubsteps = 1e7;  // prediction sub-steps between two rows

// S = L L^T in place (lower triangle, row-major p x p); false unless positive definite.
bool cholesky(double* S, std::size_t p) {
  for (std::size_t j = 0; j < p; ++j) {
    double d = S[j * p + j];
    for (std::size_t k = 0; k < j; ++k) d -= S[j * p + k] * S[j * p + k];
    if (!(d > 0)) return false;
    const double l = std::sqrt(d);
    S[j * p + j] = l;
    for (std::size_t i = j + 1; i < p; ++i) {
      double s = S[i * p + j];
      for (std::size_t k = 0; k < j; ++k) s -= S[i * p + k] * S[j * p + k];
      S[i * p + j] = s / l;
    }
  }
  return true;
}

// x = L^-1 b (forward substitution), L from cholesky().
void forward(const double* L, std::size_t p, const double* b, double* x) {
  for (std::size_t i = 0; i < p; ++i) {
    double s = b[i];
    for (std::size_t k = 0; k < i; ++k) s -= L[i * p + k] * x[k];
    x[i] = s / L[i * p + i];
  }
}

// |L^-1 b|^2, L from cholesky(); L^-1 b is left in x.
double whitened_square(const double* L, std::size_t p, const double* b, double* x) {
  forward(L, p, b, x);
  double square = 0;
  for (std::size_t i = 0; i < p; ++i) square += x[i] * x[i];
  return square;
}

double log_determinant(const double* L, std::size_t p) {
  double out = 0;
  for (std::size_t i = 0; i < p; ++i) out += 2 * std::log(L[i * p + i]);
  return out;
}

std::string at_time(double t) {
  char text[40];
  std::snprintf(text, sizeof text, "at t = %.10g", t);
  return text;
}

}  // namespace

RecordRun::RecordRun(const RecordFilter& filter, std::vector<double> values, double t0, const RecordRunOptions& options,
                     const std::vector<double>& initial)
    : filter_(filter),
      values_(std::move(values)),
      options_(options),
      t_(t0),
      state_(filter.full_state_size()),
      yhat_(filter.p),
      innovation_(filter.p),
      normalized_(filter.p),
      S_(filter.p * filter.p),
      B_(filter.p * filter.r),
      dy_(filter.p),
      whitened_(filter.p),
      R_(filter.p * filter.p),
      J_(filter.p * filter.n),
      h_up_(filter.p),
      h_down_(filter.p),
      scores_(filter.p, options.max_lags) {
  if (options_.substeps == 0) throw std::invalid_argument("substeps must be at least 1");
  if (initial.empty())
    filter.initial_state(state_.data());
  else if (filter.extra_state_size > 0)
    throw std::invalid_argument("the filter '" + filter.name + "' keeps a history and starts from the model's m0 and P0");
  else if (initial.size() == state_.size())
    state_ = initial;
  else
    throw std::invalid_argument("the initial state has " + std::to_string(initial.size()) + " entries, the filter " +
                                std::to_string(state_.size()));
}

bool RecordRun::fail(const std::string& why) {
  failure_ = why;
  return false;
}

bool RecordRun::state_finite() const {
  for (double v : state_)
    if (!std::isfinite(v)) return false;
  return true;
}

bool RecordRun::advance(double t, const double* observation) {
  if (failed()) return false;
  // A continuous record's first row at the prior's time marks where it starts: an increment needs
  // an interval before it, so there is nothing to absorb. (A sample there updates the prior.)
  const bool first = !begun_;
  begun_ = true;
  if (first && !filter_.sampled() && t == t_) return true;
  if (!(t > t_ || (filter_.sampled() && t == t_)))
    throw std::invalid_argument("the time " + std::to_string(t) + " does not come after the filter's");
  const bool ok = filter_.sampled() ? sample(t, observation) : increment(t, observation);
  t_ = t;
  if (ok && !state_finite()) return fail("the filter state is no longer finite " + at_time(t));
  return ok;
}

bool RecordRun::sample(double t, const double* y) {
  const std::size_t p = filter_.p;
  std::size_t missing = 0;
  for (std::size_t i = 0; i < p; ++i) missing += std::isnan(y[i]) ? 1 : 0;
  if (missing > 0 && missing < p)
    throw std::invalid_argument("a sample must be whole or missing: " + std::to_string(missing) + " of its " +
                                std::to_string(p) + " entries are missing");
  // Prediction sub-steps in proportion to the model's per period.
  const double interval = t - t_;
  const double share = interval * static_cast<double>(filter_.substeps) / filter_.period;
  const double steps = std::max(1.0, std::ceil(share * (1 - 1e-12)));
  // A gap that long is far more likely a wrong time (a year for a day) than a record: 10^7
  // sub-steps take seconds, and 10^9 minutes.
  if (steps > kMaxSubsteps) {
    char text[240];
    std::snprintf(text, sizeof text,
                  "the interval from t = %.10g to %.10g needs %.3g prediction sub-steps (%zu per period %.10g), more "
                  "than %.0e: check the time column",
                  t_, t, steps, filter_.substeps, filter_.period, kMaxSubsteps);
    throw std::invalid_argument(text);
  }
  const auto count = static_cast<std::size_t>(steps);
  const double dt = interval / steps;
  for (std::size_t k = 0; k < count && interval > 0; ++k)
    filter_.predict(state_.data(), values_.data(), t_ + static_cast<double>(k) * dt, dt);
  observed_ = missing == 0;
  if (!observed_) {
    for (std::size_t i = 0; i < p; ++i) innovation_[i] = normalized_[i] = yhat_[i] = std::nan("");
    return true;
  }
  if (!state_finite()) return fail("the filter state is no longer finite " + at_time(t));
  filter_.innovation(state_.data(), values_.data(), t, yhat_.data(), S_.data());
  for (std::size_t i = 0; i < p; ++i) innovation_[i] = y[i] - yhat_[i];
  if (!cholesky(S_.data(), p)) return fail("the innovation covariance S is not positive definite " + at_time(t));
  const double square = whitened_square(S_.data(), p, innovation_.data(), normalized_.data());
  scores_.add(normalized_.data(), -0.5 * (static_cast<double>(p) * kLogTwoPi + log_determinant(S_.data(), p) + square));
  if (!filter_.update(state_.data(), values_.data(), t, y))
    return fail("the update found S not positive definite " + at_time(t));
  return true;
}

bool RecordRun::increment(double t, const double* observation) {
  const std::size_t p = filter_.p, r = filter_.r, n = filter_.n;
  // A filter on a fixed grid (delayed observations) takes `substeps` steps of fixed_dt per row, on
  // its own grid tau_k = k fixed_dt from the prior: the rows must be that far apart.
  const bool on_grid = filter_.fixed_dt > 0;
  const double grid_interval = filter_.fixed_dt * static_cast<double>(options_.substeps);
  if (on_grid && !(std::abs((t - t_) - grid_interval) <= 1e-9 * grid_interval)) {
    char text[200];
    std::snprintf(text, sizeof text, "the interval from t = %.10g is %.10g, not the filters' step %.10g (relative 1e-9)",
                  t_, t - t_, grid_interval);
    throw std::invalid_argument(std::string("delayed observations need equally spaced rows: ") + text);
  }
  const double interval = on_grid ? grid_interval : t - t_;
  const double tau = on_grid ? static_cast<double>(steps_) * filter_.fixed_dt : t_;
  for (std::size_t i = 0; i < p; ++i) {
    if (std::isnan(observation[i]))
      throw std::invalid_argument("continuous data cannot have a missing value: the filter has no step without dy");
    dy_[i] = options_.continuous == ContinuousData::Rates ? observation[i] * interval : observation[i];
  }
  // h and R = B B^T where the interval starts (Ito).
  filter_.predicted_observation(state_.data(), values_.data(), tau, yhat_.data());
  filter_.observation_noise(values_.data(), t_, B_.data());
  for (std::size_t i = 0; i < p; ++i)
    for (std::size_t j = 0; j <= i; ++j) {
      double s = 0;
      for (std::size_t k = 0; k < r; ++k) s += B_[i * r + k] * B_[j * r + k];
      R_[i * p + j] = R_[j * p + i] = s;
    }
  // The innovation dy - h dt over an interval has covariance R dt + Cov(h(x)) dt^2 + O(dt^3): the
  // state's own uncertainty over the interval adds to the sensor's noise. Cov(h(x)) is taken as
  // E[J_h] P E[J_h]^T, the linearisation the filters' gains use (exact for a linear h), with
  // E[J_h] = d E[h] / dm (for Gaussian x) by central differences of the predicted observation.
  // Without that term a long record's mean square drifts above 1 by about P/R dt, which 10^7
  // steps detect.
  shifted_ = state_;
  for (std::size_t j = 0; j < n; ++j) {
    const double step = 1e-6 * std::max(1.0, std::abs(state_[j]));
    shifted_[j] = state_[j] + step;
    filter_.predicted_observation(shifted_.data(), values_.data(), tau, h_up_.data());
    shifted_[j] = state_[j] - step;
    filter_.predicted_observation(shifted_.data(), values_.data(), tau, h_down_.data());
    shifted_[j] = state_[j];
    for (std::size_t i = 0; i < p; ++i) J_[i * n + j] = (h_up_[i] - h_down_[i]) / (2 * step);
  }
  auto P = [&](std::size_t i, std::size_t j) {  // the packed upper triangle after m
    if (i > j) std::swap(i, j);
    return state_[n + packed_diagonal(n, i) + (j - i)];
  };
  for (std::size_t i = 0; i < p; ++i)
    for (std::size_t j = 0; j <= i; ++j) {
      double spread = 0;
      for (std::size_t k = 0; k < n; ++k)
        for (std::size_t l = 0; l < n; ++l) spread += J_[i * n + k] * P(k, l) * J_[j * n + l];
      S_[i * p + j] = S_[j * p + i] = R_[i * p + j] * interval + spread * interval * interval;
    }
  if (!cholesky(R_.data(), p)) return fail("the observation noise B B^T is not positive definite " + at_time(t_));
  if (!cholesky(S_.data(), p)) return fail("the innovation covariance is not positive definite " + at_time(t_));
  for (std::size_t i = 0; i < p; ++i) {
    yhat_[i] *= interval;  // h dt
    innovation_[i] = dy_[i] - yhat_[i];
  }
  const double square = whitened_square(S_.data(), p, innovation_.data(), normalized_.data());
  increment_log_density_ +=
      -0.5 * (static_cast<double>(p) * kLogTwoPi + log_determinant(S_.data(), p) + square);
  // Girsanov: h^T R^-1 dy - 1/2 h^T R^-1 h dt = (|L^-1 dy|^2 - |L^-1 (dy - h dt)|^2) / (2 dt), R = L L^T.
  const double dy_square = whitened_square(R_.data(), p, dy_.data(), whitened_.data());
  const double innovation_square = whitened_square(R_.data(), p, innovation_.data(), whitened_.data());
  scores_.add(normalized_.data(), (dy_square - innovation_square) / (2 * interval));
  observed_ = true;
  const double dt = interval / static_cast<double>(options_.substeps);
  for (std::size_t i = 0; i < p; ++i) dy_[i] /= static_cast<double>(options_.substeps);
  for (std::size_t k = 0; k < options_.substeps; ++k)
    if (on_grid)
      filter_.step(state_.data(), values_.data(), static_cast<double>(steps_++) * filter_.fixed_dt, filter_.fixed_dt,
                   dy_.data());
    else
      filter_.step(state_.data(), values_.data(), t_ + static_cast<double>(k) * dt, dt, dy_.data());
  return true;
}

}  // namespace pfgen_runtime
