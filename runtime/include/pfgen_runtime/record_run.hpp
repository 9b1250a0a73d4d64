#pragma once
// One filter run over a record, row by row, at given parameter values: the filter state after each
// row, the row's innovation and its normalised form, and the scores over the record so far.
//
// What a row holds and how the filter goes to it is the filter's timing (record_timing.hpp):
// samples, or increments (a delayed filter's on its own grid). For continuous observations two
// log-likelihoods are kept: the filter's (Girsanov) one, sum h^T R^-1 dy - 1/2 h^T R^-1 h dt, the
// log-density of the record relative to dy = B dW2 (no signal), and the discrete increments'
// Gaussian log-density, sum log N(dy; h dt, S) with S = R dt + E[J_h] P E[J_h]^T dt^2 (the
// innovation's covariance over the interval to second order in dt). The innovation is dy - h dt,
// normalised by S^(1/2). Delayed observations have h = A0 + A m(t - h) from the filter's history
// (which the current m does not move, so S is R dt).
#include <cstddef>
#include <string>
#include <vector>

#include "pfgen_runtime/innovation_scores.hpp"
#include "pfgen_runtime/record_filter.hpp"

namespace pfgen_runtime {

class RecordRun {
 public:
  // The filter from its initial state (the model's m0, P0, or `initial` when not empty: m, P's
  // upper triangle, then a moment filter's higher moments; std::invalid_argument for a filter that
  // keeps a history, a delayed one, which starts from the model's) at t0, at the parameter values
  // `values` (the plugin's order).
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
  double time() const { return progress_.t; }
  const std::vector<double>& state() const { return progress_.state; }  // m, P's upper triangle, then any extra state
  bool observed() const { return progress_.observed; }  // whether the last row had an observation
  const std::vector<double>& predicted() const { return progress_.yhat; }  // yhat, or h dt
  const std::vector<double>& innovation() const { return progress_.innovation; }
  const std::vector<double>& normalized() const { return progress_.normalized; }
  const InnovationScores& scores() const { return progress_.scores; }
  // Continuous data: the increments' Gaussian log-density (the discrete record's log-likelihood).
  double increment_log_density() const { return progress_.increment_log_density; }
  // The log-likelihood a fit maximises (RecordTiming::log_likelihood): the samples' scores, or the
  // increments' Gaussian log-density.
  double log_likelihood() const { return filter_.timing->log_likelihood(progress_); }
  const std::string& failure() const { return progress_.failure; }
  bool failed() const { return !progress_.failure.empty(); }

 private:
  bool realisable();  // false, failing the run, where a moment filter's margin is not positive

  const RecordFilter& filter_;
  RecordProgress progress_;
  std::vector<double> margins_;
  bool begun_ = false;  // a row has been given
};

}  // namespace pfgen_runtime
