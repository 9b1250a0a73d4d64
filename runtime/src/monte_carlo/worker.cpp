#include "worker.hpp"

#include <algorithm>
#include <cmath>

#include "clock.hpp"
#include "pfgen_runtime/gaussian_draw.hpp"
#include "pfgen_runtime/statistics.hpp"

namespace pfgen_runtime::monte_carlo_detail {
namespace {

// The most entries after m and P that a filter's state has (a moment filter's higher moments).
std::size_t largest_extra_state(const std::vector<FilterModel>& filters) {
  std::size_t largest = 0;
  for (const FilterModel& filter : filters) largest = std::max(largest, filter.state_size() - filter_state_size(filter.n));
  return largest;
}

}  // namespace

Worker::Worker(const TruthScheme& scheme, const Observation& observation, const std::vector<FilterModel>& filters, const Eigen::VectorXd& x0, const Plan& plan,
               const MonteCarloOptions& options, std::size_t batch)
    : scheme_(scheme.clone()), observation_(observation), filters_(filters), plan_(plan), options_(options),
      lanes_(std::max<std::size_t>(batch, 1)), passes_(lanes_.size()),
      stepper_(plan.n, plan.p, options.filter_guards.stepping, largest_extra_state(filters)) {
  filter_seconds.assign(filters.size(), 0.0);
  filter_cpu_seconds.assign(filters.size(), 0.0);
  filter_steps.assign(filters.size(), 0);
  filter_samples.assign(filters.size(), 0);
  const auto n = static_cast<Eigen::Index>(plan.n), points = static_cast<Eigen::Index>(plan.grid.steps + 1);
  for (RunBuffers& lane : lanes_) {
    lane.x0 = x0;
    lane.path.resize(n, points);
    lane.dy.resize(static_cast<Eigen::Index>(observation.p()), points - 1);
  }
  for (PassSums& pass : passes_) {
    pass.sums.resize((1 + plan.windows.size()) * plan.n);
    pass.error.resize(plan.n);
    pass.distance_sums.resize(plan.n);
  }
  if (observation.sampled()) {  // the samples' buffers
    steps_per_sample_ = observation.steps_per_sample(plan.grid.dt);
    const auto p = static_cast<Eigen::Index>(observation.p());
    const auto samples = static_cast<Eigen::Index>(plan.grid.steps / steps_per_sample_);
    for (RunBuffers& lane : lanes_) {
      lane.clean.resize(p, samples);
      lane.noisy.resize(p, samples);
    }
    estimate_.assign(observation.p(), 0.0);
    sample_sums_size_ = 4 * observation.p();
  }
  std::size_t largest = 0;
  for (const FilterModel& filter : filters_) largest = std::max(largest, filter.state_size());
  state_.resize(largest);
  nees_work_.resize(plan.n * (plan.n + 1) / 2 + plan.n);
  lane_before_.resize(largest);
  lane_increment_.resize(plan.p);
  active_.reserve(plan.windows.size());
  if (options.criterion) {
    criterion_ = true;
    weight_ = options.criterion->weight;
    weighted_ = weight_.size() > 0;
  }
  if (options.initial_prior)
    prior_root_ = covariance_square_root(options.initial_prior->covariance, "monte carlo: the initial prior's covariance");
  // The lanes' width: that of the first continuous filter with a lanes form of a width the engine
  // steps (steps_in_lanes); filters of another width go one run at a time.
  for (const FilterModel& filter : filters_)
    if (width_ == 0) width_ = lane_width(filter);
  for (const FilterModel& filter : filters_) in_lanes_.push_back(width_ > 0 && lane_width(filter) == width_);
  lanes_only_ = width_ >= 2 && !options.reference &&
                std::all_of(in_lanes_.begin(), in_lanes_.end(), [](bool in) { return in; });
  if (options.reference) {
    const double bound = options.truth_guard.bound();
    reference_ = std::make_unique<ParticleReference>(scheme, observation, *options.reference, bound);
    for (RunBuffers& lane : lanes_) {
      lane.reference_mean.resize(n, points);
      lane.second_mean.resize(n, points);
    }
  }
}

void Worker::run(std::size_t first, std::size_t count, RunResult* out) {
  Clock::time_point start = Clock::now();
  double cpu_start = thread_cpu_seconds();
  truths_interleaved_ = count >= 2 && observation_.delay() == 0;
  if (truths_interleaved_) {
    simulate_truths_lanes(first, count, out);
  } else {
    for (std::size_t k = 0; k < count; ++k) simulate_truth(first + k, k, out[k]);
  }
  truth_seconds += seconds_since(start);
  truth_cpu_seconds += thread_cpu_seconds() - cpu_start;
  if (reference_) {
    start = Clock::now();
    cpu_start = thread_cpu_seconds();
    for (std::size_t k = 0; k < count; ++k)
      run_reference(first + k, first + k == options_.shown_run, lanes_[k], out[k]);
    reference_seconds += seconds_since(start);
    reference_cpu_seconds += thread_cpu_seconds() - cpu_start;
  }
  for (std::size_t k = 0; k < count; ++k) out[k].filters.resize(filters_.size());
  // The filters with a lanes form of width_ take the runs in groups of width_ (the last one
  // partly filled), on the truths' interleaved copy; the others, and the runs of a batch whose
  // truths went one at a time, one run at a time.
  const bool grouped = width_ >= 2 && truths_interleaved_;
  for (std::size_t g = 0; g < count; g += grouped ? width_ : count) {
    const std::size_t size = grouped ? std::min(width_, count - g) : count;
    group_ = g;
    for (std::size_t f = 0; f < filters_.size(); ++f) {
      start = Clock::now();
      cpu_start = thread_cpu_seconds();
      if (grouped && in_lanes_[f]) {
        step_filter_lanes(f, first + g, size, out + g);
      } else {
        for (std::size_t k = g; k < g + size; ++k)
          step_filter(f, first + k == options_.shown_run, out[k], lanes_[k], out[k].filters[f]);
      }
      filter_seconds[f] += seconds_since(start);
      filter_cpu_seconds[f] += thread_cpu_seconds() - cpu_start;
    }
  }
}

void Worker::draw_initial_state(std::size_t run, RunBuffers& lane) const {
  if (!options_.initial_prior) return;  // lane.x0 keeps the fixed x0
  RandomStream initial(options_.seed, run, substream::initial_state);
  lane.x0 = draw_gaussian(options_.initial_prior->mean, prior_root_, initial);
}

// simulate_truth's loop (simulation.cpp) into the thread's buffers, so the same bits.
void Worker::simulate_truth(std::size_t run, std::size_t k, RunResult& out) {
  RunBuffers& lane = lanes_[k];
  std::optional<DivergenceEvent> divergence;
  draw_initial_state(run, lane);
  out.truth_last = simulate_truth_into(*scheme_, observation_, lane.x0, plan_.grid, options_.seed, run,
                                       options_.truth_guard, lane.path, lane.dy, divergence);
  finish_truth(run, k, out, divergence);
}

double Worker::truth_at(std::size_t k, std::size_t j, std::size_t i) const {
  if (truths_interleaved_ && lanes_only_)
    return lane_path_[k / width_ * group_path_size() + (j * plan_.n + i) * width_ + k % width_];
  return lanes_[k].path(static_cast<Eigen::Index>(i), static_cast<Eigen::Index>(j));
}

void Worker::finish_truth(std::size_t run, std::size_t k, RunResult& out,
                          const std::optional<DivergenceEvent>& divergence) {
  RunBuffers& lane = lanes_[k];
  if (divergence) {
    out.truth_diverged = true;
    out.truth_divergence_t = divergence->t;
    out.truth_covariance_indefinite = divergence->kind == DivergenceKind::covariance_indefinite;
  }
  // Steps taken: the stored ones, and the one the guard stopped (none when x0 was rejected).
  truth_steps += static_cast<std::uint64_t>(std::max<std::ptrdiff_t>(out.truth_last, 0)) +
                 (divergence && out.truth_last >= 0 ? 1 : 0);
  const std::size_t n = plan_.n;
  lane.samples = draw_samples(observation_, plan_.grid, steps_per_sample_, lane.path, out.truth_last, options_.seed,
                              run, lane.clean, lane.noisy);
  out.truth_record.assign(plan_.records.size() * n, nan);
  for (std::size_t r = 0; r < plan_.records.size(); ++r)
    if (static_cast<std::ptrdiff_t>(plan_.records[r]) <= out.truth_last)
      for (std::size_t i = 0; i < n; ++i) out.truth_record[r * n + i] = truth_at(k, plan_.records[r], i);
  out.truth_report.assign(plan_.reports.size() * n, nan);
  for (std::size_t q = 0; q < plan_.reports.size(); ++q)
    if (static_cast<std::ptrdiff_t>(plan_.reports[q]) <= out.truth_last)
      for (std::size_t i = 0; i < n; ++i) out.truth_report[q * n + i] = truth_at(k, plan_.reports[q], i);
}

// The particle reference on the run's increments (or samples), and its own error x - m_ref.
void Worker::run_reference(std::size_t run, bool shown, RunBuffers& lane, RunResult& out) {
  const std::size_t n = plan_.n, steps = plan_.grid.steps;
  const ObservedRun observed{&lane.dy, &lane.noisy, lane.samples};
  const ParticleReferenceRun outcome =
      reference_->run(plan_.grid, observed, out.truth_last, options_.seed, run, lane.reference_mean);
  // The second set, on streams of its own, only for the spread of the two means.
  const ParticleReferenceRun second =
      reference_->run(plan_.grid, observed, out.truth_last, options_.seed, run, lane.second_mean, 1);
  lane.reference_last = outcome.last;
  reference_steps += outcome.particle_steps + second.particle_steps;
  ReferenceRunResult& reference = out.reference;
  reference.last = outcome.last;
  reference.stopped = outcome.stopped;
  if (outcome.stopped) reference.stop_t = outcome.stop_t;
  reference.resamplings = outcome.resamplings;
  reference.mean_square.assign(n, nan);
  reference.spread_square.assign(n, nan);
  if (outcome.last == static_cast<std::ptrdiff_t>(steps) && second.last == outcome.last)
    for (std::size_t i = 0; i < n; ++i) {
      double sum = 0;
      for (std::size_t j = 0; j <= steps; ++j) {
        const auto row = static_cast<Eigen::Index>(i), column = static_cast<Eigen::Index>(j);
        const double d = lane.reference_mean(row, column) - lane.second_mean(row, column);
        sum += d * d;
      }
      reference.spread_square[i] = sum / static_cast<double>(steps + 1);
    }
  reference.error_record.assign(plan_.records.size() * n, nan);
  if (shown) reference.m_record.assign(plan_.records.size() * n, nan);
  if (outcome.last == static_cast<std::ptrdiff_t>(steps)) {
    for (std::size_t i = 0; i < n; ++i) {
      double sum = 0;
      for (std::size_t j = 0; j <= steps; ++j) {
        const double e = lane.path(static_cast<Eigen::Index>(i), static_cast<Eigen::Index>(j)) -
                         lane.reference_mean(static_cast<Eigen::Index>(i), static_cast<Eigen::Index>(j));
        sum += e * e;
      }
      reference.mean_square[i] = sum / static_cast<double>(steps + 1);
    }
  }
  for (std::size_t r = 0; r < plan_.records.size(); ++r) {
    const auto j = static_cast<Eigen::Index>(plan_.records[r]);
    if (j > outcome.last) break;  // records are in grid order
    for (std::size_t i = 0; i < n; ++i) {
      const auto row = static_cast<Eigen::Index>(i);
      reference.error_record[r * n + i] = lane.path(row, j) - lane.reference_mean(row, j);
      if (shown) reference.m_record[r * n + i] = lane.reference_mean(row, j);
    }
  }
}

// A filter pass's results, sized and NaN until reached, and its sums zeroed.
bool Worker::start_pass(bool shown, const RunResult& run, FilterRunResult& out, PassSums& pass) const {
  const std::size_t n = plan_.n;
  out.mean_square.assign(pass.sums.size(), nan);
  out.report_error.assign(plan_.reports.size() * n, nan);
  out.peak.assign(n, 0.0);
  out.error_record.assign(plan_.records.size() * n, nan);
  if (shown) {
    out.m_record.assign(plan_.records.size() * n, nan);
    out.P_record.assign(plan_.records.size() * n, nan);
  }
  if (reference_) {
    out.reference_square.assign(n, nan);
    out.reference_record.assign(plan_.records.size() * n, nan);
  }
  out.nees_record.assign(plan_.records.size(), nan);
  out.nees.assign(plan_.reports.size() + 1, nan);
  out.sample_sums.assign(sample_sums_size_, 0.0);
  std::fill(pass.sums.begin(), pass.sums.end(), 0.0);
  std::fill(pass.distance_sums.begin(), pass.distance_sums.end(), 0.0);
  return run.truth_last >= 0;  // else no truth to compare with
}

// True while the run may go on, as in run_filter; events are written when they happen.
bool Worker::guard(double t, const double* state, FilterRunResult& out, const RealisabilityCheck* realisability) {
  const FilterGuardOptions& guards = options_.filter_guards;
  const std::size_t n = plan_.n;
  if (auto event = check_filter_divergence(guards, t, state, n)) {  // as run_filter does
    out.diverged = true;
    out.divergence_t = event->t;
    return false;
  }
  if (realisability)
    if (auto event = check_realisability(*realisability, t, state, margins_)) {
      out.diverged = out.unrealisable = true;
      out.divergence_t = event->t;
      return false;
    }
  if (guards.check_psd && !out.psd_lost && !guards.psd.passes_filter_state(state, n)) {
    out.psd_lost = true;
    out.psd_t = t;
    if (guards.stop_on_psd_loss) return false;
  }
  return true;
}

// The horizon's mean e^2 and mean (m - m_ref)^2, for a pass that reached T (the latter when the
// reference did too).
void Worker::finish_pass(FilterRunResult& out, const PassSums& pass, const RunBuffers& lane) const {
  const auto steps = static_cast<std::ptrdiff_t>(plan_.grid.steps);
  if (out.last != steps) return;
  for (std::size_t i = 0; i < plan_.n; ++i) out.mean_square[i] = pass.sums[i] / static_cast<double>(steps + 1);
  if (!reference_ || lane.reference_last != steps) return;
  for (std::size_t i = 0; i < plan_.n; ++i)
    out.reference_square[i] = pass.distance_sums[i] / static_cast<double>(steps + 1);
}

void Worker::reset_plan() {
  active_.clear();
  next_open_ = next_event_ = events_begin_ = 0;
}

// run_filter (simulation.cpp) over one run's truth buffers, with the run's statistics accumulated
// as it goes.
void Worker::step_filter(std::size_t f, bool shown, const RunResult& run, RunBuffers& lane, FilterRunResult& out) {
  const FilterModel& filter = filters_[f];
  const TimeGrid& grid = plan_.grid;
  PassSums& pass = passes_[0];
  if (!start_pass(shown, run, out, pass)) return;
  double* state = state_.data();
  reset_plan();
  filter.initial_state(state);
  bool going = guard(grid.t0, state, out, &filter.realisability);
  if (out.diverged) return;
  enter(0);
  visit(0, state, shown, lane, out, pass);
  leave();
  out.last = 0;
  std::uint64_t steps = 0;
  const std::uint64_t refined_before = stepper_.refined_steps();
  const FilterInput input{grid, plan_.p, lane.dy.data(), lane.noisy.data(), steps_per_sample_, observation_.period()};
  for (std::size_t k = 0; going && static_cast<std::ptrdiff_t>(k) < run.truth_last; ++k) {
    const FilterStepOutcome outcome = filter.timing->advance(stepper_, state, input, k);
    if (outcome.stop != FilterStepOutcome::Stop::none) {
      out.diverged = true;  // mid-step, or predicted to a failed update: the state is not stored
      switch (outcome.stop) {
        case FilterStepOutcome::Stop::too_stiff: out.too_stiff = true; break;
        case FilterStepOutcome::Stop::equations_undefined: out.undefined = true; break;
        default: out.update_failed = true; break;
      }
      out.divergence_t = outcome.t;
      break;
    }
    if (outcome.sample >= 0) absorb_sample(outcome.t, outcome.sample, state, lane, out);
    ++steps;
    going = guard(grid.time(k + 1), state, out, &filter.realisability);
    if (out.diverged) break;  // a diverged state is not stored
    enter(k + 1);
    visit(k + 1, state, shown, lane, out, pass);
    leave();
    out.last = static_cast<std::ptrdiff_t>(k + 1);
  }
  filter_steps[f] += steps;
  filter_samples[f] += out.samples;
  out.refined_steps = stepper_.refined_steps() - refined_before;
  finish_pass(out, pass, lane);
}

// A sample absorbed at t (column `column` of the run's samples; docs/theory.md, section 2.5):
// the sample sums of the filter's h(t_k, m(t_k|t_k)) against the noise-free and the noisy sample.
void Worker::absorb_sample(double t, std::ptrdiff_t column, const double* state, const RunBuffers& lane,
                           FilterRunResult& out) {
  const std::size_t p = observation_.p();
  ++out.samples;
  double* hat = estimate_.data();
  observation_.rate().value(t, state, hat);  // C0 + C m(t_k|t_k), or c(m(t_k|t_k))
  const auto sample = static_cast<Eigen::Index>(column);
  for (std::size_t i = 0; i < p; ++i) {
    const double Y[2] = {lane.clean(static_cast<Eigen::Index>(i), sample), lane.noisy(static_cast<Eigen::Index>(i), sample)};
    for (int reading = 0; reading < 2; ++reading) {
      const double e = Y[reading] - hat[i];
      out.sample_sums[4 * i + reading] += e * e;
      out.sample_sums[4 * i + 2 + reading] += std::abs(e) / std::abs(Y[reading]);
    }
  }
}

// The plan's windows opening at grid point j, and its events there [events_begin_, next_event_).
void Worker::enter_events(std::size_t j) {
  while (next_open_ < plan_.opens.size() && plan_.opens[next_open_].first == j)
    active_.push_back(plan_.opens[next_open_++].second);
  events_begin_ = next_event_;
  while (next_event_ < plan_.events.size() && plan_.events[next_event_].index == j) ++next_event_;
}

// The windows closing at the current grid point, once every run has visited it.
void Worker::leave_events() {
  for (std::size_t e = events_begin_; e < next_event_; ++e)
    if (plan_.events[e].kind == Plan::Kind::window_close)
      active_.erase(std::find(active_.begin(), active_.end(), plan_.events[e].slot));
}

// Grid point j of a filter pass (between enter(j) and leave()): the error, its sums, and
// whatever the plan has at j.
void Worker::visit(std::size_t j, const double* state, bool shown, const RunBuffers& lane, FilterRunResult& out,
                   PassSums& pass) const {
  const std::size_t n = plan_.n;
  const double* x = lane.path.data() + j * n;
  double* sums = pass.sums.data();
  double* error = pass.error.data();
  for (std::size_t i = 0; i < n; ++i) {
    const double e = x[i] - state[i], square = e * e;
    error[i] = e;
    sums[i] += square;
    out.peak[i] = std::max(out.peak[i], std::abs(e));
    for (std::size_t w : active_) sums[(1 + w) * n + i] += square;
  }
  visit_rest(j, state, shown, lane, out, pass);
}

// What visit() does at j after the errors and their sums (in pass): the criterion, the distance
// to the reference, and the plan's events.
void Worker::visit_rest(std::size_t j, const double* state, bool shown, const RunBuffers& lane, FilterRunResult& out,
                        PassSums& pass) const {
  const std::size_t n = plan_.n;
  const double* sums = pass.sums.data();
  const double* error = pass.error.data();
  if (criterion_) accumulate_criterion(j, out, pass);
  const bool referenced = reference_ && static_cast<std::ptrdiff_t>(j) <= lane.reference_last;
  const double* m_ref = referenced ? lane.reference_mean.data() + j * n : nullptr;
  if (referenced)
    for (std::size_t i = 0; i < n; ++i) pass.distance_sums[i] += (state[i] - m_ref[i]) * (state[i] - m_ref[i]);
  // e^T P^-1 e where a record, a report time or T asks for it (P after m in the state).
  const auto nees = [&] { return normalized_error_squared(error, state + n, n, nees_work_.data()); };
  if (j == plan_.grid.steps) out.nees.back() = nees();
  for (std::size_t e = events_begin_; e < next_event_; ++e) {
    const Plan::Event& event = plan_.events[e];
    const std::size_t slot = event.slot;
    switch (event.kind) {
      case Plan::Kind::record:
        out.nees_record[slot] = nees();
        for (std::size_t i = 0; i < n; ++i) out.error_record[slot * n + i] = error[i];
        if (shown)
          for (std::size_t i = 0; i < n; ++i) {
            out.m_record[slot * n + i] = state[i];
            out.P_record[slot * n + i] = state[n + packed_diagonal(n, i)];
          }
        if (referenced)
          for (std::size_t i = 0; i < n; ++i) out.reference_record[slot * n + i] = state[i] - m_ref[i];
        break;
      case Plan::Kind::report:
        out.nees[slot] = nees();
        for (std::size_t i = 0; i < n; ++i) out.report_error[slot * n + i] = error[i];
        break;
      case Plan::Kind::window_close: {
        const auto& [first, last] = plan_.windows[slot];
        for (std::size_t i = 0; i < n; ++i)
          out.mean_square[(1 + slot) * n + i] = sums[(1 + slot) * n + i] / static_cast<double>(last - first + 1);
        break;
      }
    }
  }
}

// The criterion's L = e^T M e at grid point j (e in pass.error), and the trapezoid's step from
// j - 1. Every grid point a filter pass reaches is visited, in order, from j = 0.
void Worker::accumulate_criterion(std::size_t j, FilterRunResult& out, PassSums& pass) const {
  const std::size_t n = plan_.n;
  const double* error = pass.error.data();
  double L = 0;
  if (!weighted_) {
    for (std::size_t i = 0; i < n; ++i) L += error[i] * error[i];
  } else {
    for (std::size_t i = 0; i < n; ++i)
      for (std::size_t k = 0; k < n; ++k)
        L += error[i] * weight_(static_cast<Eigen::Index>(i), static_cast<Eigen::Index>(k)) * error[k];
  }
  if (j == 0)
    out.integral = 0;
  else
    out.integral += 0.5 * plan_.grid.dt * (pass.previous_L + L);
  pass.previous_L = L;
}

}  // namespace pfgen_runtime::monte_carlo_detail
