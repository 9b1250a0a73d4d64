#include "pfgen_runtime/simulation.hpp"

#include <cmath>
#include <cstdio>
#include <stdexcept>

#include "pfgen_runtime/random.hpp"

namespace pfgen_runtime {

TruthRun simulate_truth(TruthScheme& scheme, Observation& observation, const Eigen::VectorXd& x0,
                        const TimeGrid& grid, std::uint64_t seed, std::uint64_t run, const DivergenceGuard& guard) {
  const SdeSystem& system = scheme.system();
  if (x0.size() != static_cast<Eigen::Index>(system.n) || observation.n() != system.n)
    throw std::invalid_argument("simulate_truth: x0 and the observation must have the system's n states");
  if (!(grid.dt > 0)) throw std::invalid_argument("simulate_truth: dt must be positive");

  TruthRun result;
  result.grid = grid;
  result.x.resize(static_cast<Eigen::Index>(system.n), static_cast<Eigen::Index>(grid.steps + 1));
  result.dy.setZero(static_cast<Eigen::Index>(observation.p()), static_cast<Eigen::Index>(grid.steps));
  const std::ptrdiff_t last =
      simulate_truth_into(scheme, observation, x0, grid, seed, run, guard, result.x, result.dy, result.divergence);
  result.completed_steps = last > 0 ? static_cast<std::size_t>(last) : 0;
  // An invalid x0 leaves no state on record.
  result.x.conservativeResize(Eigen::NoChange, static_cast<Eigen::Index>(last + 1));
  result.dy.conservativeResize(Eigen::NoChange, static_cast<Eigen::Index>(result.completed_steps));
  return result;
}

std::optional<DivergenceEvent> take_truth_step(TruthScheme& scheme, double t, Eigen::Ref<Eigen::VectorXd> x, double dt,
                                               const Eigen::Ref<const Eigen::VectorXd>& dW) {
  try {
    scheme.step(t, x, dt, dW);
  } catch (const CovarianceIndefinite& e) {
    return DivergenceEvent{e.t, 0, e.eigenvalue, DivergenceKind::covariance_indefinite};
  }
  if (scheme.last_step_incomplete()) return DivergenceEvent{t, 0, 0.0, DivergenceKind::too_stiff};
  return std::nullopt;
}

std::ptrdiff_t simulate_truth_into(TruthScheme& scheme, Observation& observation, const Eigen::VectorXd& x0,
                                   const TimeGrid& grid, std::uint64_t seed, std::uint64_t run,
                                   const DivergenceGuard& guard, Eigen::MatrixXd& path,
                                   Eigen::MatrixXd& dy, std::optional<DivergenceEvent>& divergence) {
  scheme.start_run(seed, run);
  scheme.set_escape_bound(guard.bound());
  RandomStream truth_noise(seed, run, substream::truth_noise);
  RandomStream observation_noise(seed, run, substream::observation_noise);
  WienerIncrements truth_increments(truth_noise, scheme.system().q, grid.dt);
  WienerIncrements observation_increments(observation_noise, observation.increment_noise(), grid.dt);
  Eigen::VectorXd x = x0;
  using Increment = Eigen::Map<const Eigen::VectorXd>;
  // The delay in grid steps: dy over step k reads the path at k - D and k + 1 - D (stored before
  // the increment is taken), clamped at 0 for the pre-history x(s) = x(0), s < 0.
  const std::size_t D = observation.delay_steps(grid.dt);

  divergence = guard.check(grid.t0, x);
  if (divergence) return -1;
  path.col(0) = x;
  for (std::size_t k = 0; k < grid.steps; ++k) {
    const double t = grid.time(k);
    const Increment dW(truth_increments.next(), static_cast<Eigen::Index>(truth_increments.size()));
    const Increment dW2(observation_increments.next(), static_cast<Eigen::Index>(observation_increments.size()));
    if (auto event = take_truth_step(scheme, t, x, grid.dt, dW)) {
      divergence = event;
      return static_cast<std::ptrdiff_t>(k);
    }
    if (auto event = guard.check(grid.time(k + 1), x)) {
      divergence = event;
      return static_cast<std::ptrdiff_t>(k);
    }
    const auto column = static_cast<Eigen::Index>(k);
    path.col(column + 1) = x;
    const auto start = static_cast<Eigen::Index>(k >= D ? k - D : 0);
    const auto end = static_cast<Eigen::Index>(k + 1 >= D ? k + 1 - D : 0);
    observation.increment(t, grid.dt, path.col(start), path.col(end), dW2, dy.col(column));
  }
  return static_cast<std::ptrdiff_t>(grid.steps);
}

std::size_t draw_samples(Observation& observation, const TimeGrid& grid, std::size_t steps_per_sample,
                         const Eigen::MatrixXd& path, std::ptrdiff_t last, std::uint64_t seed, std::uint64_t run,
                         Eigen::MatrixXd& clean, Eigen::MatrixXd& noisy) {
  if (last < 0 || !observation.sampled()) return 0;  // continuous increments: no samples
  const std::size_t samples = static_cast<std::size_t>(last) / steps_per_sample;
  RandomStream noise(seed, run, substream::observation_noise);
  Eigen::VectorXd v(static_cast<Eigen::Index>(observation.r()));
  for (std::size_t k = 1; k <= samples; ++k) {
    for (Eigen::Index j = 0; j < v.size(); ++j) v[j] = noise.normal();
    const auto column = static_cast<Eigen::Index>(k - 1);
    // t_k = t0 + k T exactly, not the grid's t0 + (k N) dt (the same point up to rounding).
    observation.sample(grid.t0 + static_cast<double>(k) * observation.period(),
                       path.col(static_cast<Eigen::Index>(k * steps_per_sample)).data(), v.data(),
                       clean.col(column).data(), noisy.col(column).data());
  }
  return samples;
}

void check_filter_grid(const FilterModel& filter, const TimeGrid& grid) {
  if (filter.timing) filter.timing->check_grid(filter.name, grid);
}

FilterRun run_filter(const FilterModel& filter, const TruthRun& truth, const FilterGuardOptions& options) {
  // The truth run holds increments: a filter of samples has nothing to absorb.
  if (!filter.timing || !filter.timing->complete() || filter.timing->takes_samples() || !filter.initial_state ||
      filter.n == 0)
    throw std::invalid_argument("run_filter: filter '" + filter.name + "' lacks n, initial_state or step");
  if (truth.dy.rows() != static_cast<Eigen::Index>(filter.p))
    throw std::invalid_argument("run_filter: filter '" + filter.name + "' expects p observations");
  check_filter_grid(filter, truth.grid);
  const TimeGrid& grid = truth.grid;

  FilterRun result;
  result.name = filter.name;
  // Only m and P are kept: a delayed filter's history (extra state) would be D n values a step.
  const auto recorded = static_cast<Eigen::Index>(filter_state_size(filter.n));
  result.state.resize(recorded, static_cast<Eigen::Index>(truth.completed_steps + 1));
  Eigen::VectorXd state(filter.state_size());
  filter.initial_state(state.data());

  // True while the run may go on. Events are written only when they happen.
  std::vector<double> margins;
  auto guard = [&](double t) {
    if (auto event = check_filter_divergence(options, t, state.data(), filter.n)) {
      result.divergence = event;
      return false;
    }
    if (auto event = check_realisability(filter.realisability, t, state.data(), margins)) {
      result.divergence = event;
      return false;
    }
    if (options.check_psd && !result.psd_loss) {
      const CovarianceCheck check = options.psd.check_filter_state(state.data(), filter.n);
      if (!check.ok) {
        result.psd_loss = CovarianceEvent{t, check};
        if (options.stop_on_psd_loss) return false;
      }
    }
    return true;
  };

  FilterStepper stepper(filter.n, filter.p, options.stepping, filter.state_size() - filter_state_size(filter.n));
  bool going = guard(grid.t0);
  const bool initial_ok = !result.divergence;  // a PSD loss at t0 keeps P0 on record
  if (initial_ok) result.state.col(0) = state.head(recorded);
  const FilterInput input{grid, filter.p, truth.dy.data()};
  for (std::size_t k = 0; going && k < truth.completed_steps; ++k) {
    const FilterStepOutcome outcome = filter.timing->advance(stepper, state.data(), input, k);
    if (outcome.stop != FilterStepOutcome::Stop::none) {  // given up mid-step
      const bool defined = outcome.stop == FilterStepOutcome::Stop::too_stiff;
      result.divergence = DivergenceEvent{outcome.t, 0, 0.0,
                                          defined ? DivergenceKind::too_stiff : DivergenceKind::equations_undefined};
      going = false;
      break;
    }
    going = guard(grid.time(k + 1));
    if (result.divergence) break;  // a diverged state is not stored
    result.state.col(static_cast<Eigen::Index>(k + 1)) = state.head(recorded);
    result.completed_steps = k + 1;
  }
  result.stopped = !going;
  result.refined_steps = stepper.refined_steps();
  result.state.conservativeResize(Eigen::NoChange,
                                  initial_ok ? static_cast<Eigen::Index>(result.completed_steps + 1) : 0);
  return result;
}

}  // namespace pfgen_runtime
