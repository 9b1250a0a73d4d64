#pragma once
// One filter run over a record, row by row, at given parameter values: the filter state after each
// row, the row's innovation and its normalised form, and the scores over the record so far.
//
// Sampled observations: the filter predicts from its time to the row's time (sub-steps in
// proportion to the model's: ceil(interval x substeps / period) of them) and absorbs the row's
// sample; a row whose observation is missing (every entry NaN) is predicted to only. The term of
// the log-likelihood is log N(y; yhat, S) with the predicted sample yhat and S before the update.
//
// Continuous observations: the row holds dy over (previous time, t], or the rate dy/dt there; the
// filter steps over the interval in `substeps` equal steps (the increment split evenly). Two
// log-likelihoods are kept: the filter's (Girsanov) one, sum h^T R^-1 dy - 1/2 h^T R^-1 h dt, the
// log-density of the record relative to dy = B dW2 (no signal), and the discrete increments'
// Gaussian log-density, sum log N(dy; h dt, S) with S = R dt + E[J_h] P E[J_h]^T dt^2 (the
// innovation's covariance over the interval to second order in dt). The innovation is dy - h dt,
// normalised by S^(1/2).
//
// Delayed observations (a filter with a fixed grid step): the same, with h = A0 + A m(t - h) from
// the filter's history (which the current m does not move, so S is R dt); the rows must be
// substeps x fixed_dt apart (relative 1e-9), and the filter steps on its own grid tau_k = k
// fixed_dt, counted from the prior (its pre-history: m = m0 before).
#include <cstddef>
#include <string>
#include <vector>

#include "pfgen_runtime/innovation_scores.hpp"
#include "pfgen_runtime/record_filter.hpp"

namespace pfgen_runtime {

enum class ContinuousData { Increments, Rates };

struct RecordRunOptions {
  ContinuousData continuous = ContinuousData::Increments;
  std::size_t substeps = 1;  // continuous data: filter steps per data interval
  std::size_t max_lags = 10;  // Ljung-Box
};

class RecordRun {
 public:
  // The filter from its initial state (the model's m0, P0, or `initial` when not empty: m then
  // P's upper triangle; std::invalid_argument for a filter with extra state, which starts from
  // the model's) at t0, at the parameter values `values` (the plugin's order).
  RecordRun(const RecordFilter& filter, std::vector<double> values, double t0, const RecordRunOptions& options,
            const std::vector<double>& initial = {});
  // To the row at t > time() (or t == time() for the first row: a sample there updates the prior,
  // a continuous row there only marks where the record starts) with its observation (p entries;
  // NaN: missing). false when the filter failed there (failure() says
  // how); the run then stays failed. std::invalid_argument for a sampled row missing only some
  // entries or more than 10^7 prediction sub-steps after the last, continuous data with a gap, or
  // a fixed-grid filter's row other than substeps x fixed_dt after the last.
  bool advance(double t, const double* observation);

  const std::string& filter_name() const { return filter_.name; }
  double time() const { return t_; }
  const std::vector<double>& state() const { return state_; }  // m, P's upper triangle, then any extra state
  bool observed() const { return observed_; }  // whether the last row had an observation
  const std::vector<double>& predicted() const { return yhat_; }  // yhat, or h dt
  const std::vector<double>& innovation() const { return innovation_; }
  const std::vector<double>& normalized() const { return normalized_; }
  const InnovationScores& scores() const { return scores_; }
  // Continuous data: the increments' Gaussian log-density (the discrete record's log-likelihood).
  double increment_log_density() const { return increment_log_density_; }
  const std::string& failure() const { return failure_; }
  bool failed() const { return !failure_.empty(); }

 private:
  bool fail(const std::string& why);
  bool sample(double t, const double* y);
  bool increment(double t, const double* observation);
  bool state_finite() const;
  const RecordFilter& filter_;
  std::vector<double> values_;
  RecordRunOptions options_;
  double t_;
  std::vector<double> state_, yhat_, innovation_, normalized_, S_, B_, dy_, whitened_, R_, J_, h_up_, h_down_, shifted_;
  InnovationScores scores_;
  double increment_log_density_ = 0;
  std::size_t steps_ = 0;  // a fixed-grid filter's steps so far: its grid index
  bool observed_ = false;
  bool begun_ = false;  // a row has been given
  std::string failure_;
};

}  // namespace pfgen_runtime
