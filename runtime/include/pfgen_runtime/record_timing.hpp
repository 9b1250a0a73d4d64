#pragma once
// How a record's rows reach a compiled filter (record_filter.hpp's RecordFilter holds one, built
// once by SimulationPlugin::record_filters(); RecordRun calls it for every row): the record's
// counterpart of a simulated filter's timing (filter_timing.hpp). Two implementations:
// - RecordSamples: a row is a sample y at t. The filter predicts from its time to t in sub-steps
//   in proportion to the model's (ceil(interval x substeps / period) of them) and absorbs y; a
//   row whose observation is missing (every entry NaN) is predicted to only. The score is
//   log N(y; yhat, S) with the predicted sample yhat and S before the update. A row at the
//   filter's own time updates it there.
// - RecordIncrements (RecordFixedIncrements for a delayed filter): a row holds dy over (previous time, t], or the rate dy/dt there. The filter
//   steps over the interval in `substeps` equal steps (the increment split evenly); the scores are
//   the filter's (Girsanov) log-likelihood and the increments' Gaussian log-density (record_run.hpp).
//   The first row at the prior's time only marks where the record starts. With a fixed grid step
//   (delayed observations: the filter keeps a history, extra state after m and P) the rows must be
//   substeps x fixed_dt apart and the filter steps on its own grid tau_k = k fixed_dt from the prior.
// RecordRun never asks which one it has.
#include <cstddef>
#include <string>
#include <vector>

#include "pfgen_runtime/innovation_scores.hpp"

namespace pfgen_runtime {

enum class ContinuousData { Increments, Rates };

// The most filter steps per data interval of continuous data (--substeps).
inline constexpr std::size_t kMaxRowSubsteps = 1000000;

struct RecordRunOptions {
  ContinuousData continuous = ContinuousData::Increments;
  std::size_t substeps = 1;  // continuous data: filter steps per data interval
  std::size_t max_lags = 10;  // Ljung-Box
};

// One filter's run over a record so far (RecordRun keeps it; a timing's absorb() moves it on by a
// row): the filter's state and time, the last row's prediction and innovation, the scores, and the
// work arrays a row needs (sized once, for p observations, n states, r noise columns).
struct RecordProgress {
  RecordProgress(std::size_t n, std::size_t p, std::size_t r, std::size_t state_size, std::vector<double> values,
                 double t0, const RecordRunOptions& options);
  std::size_t n, p, r;
  std::vector<double> values;  // the parameter values, in the plugin's order
  RecordRunOptions options;
  double t;                   // the filter's time
  std::vector<double> state;  // m, P's upper triangle, then any extra state
  std::vector<double> yhat, innovation, normalized;
  InnovationScores scores;
  double increment_log_density = 0;
  std::size_t steps = 0;  // a fixed-grid filter's steps so far: its grid index
  bool observed = false;
  std::string failure;
  std::vector<double> S, B, dy, whitened, R, J, h_up, h_down, shifted;  // work arrays

  bool fail(const std::string& why) {
    failure = why;
    return false;
  }
  bool state_finite() const;
  // The end of a row at t: the filter's time is t, and a filter that absorbed it (ok) fails when
  // its state is no longer finite. Returns whether the run goes on.
  bool finish_row(double t, bool ok);
};

class RecordTiming {
 public:
  virtual ~RecordTiming() = default;
  // Entries of the state after m and P (a delayed filter's x* and history, a moment filter's higher
  // moments), 0 for the others.
  virtual std::size_t extra_state() const { return 0; }
  // Whether they hold a history begun from the model's m0 (a delayed filter's), so that the state cannot
  // start from another m; a moment filter's central moments depend on P0 only.
  virtual bool keeps_history() const { return false; }
  // The row at t with its observation (p entries, NaN: missing); `first` for the record's first
  // row. false when the filter failed there (progress.failure says how).
  // std::invalid_argument for a row this timing cannot take (out of order, a partly missing
  // sample, a gap of more than 10^7 sub-steps, a missing increment, a fixed-grid filter's row off
  // its spacing).
  virtual bool absorb(RecordProgress& progress, double t, const double* observation, bool first) const = 0;
  // The log-likelihood of the record so far, which a fit maximises: the samples' (the scores'),
  // or the increments' Gaussian log-density (the discrete record's).
  virtual double log_likelihood(const RecordProgress& progress) const = 0;
  // What a failure's message may add about the steps the rows take, since a step too long for a
  // moment filter can leave its realisable set: continuous data's --substeps; nothing for samples,
  // whose sub-steps are the model's.
  virtual std::string step_hint(const RecordProgress&) const { return ""; }
};

class RecordSamples final : public RecordTiming {
 public:
  using Predict = void (*)(double* state, const double* values, double t, double dt);
  using Update = int (*)(double* state, const double* values, double t, const double* y);
  using Innovation = void (*)(const double* state, const double* values, double t, double* yhat, double* S);
  // One prediction sub-step, the update with a sample y at t (0 when S is not positive definite),
  // and the predicted sample yhat with its covariance S (p x p) at t; `substeps` per `period`.
  // extra_state: entries after m and P that predict and update carry along (a moment filter's higher moments).
  RecordSamples(std::size_t substeps, double period, Predict predict, Update update, Innovation innovation,
                std::size_t extra_state = 0)
      : substeps_(substeps), period_(period), predict_(predict), update_(update), innovation_(innovation),
        extra_state_(extra_state) {}
  std::size_t extra_state() const override { return extra_state_; }
  bool absorb(RecordProgress& progress, double t, const double* observation, bool first) const override;
  double log_likelihood(const RecordProgress& progress) const override;

 private:
  bool predict_and_update(RecordProgress& progress, double t, const double* y, bool first) const;
  std::size_t substeps_;
  double period_;
  Predict predict_;
  Update update_;
  Innovation innovation_;
  std::size_t extra_state_;
};

class RecordIncrements : public RecordTiming {
 public:
  using Step = void (*)(double* state, const double* values, double t, double dt, const double* dy);
  using Rate = void (*)(const double* state, const double* values, double t, double* h);
  using Noise = void (*)(const double* values, double t, double* B);
  // One step over [t, t + dt] with the increment dy, the predicted rate h of a state, and B at t
  // (p x r, row-major).
  // extra_state: entries after m and P that only the step reads (a moment filter's higher moments).
  RecordIncrements(Step step, Rate predicted_observation, Noise observation_noise, std::size_t extra_state = 0)
      : step_(step), predicted_observation_(predicted_observation), observation_noise_(observation_noise),
        extra_state_(extra_state) {}
  std::size_t extra_state() const override { return extra_state_; }
  bool absorb(RecordProgress& progress, double t, const double* observation, bool first) const override;
  double log_likelihood(const RecordProgress& progress) const override { return progress.increment_log_density; }
  std::string step_hint(const RecordProgress& progress) const override;

 protected:
  // Where the filter's steps fall over the row's interval from progress.t to t: its length, the
  // time h and the rate's Jacobian are taken at, and the `substeps` steps over it (dy in
  // progress.dy, already divided among them). Any times here; RecordFixedIncrements' own grid.
  virtual double interval(const RecordProgress& progress, double t) const;
  virtual double rate_time(const RecordProgress& progress) const;
  virtual void step_over(RecordProgress& progress, double interval) const;
  Step step_;

 private:
  bool score_and_step(RecordProgress& progress, double t, const double* observation) const;
  Rate predicted_observation_;
  Noise observation_noise_;
  std::size_t extra_state_;
};

// A delayed filter's increments: its only step is fixed_dt, on its own grid tau_k = k fixed_dt
// counted from the prior (its pre-history: m = m0 before), with extra_state entries after m and P
// (x* and its history). The rows must be substeps x fixed_dt apart (relative 1e-9).
class RecordFixedIncrements final : public RecordIncrements {
 public:
  RecordFixedIncrements(Step step, Rate predicted_observation, Noise observation_noise, double fixed_dt,
                        std::size_t extra_state)
      : RecordIncrements(step, predicted_observation, observation_noise), fixed_dt_(fixed_dt),
        extra_state_(extra_state) {}
  std::size_t extra_state() const override { return extra_state_; }
  bool keeps_history() const override { return true; }

 protected:
  double interval(const RecordProgress& progress, double t) const override;
  double rate_time(const RecordProgress& progress) const override;
  void step_over(RecordProgress& progress, double interval) const override;

 private:
  double fixed_dt_;
  std::size_t extra_state_;
};

}  // namespace pfgen_runtime
