#include "pfgen_runtime/record_timing.hpp"

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

// An observation whose whitened innovation squares beyond double precision (1e308 against a prediction near 1)
// would score -inf: a failure at its row, not a log-likelihood.
std::string too_far(double t) {
  return "the observation is too far from its prediction to score in double precision " + at_time(t) +
         " (its whitened innovation squared is not finite)";
}

}  // namespace

RecordProgress::RecordProgress(std::size_t n, std::size_t p, std::size_t r, std::size_t state_size,
                               std::vector<double> values, double t0, const RecordRunOptions& options)
    : n(n),
      p(p),
      r(r),
      values(std::move(values)),
      options(options),
      t(t0),
      state(state_size),
      yhat(p),
      innovation(p),
      normalized(p),
      scores(p, options.max_lags),
      S(p * p),
      B(p * r),
      dy(p),
      whitened(p),
      R(p * p),
      J(p * n),
      h_up(p),
      h_down(p) {}

bool RecordProgress::state_finite() const {
  for (double v : state)
    if (!std::isfinite(v)) return false;
  return true;
}

bool RecordProgress::finish_row(double t_row, bool ok) {
  t = t_row;
  if (ok && !state_finite()) return fail("the filter state is no longer finite " + at_time(t_row));
  return ok;
}

bool RecordSamples::absorb(RecordProgress& run, double t, const double* y, bool first) const {
  // A sample at the filter's own time (the prior's, or the last row's) updates it there.
  if (!(t >= run.t)) throw std::invalid_argument("the time " + std::to_string(t) + " does not come after the filter's");
  return run.finish_row(t, predict_and_update(run, t, y, first));
}

double RecordSamples::log_likelihood(const RecordProgress& run) const { return run.scores.log_likelihood(); }

bool RecordSamples::predict_and_update(RecordProgress& run, double t, const double* y, bool first) const {
  const std::size_t p = run.p;
  std::size_t missing = 0;
  for (std::size_t i = 0; i < p; ++i) missing += std::isnan(y[i]) ? 1 : 0;
  if (missing > 0 && missing < p)
    throw std::invalid_argument("a sample must be whole or missing: " + std::to_string(missing) + " of its " +
                                std::to_string(p) + " entries are missing");
  // Prediction sub-steps in proportion to the model's per period.
  const double interval = t - run.t;
  const double share = interval * static_cast<double>(substeps_) / period_;
  const double steps = std::max(1.0, std::ceil(share * (1 - 1e-12)));
  // A gap that long is far more likely a wrong time (a year for a day) than a record: 10^7
  // sub-steps take seconds, and 10^9 minutes.
  if (steps > kMaxSubsteps) {
    char text[320];
    std::snprintf(text, sizeof text,
                  "the interval from t = %.10g to %.10g needs %.3g prediction sub-steps (%zu per period %.10g), more "
                  "than %.0e: check the time column%s",
                  run.t, t, steps, substeps_, period_, kMaxSubsteps,
                  first ? " and the prior's time (--t0)" : "");
    throw std::invalid_argument(text);
  }
  const auto count = static_cast<std::size_t>(steps);
  const double dt = interval / steps;
  for (std::size_t k = 0; k < count && interval > 0; ++k)
    predict_(run.state.data(), run.values.data(), run.t + static_cast<double>(k) * dt, dt);
  run.observed = missing == 0;
  if (!run.observed) {
    for (std::size_t i = 0; i < p; ++i) run.innovation[i] = run.normalized[i] = run.yhat[i] = std::nan("");
    return true;
  }
  if (!run.state_finite()) return run.fail("the filter state is no longer finite " + at_time(t));
  innovation_(run.state.data(), run.values.data(), t, run.yhat.data(), run.S.data());
  for (std::size_t i = 0; i < p; ++i) run.innovation[i] = y[i] - run.yhat[i];
  if (!cholesky(run.S.data(), p)) return run.fail("the innovation covariance S is not positive definite " + at_time(t));
  const double square = whitened_square(run.S.data(), p, run.innovation.data(), run.normalized.data());
  if (!std::isfinite(square)) return run.fail(too_far(t));
  run.scores.add(run.normalized.data(),
                 -0.5 * (static_cast<double>(p) * kLogTwoPi + log_determinant(run.S.data(), p) + square));
  if (!update_(run.state.data(), run.values.data(), t, y))
    return run.fail("the update found S not positive definite " + at_time(t));
  return true;
}

std::string RecordIncrements::step_hint(const RecordProgress& progress) const {
  const std::size_t k = progress.options.substeps;
  return "; the filter took " + std::to_string(k) + (k == 1 ? " step" : " steps") + " per row" +
         (k < kMaxRowSubsteps ? ": if they are too long for its moments, --substeps takes more" : "");
}

bool RecordIncrements::absorb(RecordProgress& run, double t, const double* observation, bool first) const {
  // The first row at the prior's time marks where the record starts: an increment needs an
  // interval before it, so there is nothing to absorb.
  if (first && t == run.t) return true;
  if (!(t > run.t)) throw std::invalid_argument("the time " + std::to_string(t) + " does not come after the filter's");
  return run.finish_row(t, score_and_step(run, t, observation));
}

double RecordIncrements::interval(const RecordProgress& run, double t) const { return t - run.t; }
double RecordIncrements::rate_time(const RecordProgress& run) const { return run.t; }

void RecordIncrements::step_over(RecordProgress& run, double interval) const {
  const double dt = interval / static_cast<double>(run.options.substeps);
  for (std::size_t k = 0; k < run.options.substeps; ++k)
    step_(run.state.data(), run.values.data(), run.t + static_cast<double>(k) * dt, dt, run.dy.data());
}

// `substeps` steps of fixed_dt per row, on the filter's own grid from the prior: the rows must be
// that far apart.
double RecordFixedIncrements::interval(const RecordProgress& run, double t) const {
  const double grid_interval = fixed_dt_ * static_cast<double>(run.options.substeps);
  if (!(std::abs((t - run.t) - grid_interval) <= 1e-9 * grid_interval)) {
    char text[200];
    std::snprintf(text, sizeof text, "the interval from t = %.10g is %.10g, not the filters' step %.10g (relative 1e-9)",
                  run.t, t - run.t, grid_interval);
    throw std::invalid_argument(std::string("delayed observations need equally spaced rows: ") + text);
  }
  return grid_interval;
}

double RecordFixedIncrements::rate_time(const RecordProgress& run) const {
  return static_cast<double>(run.steps) * fixed_dt_;
}

void RecordFixedIncrements::step_over(RecordProgress& run, double) const {
  for (std::size_t k = 0; k < run.options.substeps; ++k)
    step_(run.state.data(), run.values.data(), static_cast<double>(run.steps++) * fixed_dt_, fixed_dt_, run.dy.data());
}

bool RecordIncrements::score_and_step(RecordProgress& run, double t, const double* observation) const {
  const std::size_t p = run.p, r = run.r, n = run.n;
  const double interval = this->interval(run, t);
  const double tau = rate_time(run);
  for (std::size_t i = 0; i < p; ++i) {
    if (std::isnan(observation[i]))
      throw std::invalid_argument("continuous data cannot have a missing value: the filter has no step without dy");
    run.dy[i] = run.options.continuous == ContinuousData::Rates ? observation[i] * interval : observation[i];
  }
  // h and R = B B^T where the interval starts (Ito).
  predicted_observation_(run.state.data(), run.values.data(), tau, run.yhat.data());
  observation_noise_(run.values.data(), run.t, run.B.data());
  for (std::size_t i = 0; i < p; ++i)
    for (std::size_t j = 0; j <= i; ++j) {
      double s = 0;
      for (std::size_t k = 0; k < r; ++k) s += run.B[i * r + k] * run.B[j * r + k];
      run.R[i * p + j] = run.R[j * p + i] = s;
    }
  // The innovation dy - h dt over an interval has covariance R dt + Cov(h(x)) dt^2 + O(dt^3): the
  // state's own uncertainty over the interval adds to the sensor's noise. Cov(h(x)) is taken as
  // E[J_h] P E[J_h]^T, the linearisation the filters' gains use (exact for a linear h), with
  // E[J_h] = d E[h] / dm (for Gaussian x) by central differences of the predicted observation.
  // Without that term a long record's mean square drifts above 1 by about P/R dt, which 10^7
  // steps detect.
  run.shifted = run.state;
  for (std::size_t j = 0; j < n; ++j) {
    const double step = 1e-6 * std::max(1.0, std::abs(run.state[j]));
    run.shifted[j] = run.state[j] + step;
    predicted_observation_(run.shifted.data(), run.values.data(), tau, run.h_up.data());
    run.shifted[j] = run.state[j] - step;
    predicted_observation_(run.shifted.data(), run.values.data(), tau, run.h_down.data());
    run.shifted[j] = run.state[j];
    for (std::size_t i = 0; i < p; ++i) run.J[i * n + j] = (run.h_up[i] - run.h_down[i]) / (2 * step);
  }
  auto P = [&](std::size_t i, std::size_t j) {  // the packed upper triangle after m
    if (i > j) std::swap(i, j);
    return run.state[n + packed_diagonal(n, i) + (j - i)];
  };
  for (std::size_t i = 0; i < p; ++i)
    for (std::size_t j = 0; j <= i; ++j) {
      double spread = 0;
      for (std::size_t k = 0; k < n; ++k)
        for (std::size_t l = 0; l < n; ++l) spread += run.J[i * n + k] * P(k, l) * run.J[j * n + l];
      run.S[i * p + j] = run.S[j * p + i] = run.R[i * p + j] * interval + spread * interval * interval;
    }
  if (!cholesky(run.R.data(), p)) return run.fail("the observation noise B B^T is not positive definite " + at_time(run.t));
  if (!cholesky(run.S.data(), p)) return run.fail("the innovation covariance is not positive definite " + at_time(run.t));
  for (std::size_t i = 0; i < p; ++i) {
    run.yhat[i] *= interval;  // h dt
    run.innovation[i] = run.dy[i] - run.yhat[i];
  }
  const double square = whitened_square(run.S.data(), p, run.innovation.data(), run.normalized.data());
  run.increment_log_density +=
      -0.5 * (static_cast<double>(p) * kLogTwoPi + log_determinant(run.S.data(), p) + square);
  // Girsanov: h^T R^-1 dy - 1/2 h^T R^-1 h dt = (|L^-1 dy|^2 - |L^-1 (dy - h dt)|^2) / (2 dt), R = L L^T.
  const double dy_square = whitened_square(run.R.data(), p, run.dy.data(), run.whitened.data());
  const double innovation_square = whitened_square(run.R.data(), p, run.innovation.data(), run.whitened.data());
  if (!std::isfinite(square) || !std::isfinite(dy_square - innovation_square)) return run.fail(too_far(t));
  run.scores.add(run.normalized.data(), (dy_square - innovation_square) / (2 * interval));
  run.observed = true;
  for (std::size_t i = 0; i < p; ++i) run.dy[i] /= static_cast<double>(run.options.substeps);
  step_over(run, interval);
  return true;
}

}  // namespace pfgen_runtime
