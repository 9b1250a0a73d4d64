#pragma once
// One Monte Carlo run: the truth and its observations on a fixed grid, then any number of
// filters stepped on the same observation increments. Each run draws from its own streams,
// RandomStream(seed, run, substream::truth_noise / observation_noise), so a run is the same
// whichever thread computes it and in whatever order.
#include <cmath>
#include <cstddef>
#include <cstdint>
#include <functional>
#include <memory>
#include <optional>
#include <string>
#include <utility>
#include <vector>

#include <Eigen/Core>

#include "pfgen_runtime/filter_stepping.hpp"
#include "pfgen_runtime/filter_timing.hpp"
#include "pfgen_runtime/guards.hpp"
#include "pfgen_runtime/observation.hpp"
#include "pfgen_runtime/schemes.hpp"
#include "pfgen_runtime/time_grid.hpp"

namespace pfgen_runtime {

struct TruthRun {
  TimeGrid grid;
  std::size_t completed_steps = 0;  // == grid.steps unless the truth diverged
  Eigen::MatrixXd x;                // n x (completed_steps + 1): column k is x at grid.time(k)
  Eigen::MatrixXd dy;               // p x completed_steps: column k is y(t_{k+1}) - y(t_k)
  std::optional<DivergenceEvent> divergence;  // set when the run was stopped
  bool diverged() const { return divergence.has_value(); }
};

// Steps `scheme` from x0 over `grid` with Wiener increments from the run's truth stream, and
// generates dy from its observation stream (continuous observations; for samples dy is zero and
// draw_samples takes them after the truth) (with the observation's delay h = D dt, dy over step k
// from the path at k - D and k + 1 - D, x(s) = x(0) for s < 0; std::invalid_argument unless h is
// a whole number of steps). The run stops at the first grid time whose state
// the guard rejects (that state is not stored; the event has its time). The scheme and
// observation are used, not copied: give each thread its own.
TruthRun simulate_truth(TruthScheme& scheme, Observation& observation, const Eigen::VectorXd& x0,
                        const TimeGrid& grid, std::uint64_t seed, std::uint64_t run,
                        const DivergenceGuard& guard = DivergenceGuard());

// One grid step of a truth by `scheme` over [t, t + dt], as simulate_truth takes it: the event
// that stops the run there, with x mid-step, when the diffusion covariance lost definiteness
// (CovarianceIndefinite) or the scheme ran out of sub-steps (too_stiff); nothing otherwise.
std::optional<DivergenceEvent> take_truth_step(TruthScheme& scheme, double t, Eigen::Ref<Eigen::VectorXd> x, double dt,
                                               const Eigen::Ref<const Eigen::VectorXd>& dW);

// simulate_truth's loop into storage the caller keeps across runs (the Monte Carlo engine reuses
// one per thread, so a run allocates no path): path is n x (steps + 1), dy p x steps, both sized
// by the caller. Returns the last grid index whose state is stored in path (-1 when the guard
// rejects x0); `divergence` is the guard's event when it stopped the run. No argument checks:
// simulate_truth makes them.
std::ptrdiff_t simulate_truth_into(TruthScheme& scheme, Observation& observation, const Eigen::VectorXd& x0,
                                   const TimeGrid& grid, std::uint64_t seed, std::uint64_t run,
                                   const DivergenceGuard& guard, Eigen::MatrixXd& path,
                                   Eigen::MatrixXd& dy, std::optional<DivergenceEvent>& divergence);

// The samples of one truth path (an observation with samples): for k = 1 .. K with
// k * steps_per_sample <= last (the last stored grid index), column k - 1 of `clean` is h(t_k,
// x(t_k)) and of `noisy` the sample y_k, the noise drawn from RandomStream(seed, run,
// substream::observation_noise), r() normals per sample in sample order. Returns K. The matrices
// are p x (at least K), sized by the caller. 0 for continuous increments.
std::size_t draw_samples(Observation& observation, const TimeGrid& grid, std::size_t steps_per_sample,
                         const Eigen::MatrixXd& path, std::ptrdiff_t last, std::uint64_t seed, std::uint64_t run,
                         Eigen::MatrixXd& clean, Eigen::MatrixXd& noisy);

// A filter as plain functions over its packed state [m (n), P upper triangle, any extra state], the
// calling convention of generated headers: its initial state and its timing (filter_timing.hpp),
// GridSteps (a continuous filter's step over [t, t + dt] given dy, p entries), FixedSteps (a
// delayed filter's, once per grid step of the one grid it was generated for) or SampledSteps
// (prediction sub-steps between samples, the update at each). Copies are independent (the timing
// is cloned): each thread steps its own.
struct FilterModel {
  std::string name;
  std::size_t n = 0;
  std::size_t p = 0;
  std::function<void(double* state)> initial_state;
  std::unique_ptr<FilterTiming> timing;
  RealisabilityCheck realisability;

  FilterModel() = default;
  FilterModel(std::string name, std::size_t n, std::size_t p, std::function<void(double* state)> initial_state,
              std::unique_ptr<FilterTiming> timing)
      : name(std::move(name)), n(n), p(p), initial_state(std::move(initial_state)), timing(std::move(timing)) {}
  FilterModel(const FilterModel& other)
      : name(other.name), n(other.n), p(other.p), initial_state(other.initial_state),
        timing(other.timing ? other.timing->clone() : nullptr), realisability(other.realisability) {}
  FilterModel& operator=(const FilterModel& other) {
    if (this != &other) *this = FilterModel(other);
    return *this;
  }
  FilterModel(FilterModel&&) noexcept = default;
  FilterModel& operator=(FilterModel&&) noexcept = default;
  ~FilterModel() = default;

  // m, P and the extra state: what initial_state and the timing's steps read and write.
  std::size_t state_size() const { return filter_state_size(n) + (timing ? timing->extra_state() : 0); }
};

// std::invalid_argument unless the filter can run on `grid` (FilterTiming::check_grid: a fixed-step
// filter needs grid.dt == fixed_dt, relative tolerance 1e-9, and t0 = 0).
void check_filter_grid(const FilterModel& filter, const TimeGrid& grid);

// Adapts a generated header: for namespace F,
//   make_filter_model("optimal", F::n, F::p, &F::initial_state<double>, &F::step<double>)
// (Params default-constructed, i.e. the model file's defaults, unless given).
template <class Params>
FilterModel make_filter_model(std::string name, std::size_t n, std::size_t p, void (*initial_state)(double*),
                              void (*step)(double*, double, double, const double*, const Params&),
                              Params params = Params{}) {
  return FilterModel(std::move(name), n, p, initial_state,
                     std::make_unique<GridSteps>([step, params = std::move(params)](double* state, double t, double dt,
                                                                                    const double* dy) {
                       step(state, t, dt, dy, params);
                     }));
}

// Adapts a generated delayed filter's header (generator/src/observations/delayed/templates/cpp/delayed_filter.hpp.tmpl): for namespace F,
//   make_delayed_filter_model("delay-optimal", F::n, F::p, F::state_size, F::history_size, F::dt<double>(),
//                             &F::initial_state<double>, &F::initial_history<double>, &F::step<double>)
// The FilterModel's state is [F's state, history]; its FixedSteps' step(state, t, dt, dy) calls
// F::step(state, history, k, dy, params) with k = round(t / dt).
template <class Params>
FilterModel make_delayed_filter_model(std::string name, std::size_t n, std::size_t p, std::size_t state_size,
                                      std::size_t history_size, double dt, void (*initial_state)(double*),
                                      void (*initial_history)(const double*, double*),
                                      void (*step)(double*, double*, std::size_t, const double*, const Params&),
                                      Params params = Params{}) {
  auto initial = [initial_state, initial_history, state_size](double* state) {
    initial_state(state);
    initial_history(state, state + state_size);
  };
  auto fixed_step = [step, state_size, dt, params = std::move(params)](double* state, double t, double, const double* dy) {
    step(state, state + state_size, static_cast<std::size_t>(std::llround(t / dt)), dy, params);
  };
  return FilterModel(std::move(name), n, p, initial,
                     std::make_unique<FixedSteps>(fixed_step, dt, state_size + history_size - filter_state_size(n)));
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
  // m and P (filter_state_size(n) rows, no extra state) x (completed_steps + 1): column k at grid.time(k)
  Eigen::MatrixXd state;
  std::optional<DivergenceEvent> divergence;  // m or P non-finite or beyond its bound
  std::optional<CovarianceEvent> psd_loss;    // first time P failed the PSD check
  bool stopped = false;  // by a divergence, or by a PSD loss with stop_on_psd_loss
  std::uint64_t refined_steps = 0;  // grid steps taken in sub-steps (FilterStepper)
};

// Steps the filter from its initial state over every increment of the truth run (or until a
// guard stops it); t = 0's state is checked too, so an indefinite P0 is reported at t0.
// std::invalid_argument for a filter of samples (SampledSteps): a TruthRun holds increments only
// (run_monte_carlo runs sampled filters on the samples it draws).
FilterRun run_filter(const FilterModel& filter, const TruthRun& truth, const FilterGuardOptions& options = {});

}  // namespace pfgen_runtime
