#include "worker.hpp"

#include <algorithm>
#include <cmath>

#include "clock.hpp"
#include "pfgen_runtime/gaussian_draw.hpp"

namespace pfgen_runtime::monte_carlo_detail {

Worker::Worker(const TruthScheme& scheme, const LinearObservation& observation, const SampledMeasurement* measurement,
               const std::vector<FilterModel>& filters, const Eigen::VectorXd& x0, const Plan& plan,
               const MonteCarloOptions& options)
    : scheme_(scheme.clone()), observation_(observation), filters_(filters), x0_(x0), plan_(plan),
      options_(options), path_(plan.n, plan.grid.steps + 1),
      dy_(static_cast<Eigen::Index>(observation.p()), plan.grid.steps),
      error_(plan.n),
      sums_((1 + plan.windows.size()) * plan.n), stepper_(plan.n, plan.p, options.filter_guards.stepping) {
  filter_seconds.assign(filters.size(), 0.0);
  filter_cpu_seconds.assign(filters.size(), 0.0);
  filter_steps.assign(filters.size(), 0);
  filter_samples.assign(filters.size(), 0);
  if (measurement) {
    measurement_ = *measurement;
    steps_per_sample_ = measurement->steps_per_sample(plan.grid);
    const auto p = static_cast<Eigen::Index>(measurement->p());
    const auto samples = static_cast<Eigen::Index>(plan.grid.steps / steps_per_sample_);
    clean_.resize(p, samples);
    noisy_.resize(p, samples);
    zeros_.assign(measurement->q(), 0.0);
    estimate_.assign(2 * measurement->p(), 0.0);
  }
  std::size_t largest = 0;
  for (const FilterModel& filter : filters_) largest = std::max(largest, filter.state_size());
  state_.resize(largest);
  active_.reserve(plan.windows.size());
  if (options.criterion) {
    criterion_ = true;
    weight_ = options.criterion->weight;
    weighted_ = weight_.size() > 0;
  }
  if (options.initial_prior)
    prior_root_ = covariance_square_root(options.initial_prior->covariance, "monte carlo: the initial prior's covariance");
  if (options.reference) {
    const double bound = options.truth_guard.bound();
    reference_ = measurement ? std::make_unique<ParticleReference>(scheme, *measurement, *options.reference, bound)
                             : std::make_unique<ParticleReference>(scheme, observation, *options.reference, bound);
    reference_mean_.resize(static_cast<Eigen::Index>(plan.n), static_cast<Eigen::Index>(plan.grid.steps + 1));
    distance_sums_.resize(plan.n);
  }
}

void Worker::run(std::size_t run, RunResult& out) {
  Clock::time_point start = Clock::now();
  double cpu_start = thread_cpu_seconds();
  simulate_truth(run, out);
  truth_seconds += seconds_since(start);
  truth_cpu_seconds += thread_cpu_seconds() - cpu_start;
  if (reference_) {
    start = Clock::now();
    cpu_start = thread_cpu_seconds();
    run_reference(run, run == options_.shown_run, out);
    reference_seconds += seconds_since(start);
    reference_cpu_seconds += thread_cpu_seconds() - cpu_start;
  }
  out.filters.resize(filters_.size());
  for (std::size_t f = 0; f < filters_.size(); ++f) {
    start = Clock::now();
    cpu_start = thread_cpu_seconds();
    step_filter(f, run == options_.shown_run, out, out.filters[f]);
    filter_seconds[f] += seconds_since(start);
    filter_cpu_seconds[f] += thread_cpu_seconds() - cpu_start;
  }
}

// simulate_truth's loop (simulation.cpp) into the thread's buffers, so the same bits.
void Worker::simulate_truth(std::size_t run, RunResult& out) {
  std::optional<DivergenceEvent> divergence;
  if (options_.initial_prior) {  // the run's own draw, from its own stream
    RandomStream initial(options_.seed, run, substream::initial_state);
    x0_ = draw_gaussian(options_.initial_prior->mean, prior_root_, initial);
  }
  out.truth_last = simulate_truth_into(*scheme_, observation_, x0_, plan_.grid, options_.seed, run,
                                       options_.truth_guard, path_, dy_, divergence);
  if (divergence) {
    out.truth_diverged = true;
    out.truth_divergence_t = divergence->t;
    out.truth_covariance_indefinite = divergence->kind == DivergenceKind::covariance_indefinite;
  }
  // Steps taken: the stored ones, and the one the guard stopped (none when x0 was rejected).
  truth_steps += static_cast<std::uint64_t>(std::max<std::ptrdiff_t>(out.truth_last, 0)) +
                 (divergence && out.truth_last >= 0 ? 1 : 0);
  const std::size_t n = plan_.n;
  if (measurement_)
    samples_ = draw_samples(*measurement_, plan_.grid, steps_per_sample_, path_, out.truth_last, options_.seed, run,
                            clean_, noisy_);
  out.truth_record.assign(plan_.records.size() * n, nan);
  for (std::size_t r = 0; r < plan_.records.size(); ++r)
    if (static_cast<std::ptrdiff_t>(plan_.records[r]) <= out.truth_last)
      for (std::size_t i = 0; i < n; ++i) out.truth_record[r * n + i] = path_(i, plan_.records[r]);
  out.truth_report.assign(plan_.reports.size() * n, nan);
  for (std::size_t q = 0; q < plan_.reports.size(); ++q)
    if (static_cast<std::ptrdiff_t>(plan_.reports[q]) <= out.truth_last)
      for (std::size_t i = 0; i < n; ++i) out.truth_report[q * n + i] = path_(i, plan_.reports[q]);
}

// The particle reference on the run's increments (or samples), and its own error x - m_ref.
void Worker::run_reference(std::size_t run, bool shown, RunResult& out) {
  const std::size_t n = plan_.n, steps = plan_.grid.steps;
  const ParticleReferenceRun outcome =
      measurement_ ? reference_->run_sampled(plan_.grid, steps_per_sample_, noisy_, samples_, out.truth_last,
                                             options_.seed, run, reference_mean_)
                   : reference_->run(plan_.grid, dy_, out.truth_last, options_.seed, run, reference_mean_);
  reference_last_ = outcome.last;
  reference_steps += outcome.particle_steps;
  ReferenceRunResult& reference = out.reference;
  reference.last = outcome.last;
  reference.stopped = outcome.stopped;
  if (outcome.stopped) reference.stop_t = outcome.stop_t;
  reference.resamplings = outcome.resamplings;
  reference.mean_square.assign(n, nan);
  reference.error_record.assign(plan_.records.size() * n, nan);
  if (shown) reference.m_record.assign(plan_.records.size() * n, nan);
  if (outcome.last == static_cast<std::ptrdiff_t>(steps)) {
    for (std::size_t i = 0; i < n; ++i) {
      double sum = 0;
      for (std::size_t j = 0; j <= steps; ++j) {
        const double e = path_(static_cast<Eigen::Index>(i), static_cast<Eigen::Index>(j)) -
                         reference_mean_(static_cast<Eigen::Index>(i), static_cast<Eigen::Index>(j));
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
      reference.error_record[r * n + i] = path_(row, j) - reference_mean_(row, j);
      if (shown) reference.m_record[r * n + i] = reference_mean_(row, j);
    }
  }
}

// run_filter (simulation.cpp) over the thread's truth buffers, with the run's statistics
// accumulated as it goes.
void Worker::step_filter(std::size_t f, bool shown, const RunResult& run, FilterRunResult& out) {
  const FilterModel& filter = filters_[f];
  const FilterGuardOptions& guards = options_.filter_guards;
  const TimeGrid& grid = plan_.grid;
  const std::size_t n = plan_.n;
  out.mean_square.assign(sums_.size(), nan);
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
    std::fill(distance_sums_.begin(), distance_sums_.end(), 0.0);
  }
  if (run.truth_last < 0) return;  // no truth to compare with

  double* state = state_.data();
  std::fill(sums_.begin(), sums_.end(), 0.0);
  active_.clear();
  next_open_ = next_event_ = 0;
  // True while the run may go on, as in run_filter; events are written when they happen.
  auto guard = [&](double t) {
    if (auto event = check_filter_divergence(guards, t, state, n)) {  // as run_filter does
      out.diverged = true;
      out.divergence_t = event->t;
      return false;
    }
    if (guards.check_psd && !out.psd_lost && !guards.psd.passes_filter_state(state, n)) {
      out.psd_lost = true;
      out.psd_t = t;
      if (guards.stop_on_psd_loss) return false;
    }
    return true;
  };

  filter.initial_state(state);
  bool going = guard(grid.t0);
  if (out.diverged) return;
  visit(0, state, shown, out);
  out.last = 0;
  std::uint64_t steps = 0;
  if (filter.sampled()) {
    if (going) step_sampled_filter(filter, run.truth_last, out, guard, shown, steps);
    filter_steps[f] += steps;
    filter_samples[f] += out.samples;
    if (out.last == static_cast<std::ptrdiff_t>(grid.steps))
      for (std::size_t i = 0; i < n; ++i) out.mean_square[i] = sums_[i] / static_cast<double>(grid.steps + 1);
    finish_reference_distance(out);
    return;
  }
  const std::uint64_t refined_before = stepper_.refined_steps();
  const double* dy = dy_.data();
  const bool fixed_step = filter.fixed_step();  // a delayed filter: once per grid step, as run_filter
  for (std::size_t k = 0; going && static_cast<std::ptrdiff_t>(k) < run.truth_last; ++k) {
    if (fixed_step) {
      filter.step(state, grid.time(k), grid.dt, dy + k * plan_.p);
    } else if (stepper_.advance(filter.step, state, grid.time(k), grid.dt, dy + k * plan_.p) == 0) {
      out.diverged = true;  // mid-step: the state is not stored
      (stepper_.equations_finite_at_start(filter.step, grid.time(k)) ? out.too_stiff : out.undefined) = true;
      out.divergence_t = grid.time(k);
      break;
    }
    ++steps;
    going = guard(grid.time(k + 1));
    if (out.diverged) break;  // a diverged state is not stored
    visit(k + 1, state, shown, out);
    out.last = static_cast<std::ptrdiff_t>(k + 1);
  }
  filter_steps[f] += steps;
  out.refined_steps = stepper_.refined_steps() - refined_before;
  if (out.last == static_cast<std::ptrdiff_t>(grid.steps))
    for (std::size_t i = 0; i < n; ++i) out.mean_square[i] = sums_[i] / static_cast<double>(grid.steps + 1);
  finish_reference_distance(out);
}

// The horizon's mean (m - m_ref)^2, when the filter and the reference both reached T.
void Worker::finish_reference_distance(FilterRunResult& out) {
  const auto steps = static_cast<std::ptrdiff_t>(plan_.grid.steps);
  if (!reference_ || out.last != steps || reference_last_ != steps) return;
  for (std::size_t i = 0; i < plan_.n; ++i)
    out.reference_square[i] = distance_sums_[i] / static_cast<double>(steps + 1);
}

// A sampled filter over the truth's grid (docs/theory.md, section 2.5): grid step k lies in the
// period starting at sample time t_s = t0 + s T, s = k / N (N grid steps per period), and the
// filter makes there the sub-steps u with k' s_f / N <= u < (k' + 1) s_f / N, k' = k mod N, s_f its
// substeps: integer arithmetic, so every period gets exactly s_f predictions of T / s_f, each
// started at t_s + u T / s_f, whatever N. At the period's last grid step the update absorbs
// y_{s+1}. The state visited at a grid point is so the prediction from the last sample to the
// last sub-step completed (a zero-order hold between sub-steps), and at a sample time the updated
// state, m(t_k|t_k).
void Worker::step_sampled_filter(const FilterModel& filter, std::ptrdiff_t truth_last, FilterRunResult& out,
                                 const std::function<bool(double)>& guard, bool shown, std::uint64_t& steps) {
  const TimeGrid& grid = plan_.grid;
  const std::size_t N = steps_per_sample_, substeps = filter.substeps, p = measurement_->p();
  const double period = measurement_->period(), delta = period / static_cast<double>(substeps);
  double* state = state_.data();
  out.sample_sums.assign(4 * p, 0.0);
  for (std::size_t k = 0; static_cast<std::ptrdiff_t>(k) < truth_last; ++k) {
    const std::size_t sample = k / N, within = k % N;
    const double start = grid.t0 + static_cast<double>(sample) * period;
    for (std::size_t u = within * substeps / N; u < (within + 1) * substeps / N; ++u)
      filter.predict(state, start + static_cast<double>(u) * delta, delta);
    if (within + 1 == N) {
      const double t = grid.t0 + static_cast<double>(sample + 1) * period;  // t_k = t0 + k T, as draw_samples
      const auto column = static_cast<Eigen::Index>(sample);
      if (!filter.update(state, t, noisy_.col(column).data())) {
        out.diverged = out.update_failed = true;  // the state is the predicted one: not stored
        out.divergence_t = t;
        return;
      }
      ++out.samples;
      double* hat = estimate_.data();
      measurement_->sample(t, state, zeros_.data(), hat, hat + p);  // C0 + C m(t_k|t_k)
      for (std::size_t i = 0; i < p; ++i) {
        const double Y[2] = {clean_(static_cast<Eigen::Index>(i), column), noisy_(static_cast<Eigen::Index>(i), column)};
        for (int reading = 0; reading < 2; ++reading) {
          const double e = Y[reading] - hat[i];
          out.sample_sums[4 * i + reading] += e * e;
          out.sample_sums[4 * i + 2 + reading] += std::abs(e) / std::abs(Y[reading]);
        }
      }
    }
    ++steps;
    const bool going = guard(grid.time(k + 1));
    if (out.diverged) return;  // a diverged state is not stored
    visit(k + 1, state, shown, out);
    out.last = static_cast<std::ptrdiff_t>(k + 1);
    if (!going) return;
  }
}

// Grid point j of a filter pass: the error, its sums, and whatever the plan has at j.
void Worker::visit(std::size_t j, const double* state, bool shown, FilterRunResult& out) {
  const std::size_t n = plan_.n;
  while (next_open_ < plan_.opens.size() && plan_.opens[next_open_].first == j)
    active_.push_back(plan_.opens[next_open_++].second);
  const double* x = path_.data() + j * n;
  for (std::size_t i = 0; i < n; ++i) {
    const double e = x[i] - state[i], square = e * e;
    error_[i] = e;
    sums_[i] += square;
    out.peak[i] = std::max(out.peak[i], std::abs(e));
    for (std::size_t w : active_) sums_[(1 + w) * n + i] += square;
  }
  if (criterion_) accumulate_criterion(j, out);
  const bool referenced = reference_ && static_cast<std::ptrdiff_t>(j) <= reference_last_;
  const double* m_ref = referenced ? reference_mean_.data() + j * n : nullptr;
  if (referenced)
    for (std::size_t i = 0; i < n; ++i) distance_sums_[i] += (state[i] - m_ref[i]) * (state[i] - m_ref[i]);
  while (next_event_ < plan_.events.size() && plan_.events[next_event_].index == j) {
    const Plan::Event& event = plan_.events[next_event_++];
    const std::size_t slot = event.slot;
    switch (event.kind) {
      case Plan::Kind::record:
        for (std::size_t i = 0; i < n; ++i) out.error_record[slot * n + i] = error_[i];
        if (shown)
          for (std::size_t i = 0; i < n; ++i) {
            out.m_record[slot * n + i] = state[i];
            out.P_record[slot * n + i] = state[n + packed_diagonal(n, i)];
          }
        if (referenced)
          for (std::size_t i = 0; i < n; ++i) out.reference_record[slot * n + i] = state[i] - m_ref[i];
        break;
      case Plan::Kind::report:
        for (std::size_t i = 0; i < n; ++i) out.report_error[slot * n + i] = error_[i];
        break;
      case Plan::Kind::window_close: {
        const auto& [first, last] = plan_.windows[slot];
        for (std::size_t i = 0; i < n; ++i)
          out.mean_square[(1 + slot) * n + i] = sums_[(1 + slot) * n + i] / static_cast<double>(last - first + 1);
        active_.erase(std::find(active_.begin(), active_.end(), slot));
        break;
      }
    }
  }
}

// The criterion's L = e^T M e at grid point j (e in error_), and the trapezoid's step from j - 1.
// Every grid point a filter pass reaches is visited, in order, from j = 0.
void Worker::accumulate_criterion(std::size_t j, FilterRunResult& out) {
  const std::size_t n = plan_.n;
  double L = 0;
  if (!weighted_) {
    for (std::size_t i = 0; i < n; ++i) L += error_[i] * error_[i];
  } else {
    for (std::size_t i = 0; i < n; ++i)
      for (std::size_t k = 0; k < n; ++k)
        L += error_[i] * weight_(static_cast<Eigen::Index>(i), static_cast<Eigen::Index>(k)) * error_[k];
  }
  if (j == 0)
    out.integral = 0;
  else
    out.integral += 0.5 * plan_.grid.dt * (previous_L_ + L);
  previous_L_ = L;
}

}  // namespace pfgen_runtime::monte_carlo_detail
