#pragma once
// One Monte Carlo run: the truth and its observations on a fixed grid, then any number of
// filters stepped on the same observation increments. Each run draws from its own streams,
// RandomStream(seed, run, substream::truth_noise / observation_noise), so a run is the same
// whichever thread computes it and in whatever order.
#include <cstddef>
#include <cstdint>
#include <functional>
#include <optional>
#include <string>
#include <utility>

#include <Eigen/Core>

#include "pfgen_runtime/filter_stepping.hpp"
#include "pfgen_runtime/guards.hpp"
#include "pfgen_runtime/observation.hpp"
#include "pfgen_runtime/schemes.hpp"

namespace pfgen_runtime {

struct TimeGrid {
  double t0 = 0;
  double dt = 0;
  std::size_t steps = 0;
  // Grid times are t0 + k dt (no accumulated round-off).
  double time(std::size_t k) const { return t0 + static_cast<double>(k) * dt; }
  double end() const { return time(steps); }
  // round((T - t0) / dt) steps; std::invalid_argument unless dt > 0 and T > t0.
  static TimeGrid to_horizon(double t0, double T, double dt);
};

struct TruthRun {
  TimeGrid grid;
  std::size_t completed_steps = 0;  // == grid.steps unless the truth diverged
  Eigen::MatrixXd x;                // n x (completed_steps + 1): column k is x at grid.time(k)
  Eigen::MatrixXd dy;               // p x completed_steps: column k is y(t_{k+1}) - y(t_k)
  std::optional<DivergenceEvent> divergence;  // set when the run was stopped
  bool diverged() const { return divergence.has_value(); }
};

// Steps `scheme` from x0 over `grid` with Wiener increments from the run's truth stream, and
// generates dy from its observation stream. The run stops at the first grid time whose state
// the guard rejects (that state is not stored; the event has its time). The scheme and
// observation are used, not copied: give each thread its own.
TruthRun simulate_truth(TruthScheme& scheme, LinearObservation& observation, const Eigen::VectorXd& x0,
                        const TimeGrid& grid, std::uint64_t seed, std::uint64_t run,
                        const DivergenceGuard& guard = DivergenceGuard());

// simulate_truth's loop into storage the caller keeps across runs (the Monte Carlo engine reuses
// one per thread, so a run allocates no path): path is n x (steps + 1), dy p x steps, both sized
// by the caller. Returns the last grid index whose state is stored in path (-1 when the guard
// rejects x0); `divergence` is the guard's event when it stopped the run. No argument checks:
// simulate_truth makes them.
std::ptrdiff_t simulate_truth_into(TruthScheme& scheme, LinearObservation& observation, const Eigen::VectorXd& x0,
                                   const TimeGrid& grid, std::uint64_t seed, std::uint64_t run,
                                   const DivergenceGuard& guard, Eigen::MatrixXd& path,
                                   Eigen::MatrixXd& dy, std::optional<DivergenceEvent>& divergence);

// A filter as plain functions over its packed state [m (n), P upper triangle], the calling
// convention of generated headers. `step` advances the state over [t, t + dt] given dy (p).
struct FilterModel {
  std::string name;
  std::size_t n = 0;
  std::size_t p = 0;
  std::function<void(double* state)> initial_state;
  std::function<void(double* state, double t, double dt, const double* dy)> step;
  std::size_t state_size() const { return filter_state_size(n); }
};

// Adapts a generated header: for namespace F,
//   make_filter_model("optimal", F::n, F::p, &F::initial_state<double>, &F::step<double>)
// (Params default-constructed, i.e. the model file's defaults, unless given).
template <class Params>
FilterModel make_filter_model(std::string name, std::size_t n, std::size_t p, void (*initial_state)(double*),
                              void (*step)(double*, double, double, const double*, const Params&),
                              Params params = Params{}) {
  FilterModel model;
  model.name = std::move(name);
  model.n = n;
  model.p = p;
  model.initial_state = initial_state;
  model.step = [step, params = std::move(params)](double* state, double t, double dt, const double* dy) {
    step(state, t, dt, dy, params);
  };
  return model;
}

struct FilterGuardOptions {
  DivergenceGuard estimate_guard{1e8};     // on m
  DivergenceGuard covariance_guard{1e16};  // on the entries of P
  CovarianceGuard psd = CovarianceGuard();  // P symmetric positive semi-definite
  bool check_psd = true;
  bool stop_on_psd_loss = false;  // by default record the first loss and go on
  FilterStepControl stepping;     // grid steps refined where one step would be unstable
};

// The first divergence of a filter state at time t, if any: an entry of m beyond the estimate
// guard, then an entry of P beyond the covariance guard (the event's index counts into the
// whole state). run_filter and the Monte Carlo engine both stop on it.
// Inline: it runs after every filter step.
inline std::optional<DivergenceEvent> check_filter_divergence(const FilterGuardOptions& options, double t,
                                                              const double* state, std::size_t n) {
  if (auto event = options.estimate_guard.check(t, state, n)) return event;
  if (auto event = options.covariance_guard.check(t, state + n, packed_size(n))) {
    event->index += n;  // index into the whole filter state
    return event;
  }
  return std::nullopt;
}

struct CovarianceEvent {
  double t = 0;
  CovarianceCheck check;
};

struct FilterRun {
  std::string name;
  std::size_t completed_steps = 0;
  Eigen::MatrixXd state;  // state_size x (completed_steps + 1): column k at grid.time(k)
  std::optional<DivergenceEvent> divergence;  // m or P non-finite or beyond its bound
  std::optional<CovarianceEvent> psd_loss;    // first time P failed the PSD check
  bool stopped = false;  // by a divergence, or by a PSD loss with stop_on_psd_loss
  std::uint64_t refined_steps = 0;  // grid steps taken in sub-steps (FilterStepper)
};

// Steps the filter from its initial state over every increment of the truth run (or until a
// guard stops it); t = 0's state is checked too, so an indefinite P0 is reported at t0.
FilterRun run_filter(const FilterModel& filter, const TruthRun& truth, const FilterGuardOptions& options = {});

}  // namespace pfgen_runtime
