#pragma once
// The timing of a filter (simulation.hpp's FilterModel composes it with the filter's name,
// dimensions and initial state), the filter's counterpart of an observation's timing
// (observation_timing.hpp): how the filter's state goes over one step of the truth's grid. Three
// implementations:
// - GridSteps: a continuous filter, step(state, t, dt, dy) over [t, t + dt] on the step's
//   increment dy, taken in sub-steps by FilterStepper where one step would change P too fast;
//   optionally with a lanes form that steps several runs at once (the Monte Carlo engine's lanes);
// - FixedSteps: a filter of delayed observations, generated for one grid step fixed_dt: it keeps
//   more state after m and P (x* and the history of its last D grid values) and is stepped exactly
//   once per grid step, never refined (sub-steps would leave the history's grid), and only on the
//   grid t_k = k fixed_dt;
// - SampledSteps: between samples `substeps` predictions of dt = period / substeps, at each sample
//   the update (false when C P C^T + Uv Uv^T is not positive definite) (docs/theory.md §2.5).
// The Monte Carlo engine and run_filter call advance() and never ask which one it is.
#include <cstddef>
#include <cstdint>
#include <functional>
#include <memory>
#include <string>

#include "pfgen_runtime/filter_stepping.hpp"
#include "pfgen_runtime/time_grid.hpp"

namespace pfgen_runtime {

// A filter's step over [t, t + dt] given the increment dy (p entries), on its packed state [m, P's
// upper triangle, any extra state]; also the lanes form's signature, entry-major over its lanes.
using FilterStepFunction = std::function<void(double* state, double t, double dt, const double* dy)>;
// A sampled filter's prediction sub-step over [t, t + dt], and its update with a sample y at t.
using FilterPredictFunction = std::function<void(double* state, double t, double dt)>;
using FilterUpdateFunction = std::function<bool(double* state, double t, const double* y)>;

// What a filter reads of one run: the truth's grid and the run's observations, its increments
// (p x steps, column-major: column k over grid step k) or its samples (p x samples: column s at
// t0 + (s + 1) period, every steps_per_sample grid steps). A timing reads only its own kind.
struct FilterInput {
  TimeGrid grid;
  std::size_t p = 0;
  const double* dy = nullptr;
  const double* samples = nullptr;
  std::size_t steps_per_sample = 0;
  double period = 0;
};

// What one grid step of a filter did: nothing to report, a stop (the state is not stored: it is
// mid-step, or predicted up to a failed update), or a sample absorbed at the step's end.
struct FilterStepOutcome {
  enum class Stop { none, too_stiff, equations_undefined, update_failed };
  Stop stop = Stop::none;
  double t = 0;                // the stop's time, or the absorbed sample's t0 + (sample + 1) period
  std::ptrdiff_t sample = -1;  // the absorbed sample's column, -1 for none
};

class GridSteps;

class FilterTiming {
 public:
  virtual ~FilterTiming() = default;
  virtual std::unique_ptr<FilterTiming> clone() const = 0;

  // Samples (prediction and update) rather than increments: it meets only an observation of the
  // same timing.
  virtual bool takes_samples() const = 0;
  // Whether its functions are given (a step, or a prediction and an update).
  virtual bool complete() const = 0;
  // Entries of the state after m and P (a delayed filter's x* and history); 0 for the others.
  virtual std::size_t extra_state() const { return 0; }
  // Whether its grid steps may be refined (FilterStepper's sub-steps, counted in refined steps).
  virtual bool refines_steps() const { return false; }
  // std::invalid_argument, naming the filter, unless it can run on `grid`.
  virtual void check_grid(const std::string& name, const TimeGrid& grid) const;
  // Its lanes form (several runs at once), or nullptr: only a grid-stepped filter can have one,
  // since a lane whose step is not kept is refined alone through the one-run step.
  virtual const GridSteps* lanes() const { return nullptr; }
  // Grid step k of a run, [t_k, t_{k+1}]: the state from t_k to t_{k+1}. `stepper` holds the
  // caller's work arrays and counts refined steps.
  virtual FilterStepOutcome advance(FilterStepper& stepper, double* state, const FilterInput& input,
                                    std::size_t k) const = 0;
};

class GridSteps final : public FilterTiming {
 public:
  // step_lanes (optional): `lanes` states at once, entry-major (state[e * lanes + k],
  // dy[r * lanes + k]), each lane bit for bit what `step` makes of it.
  // extra_state: entries after m and P that only the step reads (a moment filter's higher moments; no lanes form
  // then), refined with the rest.
  explicit GridSteps(FilterStepFunction step, FilterStepFunction step_lanes = {}, std::size_t lanes = 0,
                     std::size_t extra_state = 0)
      : step_(std::move(step)), step_lanes_(std::move(step_lanes)), lanes_(step_lanes_ ? lanes : 0),
        extra_state_(extra_state) {}
  std::unique_ptr<FilterTiming> clone() const override { return std::make_unique<GridSteps>(*this); }
  bool takes_samples() const override { return false; }
  bool complete() const override { return static_cast<bool>(step_); }
  bool refines_steps() const override { return true; }
  std::size_t extra_state() const override { return extra_state_; }
  const GridSteps* lanes() const override { return step_lanes_ ? this : nullptr; }
  FilterStepOutcome advance(FilterStepper& stepper, double* state, const FilterInput& input,
                            std::size_t k) const override;

  const FilterStepFunction& step() const { return step_; }
  const FilterStepFunction& step_lanes() const { return step_lanes_; }
  std::size_t width() const { return lanes_; }  // the lanes form's lanes, 0 without one

 private:
  FilterStepFunction step_, step_lanes_;
  std::size_t lanes_;
  std::size_t extra_state_;
};

class FixedSteps final : public FilterTiming {
 public:
  // `step` is called once per grid step, with t = k fixed_dt; std::invalid_argument unless
  // fixed_dt is finite and > 0.
  FixedSteps(FilterStepFunction step, double fixed_dt, std::size_t extra_state);
  std::unique_ptr<FilterTiming> clone() const override { return std::make_unique<FixedSteps>(*this); }
  bool takes_samples() const override { return false; }
  bool complete() const override { return static_cast<bool>(step_); }
  std::size_t extra_state() const override { return extra_state_; }
  // The grid must be t_k = k fixed_dt: dt == fixed_dt (relative tolerance 1e-9) and t0 = 0.
  void check_grid(const std::string& name, const TimeGrid& grid) const override;
  FilterStepOutcome advance(FilterStepper& stepper, double* state, const FilterInput& input,
                            std::size_t k) const override;

  const FilterStepFunction& step() const { return step_; }
  double fixed_dt() const { return fixed_dt_; }

 private:
  FilterStepFunction step_;
  double fixed_dt_;
  std::size_t extra_state_;
};

class SampledSteps final : public FilterTiming {
 public:
  // std::invalid_argument unless substeps >= 1.
  // extra_state: entries after m and P that predict and update carry along (a moment filter's higher moments).
  SampledSteps(std::size_t substeps, FilterPredictFunction predict, FilterUpdateFunction update,
               std::size_t extra_state = 0);
  std::unique_ptr<FilterTiming> clone() const override { return std::make_unique<SampledSteps>(*this); }
  bool takes_samples() const override { return true; }
  bool complete() const override { return predict_ && update_; }
  // Grid step k lies in the period starting at t_s = t0 + s T, s = k / N (N grid steps per period),
  // and takes there the sub-steps u with k' s_f / N <= u < (k' + 1) s_f / N, k' = k mod N, s_f the
  // filter's substeps: integer arithmetic, so every period gets exactly s_f predictions of
  // T / s_f, each started at t_s + u T / s_f, whatever N. At the period's last grid step the update
  // absorbs y_{s+1}. Between sub-steps the state is held (a zero-order hold).
  FilterStepOutcome advance(FilterStepper& stepper, double* state, const FilterInput& input,
                            std::size_t k) const override;

  std::size_t extra_state() const override { return extra_state_; }
  std::size_t substeps() const { return substeps_; }
  const FilterPredictFunction& predict() const { return predict_; }
  const FilterUpdateFunction& update() const { return update_; }

 private:
  std::size_t substeps_;
  FilterPredictFunction predict_;
  FilterUpdateFunction update_;
  std::size_t extra_state_;
};

}  // namespace pfgen_runtime
