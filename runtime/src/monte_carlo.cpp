#include "pfgen_runtime/monte_carlo.hpp"

#include <algorithm>
#include <atomic>
#include <chrono>
#include <cmath>
#include <exception>
#include <limits>
#include <memory>
#include <mutex>
#include <set>
#include <sstream>
#include <stdexcept>
#include <thread>

#include <time.h>

#include "pfgen_runtime/random.hpp"
#include "pfgen_runtime/statistics.hpp"

namespace pfgen_runtime {

namespace {

constexpr double nan = std::numeric_limits<double>::quiet_NaN();
using Clock = std::chrono::steady_clock;

double seconds_since(Clock::time_point start) {
  return std::chrono::duration<double>(Clock::now() - start).count();
}

// CPU time of the calling thread (std::chrono has no thread clock).
double thread_cpu_seconds() {
  timespec now{};
  clock_gettime(CLOCK_THREAD_CPUTIME_ID, &now);
  return static_cast<double>(now.tv_sec) + 1e-9 * static_cast<double>(now.tv_nsec);
}

// The grid points at which a run needs more than accumulating e^2: decided once, shared
// read-only by all threads.
struct Plan {
  enum class Kind { record, report, window_close };
  struct Event {
    std::size_t index;  // grid index
    Kind kind;
    std::size_t slot;  // record, report or window number
  };
  std::size_t n = 0, p = 0;
  TimeGrid grid;
  std::vector<std::size_t> records;                            // grid indices
  std::vector<std::size_t> reports;                            // grid indices, as requested
  std::vector<std::pair<std::size_t, std::size_t>> windows;    // first, last grid index
  std::vector<Event> events;                                   // by grid index
  std::vector<std::pair<std::size_t, std::size_t>> opens;      // (first index, window), by index
  std::vector<std::size_t> diagonal;                           // offsets of P(i, i) in a filter state
};

std::size_t snap(const TimeGrid& grid, double t, const char* what) {
  const double position = (t - grid.t0) / grid.dt;
  // Half a step of slack either side: "T" typed by a user may differ from t0 + steps dt in the
  // last bit.
  if (!std::isfinite(position) || position < -0.5 || position > static_cast<double>(grid.steps) + 0.5) {
    std::ostringstream message;
    message << "monte carlo: " << what << " t = " << t << " is outside [" << grid.t0 << ", " << grid.end() << "]";
    throw std::invalid_argument(message.str());
  }
  return static_cast<std::size_t>(std::llround(std::max(0.0, position)));
}

Plan make_plan(std::size_t n, std::size_t p, const MonteCarloOptions& options) {
  Plan plan;
  plan.n = n;
  plan.p = p;
  plan.grid = options.grid;
  const std::size_t steps = options.grid.steps;
  const std::size_t stride = std::max<std::size_t>(1, steps / options.record_points);
  for (std::size_t k = 0; k <= steps; k += stride) plan.records.push_back(k);
  if (plan.records.back() != steps) plan.records.push_back(steps);
  for (double t : options.report_times) plan.reports.push_back(snap(options.grid, t, "report time"));
  for (const auto& [a, b] : options.windows) {
    if (!(a < b)) throw std::invalid_argument("monte carlo: a window [a, b] needs a < b");
    const std::size_t first = snap(options.grid, a, "window start"), last = snap(options.grid, b, "window end");
    if (first >= last) throw std::invalid_argument("monte carlo: a window is shorter than a grid step");
    plan.windows.emplace_back(first, last);
  }
  for (std::size_t r = 0; r < plan.records.size(); ++r) plan.events.push_back({plan.records[r], Plan::Kind::record, r});
  for (std::size_t q = 0; q < plan.reports.size(); ++q) plan.events.push_back({plan.reports[q], Plan::Kind::report, q});
  for (std::size_t w = 0; w < plan.windows.size(); ++w) {
    plan.events.push_back({plan.windows[w].second, Plan::Kind::window_close, w});
    plan.opens.emplace_back(plan.windows[w].first, w);
  }
  std::stable_sort(plan.events.begin(), plan.events.end(),
                   [](const Plan::Event& x, const Plan::Event& y) { return x.index < y.index; });
  std::stable_sort(plan.opens.begin(), plan.opens.end());
  for (std::size_t i = 0, offset = n; i < n; offset += n - i, ++i) plan.diagonal.push_back(offset);
  return plan;
}

// What one run leaves behind for the statistics (no paths: only values at the plan's points).
struct FilterRunResult {
  std::ptrdiff_t last = -1;  // last grid index with a stored filter state; -1: none
  bool diverged = false, psd_lost = false;
  double divergence_t = nan, psd_t = nan;
  std::vector<double> mean_square;   // (1 + windows) x n, the horizon first; NaN unless reached
  std::vector<double> report_error;  // reports x n; NaN where not alive
  std::vector<double> peak;          // n: max |e| over the stored states
  std::uint64_t refined_steps = 0;   // grid steps the FilterStepper split
  std::vector<double> error_record;  // records x n
  std::vector<double> m_record, P_record;  // records x n, the shown run only
};

struct RunResult {
  std::ptrdiff_t truth_last = -1;  // last grid index with a stored truth state; -1: none
  bool truth_diverged = false;
  double truth_divergence_t = nan;
  std::vector<double> truth_record;  // records x n
  std::vector<double> truth_report;  // reports x n; NaN where the truth had stopped
  std::vector<FilterRunResult> filters;
};

// The same first guard failure as run_filter's (simulation.cpp): m, then P's entries.
bool state_diverged(const FilterGuardOptions& guards, double t, const double* state, std::size_t n, double& at) {
  if (auto event = guards.estimate_guard.check(t, state, n)) {
    at = event->t;
    return true;
  }
  if (auto event = guards.covariance_guard.check(t, state + n, packed_size(n))) {
    at = event->t;
    return true;
  }
  return false;
}

// One thread's copies of the scheme, observation and filters, and its reusable buffers.
class Worker {
 public:
  Worker(const TruthScheme& scheme, const LinearObservation& observation, const std::vector<FilterModel>& filters,
         const Eigen::VectorXd& x0, const Plan& plan, const MonteCarloOptions& options)
      : scheme_(scheme.clone()), observation_(observation), filters_(filters), x0_(x0), plan_(plan),
        options_(options), path_(plan.n, plan.grid.steps + 1), dy_(plan.p, plan.grid.steps),
        x_(plan.n), dW_(scheme.system().q), dW2_(observation.r()), error_(plan.n),
        sums_((1 + plan.windows.size()) * plan.n), stepper_(plan.n, plan.p, options.filter_guards.stepping) {
    filter_seconds.assign(filters.size(), 0.0);
    filter_cpu_seconds.assign(filters.size(), 0.0);
    filter_steps.assign(filters.size(), 0);
    std::size_t largest = 0;
    for (const FilterModel& filter : filters_) largest = std::max(largest, filter.state_size());
    state_.resize(largest);
    active_.reserve(plan.windows.size());
  }

  void run(std::size_t run, RunResult& out) {
    Clock::time_point start = Clock::now();
    double cpu_start = thread_cpu_seconds();
    simulate_truth(run, out);
    truth_seconds += seconds_since(start);
    truth_cpu_seconds += thread_cpu_seconds() - cpu_start;
    out.filters.resize(filters_.size());
    for (std::size_t f = 0; f < filters_.size(); ++f) {
      start = Clock::now();
      cpu_start = thread_cpu_seconds();
      step_filter(f, run == options_.shown_run, out, out.filters[f]);
      filter_seconds[f] += seconds_since(start);
      filter_cpu_seconds[f] += thread_cpu_seconds() - cpu_start;
    }
  }

  double truth_seconds = 0, truth_cpu_seconds = 0;
  std::uint64_t truth_steps = 0;
  std::vector<double> filter_seconds, filter_cpu_seconds;
  std::vector<std::uint64_t> filter_steps;

 private:
  // simulate_truth (simulation.cpp) into the thread's buffers: the same streams, draws, order
  // of operations and guard, so the same bits.
  void simulate_truth(std::size_t run, RunResult& out) {
    const TimeGrid& grid = plan_.grid;
    scheme_->start_run(options_.seed, run);
    RandomStream truth_noise(options_.seed, run, substream::truth_noise);
    RandomStream observation_noise(options_.seed, run, substream::observation_noise);
    x_ = x0_;
    if (auto event = options_.truth_guard.check(grid.t0, x_)) {
      out.truth_diverged = true;
      out.truth_divergence_t = event->t;
    } else {
      path_.col(0) = x_;
      out.truth_last = 0;
      for (std::size_t k = 0; k < grid.steps; ++k) {
        const double t = grid.time(k);
        truth_noise.wiener_increment(grid.dt, dW_);
        observation_noise.wiener_increment(grid.dt, dW2_);
        scheme_->step(t, x_, grid.dt, dW_);
        ++truth_steps;
        if (auto event = options_.truth_guard.check(grid.time(k + 1), x_)) {
          out.truth_diverged = true;
          out.truth_divergence_t = event->t;
          break;
        }
        const auto column = static_cast<Eigen::Index>(k);
        observation_.increment(t, grid.dt, path_.col(column), x_, dW2_, dy_.col(column));
        path_.col(column + 1) = x_;
        out.truth_last = static_cast<std::ptrdiff_t>(k + 1);
      }
    }
    const std::size_t n = plan_.n;
    out.truth_record.assign(plan_.records.size() * n, nan);
    for (std::size_t r = 0; r < plan_.records.size(); ++r)
      if (static_cast<std::ptrdiff_t>(plan_.records[r]) <= out.truth_last)
        for (std::size_t i = 0; i < n; ++i) out.truth_record[r * n + i] = path_(i, plan_.records[r]);
    out.truth_report.assign(plan_.reports.size() * n, nan);
    for (std::size_t q = 0; q < plan_.reports.size(); ++q)
      if (static_cast<std::ptrdiff_t>(plan_.reports[q]) <= out.truth_last)
        for (std::size_t i = 0; i < n; ++i) out.truth_report[q * n + i] = path_(i, plan_.reports[q]);
  }

  // run_filter (simulation.cpp) over the thread's truth buffers, with the run's statistics
  // accumulated as it goes.
  void step_filter(std::size_t f, bool shown, const RunResult& run, FilterRunResult& out) {
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
    if (run.truth_last < 0) return;  // no truth to compare with

    double* state = state_.data();
    std::fill(sums_.begin(), sums_.end(), 0.0);
    active_.clear();
    next_open_ = next_event_ = 0;
    // True while the run may go on, as in run_filter; events are written when they happen.
    auto guard = [&](double t) {
      if (state_diverged(guards, t, state, n, out.divergence_t)) {
        out.diverged = true;
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
    const std::uint64_t refined_before = stepper_.refined_steps();
    const double* dy = dy_.data();
    for (std::size_t k = 0; going && static_cast<std::ptrdiff_t>(k) < run.truth_last; ++k) {
      stepper_.advance(filter.step, state, grid.time(k), grid.dt, dy + k * plan_.p);
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
  }

  // Grid point j of a filter pass: the error, its sums, and whatever the plan has at j.
  void visit(std::size_t j, const double* state, bool shown, FilterRunResult& out) {
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
    while (next_event_ < plan_.events.size() && plan_.events[next_event_].index == j) {
      const Plan::Event& event = plan_.events[next_event_++];
      const std::size_t slot = event.slot;
      switch (event.kind) {
        case Plan::Kind::record:
          for (std::size_t i = 0; i < n; ++i) out.error_record[slot * n + i] = error_[i];
          if (shown)
            for (std::size_t i = 0; i < n; ++i) {
              out.m_record[slot * n + i] = state[i];
              out.P_record[slot * n + i] = state[plan_.diagonal[i]];
            }
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

  std::unique_ptr<TruthScheme> scheme_;
  LinearObservation observation_;
  std::vector<FilterModel> filters_;
  Eigen::VectorXd x0_;
  const Plan& plan_;
  const MonteCarloOptions& options_;
  Eigen::MatrixXd path_;  // n x (steps + 1): x at the grid times of the current run
  Eigen::MatrixXd dy_;    // p x steps
  Eigen::VectorXd x_, dW_, dW2_;
  std::vector<double> state_, error_, sums_;
  FilterStepper stepper_;
  std::vector<std::size_t> active_;  // windows open at the current grid point
  std::size_t next_open_ = 0, next_event_ = 0;
};

// Mean and 5/50/95 % quantiles of `values` into row `row`, column `i`; NaN when empty.
void summarize(std::vector<double>& values, SeriesStatistics& out, Eigen::Index row, Eigen::Index i) {
  if (values.empty()) {
    out.mean(row, i) = out.q05(row, i) = out.q50(row, i) = out.q95(row, i) = nan;
    return;
  }
  double sum = 0;
  for (double v : values) sum += v;  // in run order
  out.mean(row, i) = sum / static_cast<double>(values.size());
  std::sort(values.begin(), values.end());  // quantile sorts its copy again, now cheaply
  out.q05(row, i) = quantile(values, 0.05);
  out.q50(row, i) = quantile(values, 0.50);
  out.q95(row, i) = quantile(values, 0.95);
}

SeriesStatistics make_series_statistics(std::size_t records, std::size_t n) {
  const auto rows = static_cast<Eigen::Index>(records), cols = static_cast<Eigen::Index>(n);
  return {Eigen::MatrixXd(rows, cols), Eigen::MatrixXd(rows, cols), Eigen::MatrixXd(rows, cols),
          Eigen::MatrixXd(rows, cols)};
}

Eigen::MatrixXd records_matrix(const std::vector<double>& values, std::size_t records, std::size_t n) {
  Eigen::MatrixXd matrix(static_cast<Eigen::Index>(records), static_cast<Eigen::Index>(n));
  for (std::size_t r = 0; r < records; ++r)
    for (std::size_t i = 0; i < n; ++i)
      matrix(static_cast<Eigen::Index>(r), static_cast<Eigen::Index>(i)) = values[r * n + i];
  return matrix;
}

// body(i, state) for i in [0, count), taken in turn from an atomic counter by up to `threads`
// threads, each with its own state = make_state(thread number). The first exception stops the
// other threads and is rethrown once all have stopped.
template <class MakeState, class Body>
void parallel_for(std::size_t count, unsigned threads, MakeState make_state, Body body) {
  std::atomic<std::size_t> next{0};
  std::atomic<bool> failed{false};
  std::exception_ptr error;
  std::mutex error_mutex;
  auto work = [&](unsigned thread) {
    try {
      auto state = make_state(thread);
      for (std::size_t i; !failed.load() && (i = next.fetch_add(1)) < count;) body(i, state);
    } catch (...) {
      std::lock_guard<std::mutex> lock(error_mutex);
      if (!error) error = std::current_exception();
      failed = true;
    }
  };
  std::vector<std::thread> pool;
  try {
    for (unsigned t = 1; t < threads; ++t) pool.emplace_back(work, t);
  } catch (...) {  // could not start a thread: stop the others and report
    failed = true;
    for (std::thread& thread : pool) thread.join();
    throw;
  }
  work(0);
  for (std::thread& thread : pool) thread.join();
  if (error) std::rethrow_exception(error);
}

// Folds the runs, in run order, into the result's statistics and series.
void aggregate(const Plan& plan, const std::vector<FilterModel>& filters, const std::vector<RunResult>& runs,
               const MonteCarloOptions& options, unsigned threads, MonteCarloResult& result) {
  const std::size_t n = plan.n, records = plan.records.size();
  const auto steps = static_cast<std::ptrdiff_t>(plan.grid.steps);
  std::vector<double> values;
  values.reserve(runs.size());

  for (std::size_t r = 0; r < runs.size(); ++r)
    if (runs[r].truth_diverged) result.truth_divergences.events.push_back({r, runs[r].truth_divergence_t});

  for (std::size_t q = 0; q < plan.reports.size(); ++q) {
    TruthReportStatistics report;
    report.index = plan.reports[q];
    report.t = plan.grid.time(report.index);
    for (std::size_t i = 0; i < n; ++i) {
      values.clear();
      for (const RunResult& run : runs)
        if (run.truth_last >= static_cast<std::ptrdiff_t>(report.index)) values.push_back(run.truth_report[q * n + i]);
      report.alive = values.size();
      double sum = 0;
      for (double v : values) sum += v;
      report.mean.push_back(values.empty() ? nan : sum / static_cast<double>(values.size()));
      report.q05.push_back(values.empty() ? nan : quantile(values, 0.05));
      report.q50.push_back(values.empty() ? nan : quantile(values, 0.5));
      report.q95.push_back(values.empty() ? nan : quantile(values, 0.95));
    }
    result.truth_reports.push_back(std::move(report));
  }

  for (std::size_t f = 0; f < filters.size(); ++f) {
    FilterStatistics stats;
    stats.name = filters[f].name;
    // Window 0 is the horizon.
    for (std::size_t w = 0; w <= plan.windows.size(); ++w) {
      WindowStatistics window;
      window.first = w == 0 ? 0 : plan.windows[w - 1].first;
      window.last = w == 0 ? plan.grid.steps : plan.windows[w - 1].second;
      window.a = plan.grid.time(window.first);
      window.b = plan.grid.time(window.last);
      std::vector<double> sum(n, 0.0);
      for (const RunResult& run : runs) {
        const FilterRunResult& filter = run.filters[f];
        if (filter.last < static_cast<std::ptrdiff_t>(window.last)) continue;
        ++window.runs;
        for (std::size_t i = 0; i < n; ++i) sum[i] += filter.mean_square[w * n + i];
      }
      for (std::size_t i = 0; i < n; ++i)
        window.rms.push_back(window.runs > 0 ? std::sqrt(sum[i] / static_cast<double>(window.runs)) : nan);
      if (w == 0)
        stats.horizon = std::move(window);
      else
        stats.windows.push_back(std::move(window));
    }
    for (std::size_t q = 0; q < plan.reports.size(); ++q) {
      ReportStatistics report;
      report.index = plan.reports[q];
      report.t = plan.grid.time(report.index);
      std::vector<double> sum_abs(n, 0.0), sum_square(n, 0.0);
      for (const RunResult& run : runs) {
        const FilterRunResult& filter = run.filters[f];
        if (filter.last < static_cast<std::ptrdiff_t>(report.index)) continue;
        ++report.alive;
        for (std::size_t i = 0; i < n; ++i) {
          const double e = filter.report_error[q * n + i];
          sum_abs[i] += std::abs(e);
          sum_square[i] += e * e;
        }
      }
      const double alive = static_cast<double>(report.alive);
      for (std::size_t i = 0; i < n; ++i) {
        report.mean_abs.push_back(report.alive > 0 ? sum_abs[i] / alive : nan);
        report.rms.push_back(report.alive > 0 ? std::sqrt(sum_square[i] / alive) : nan);
      }
      stats.reports.push_back(std::move(report));
    }
    for (std::size_t i = 0; i < n; ++i) {
      values.clear();
      for (const RunResult& run : runs)
        if (run.filters[f].last == steps) values.push_back(run.filters[f].peak[i]);
      stats.peak_median.push_back(values.empty() ? nan : quantile(values, 0.5));
      stats.peak_q95.push_back(values.empty() ? nan : quantile(values, 0.95));
    }
    for (std::size_t r = 0; r < runs.size(); ++r) {
      const FilterRunResult& filter = runs[r].filters[f];
      if (filter.diverged) stats.divergences.events.push_back({r, filter.divergence_t});
      if (filter.psd_lost) stats.psd_losses.events.push_back({r, filter.psd_t});
      stats.refined_steps += filter.refined_steps;
      stats.refined_runs += filter.refined_steps > 0;
    }
    result.filters.push_back(std::move(stats));
  }

  MonteCarloSeries& series = result.series;
  series.index = plan.records;
  for (std::size_t k : plan.records) series.t.push_back(plan.grid.time(k));
  series.shown_run = options.shown_run;
  const RunResult& shown = runs[options.shown_run];
  series.truth = records_matrix(shown.truth_record, records, n);
  series.truth_statistics = make_series_statistics(records, n);
  series.truth_alive.assign(records, 0);
  for (std::size_t f = 0; f < filters.size(); ++f) {
    FilterSeries filter;
    filter.m = records_matrix(shown.filters[f].m_record, records, n);
    filter.P_diagonal = records_matrix(shown.filters[f].P_record, records, n);
    filter.error = make_series_statistics(records, n);
    filter.alive.assign(records, 0);
    series.filters.push_back(std::move(filter));
  }
  // Across runs at each record time. Record times are independent (each writes its own rows), so
  // they are shared among threads without changing a bit; the sorting for the quantiles is most
  // of the statistics' time.
  auto scratch = [&runs](unsigned) {
    std::vector<double> values;
    values.reserve(runs.size());
    return values;
  };
  parallel_for(records, threads, scratch, [&](std::size_t r, std::vector<double>& values) {
    const auto index = static_cast<std::ptrdiff_t>(plan.records[r]);
    const auto row = static_cast<Eigen::Index>(r);
    for (std::size_t i = 0; i < n; ++i) {
      values.clear();
      for (const RunResult& run : runs)
        if (run.truth_last >= index) values.push_back(run.truth_record[r * n + i]);
      series.truth_alive[r] = values.size();
      summarize(values, series.truth_statistics, row, static_cast<Eigen::Index>(i));
    }
    for (std::size_t f = 0; f < filters.size(); ++f) {
      FilterSeries& filter = series.filters[f];
      for (std::size_t i = 0; i < n; ++i) {
        values.clear();
        for (const RunResult& run : runs)
          if (run.filters[f].last >= index) values.push_back(run.filters[f].error_record[r * n + i]);
        filter.alive[r] = values.size();
        summarize(values, filter.error, row, static_cast<Eigen::Index>(i));
      }
    }
  });
}

void validate(const TruthScheme& scheme, const LinearObservation& observation, const Eigen::VectorXd& x0,
              const std::vector<FilterModel>& filters, const MonteCarloOptions& options) {
  const std::size_t n = scheme.system().n;
  if (static_cast<std::size_t>(x0.size()) != n || observation.n() != n)
    throw std::invalid_argument("monte carlo: x0 and the observation must have the truth's n states");
  if (!(options.grid.dt > 0) || options.grid.steps == 0 || !std::isfinite(options.grid.t0) ||
      !std::isfinite(options.grid.end()))
    throw std::invalid_argument("monte carlo: the time grid needs dt > 0 and at least one step");
  if (options.runs == 0) throw std::invalid_argument("monte carlo: runs must be at least 1");
  if (options.threads == 0) throw std::invalid_argument("monte carlo: threads must be at least 1");
  if (options.record_points == 0) throw std::invalid_argument("monte carlo: record_points must be at least 1");
  if (options.shown_run >= options.runs) throw std::invalid_argument("monte carlo: the shown run is not among the runs");
  std::set<std::string> names;
  for (const FilterModel& filter : filters) {
    if (filter.name.empty() || !names.insert(filter.name).second)
      throw std::invalid_argument("monte carlo: filter names must be non-empty and distinct ('" + filter.name + "')");
    if (!filter.step || !filter.initial_state)
      throw std::invalid_argument("monte carlo: filter '" + filter.name + "' lacks initial_state or step");
    if (filter.n != n || filter.p != observation.p())
      throw std::invalid_argument("monte carlo: filter '" + filter.name +
                                  "' must have the truth's n states and the observation's p");
  }
}

}  // namespace

double EventSummary::earliest() const {
  double t = nan;
  for (const RunEvent& event : events)
    if (!(event.t >= t)) t = event.t;  // the first comparison with NaN takes the event
  return t;
}

double EventSummary::median() const {
  if (events.empty()) return nan;
  std::vector<double> times;
  for (const RunEvent& event : events) times.push_back(event.t);
  return quantile(std::move(times), 0.5);
}

MonteCarloResult run_monte_carlo(const TruthScheme& scheme, const LinearObservation& observation,
                                 const Eigen::VectorXd& x0, const std::vector<FilterModel>& filters,
                                 const MonteCarloOptions& options) {
  const Clock::time_point wall_start = Clock::now();
  validate(scheme, observation, x0, filters, options);
  const Plan plan = make_plan(scheme.system().n, observation.p(), options);

  std::vector<RunResult> runs(options.runs);
  const unsigned threads = static_cast<unsigned>(std::min<std::size_t>(options.threads, options.runs));
  std::vector<std::unique_ptr<Worker>> workers(threads);
  std::atomic<std::size_t> finished{0};
  auto make_worker = [&](unsigned thread) {
    workers[thread] = std::make_unique<Worker>(scheme, observation, filters, x0, plan, options);
    return workers[thread].get();
  };
  parallel_for(options.runs, threads, make_worker, [&](std::size_t run, Worker* worker) {
    worker->run(run, runs[run]);
    const std::size_t done = finished.fetch_add(1) + 1;
    if (options.on_run_finished) options.on_run_finished(done, options.runs);
  });

  const Clock::time_point aggregation_start = Clock::now();
  MonteCarloResult result;
  result.grid = options.grid;
  result.runs = options.runs;
  result.seed = options.seed;
  result.scheme = scheme.name();
  result.n = plan.n;
  aggregate(plan, filters, runs, options, threads, result);

  MonteCarloTiming& timing = result.timing;
  timing.threads = threads;
  timing.filter_seconds.assign(filters.size(), 0.0);
  timing.filter_cpu_seconds.assign(filters.size(), 0.0);
  timing.filter_steps.assign(filters.size(), 0);
  for (const auto& worker : workers) {
    timing.truth_seconds += worker->truth_seconds;
    timing.truth_cpu_seconds += worker->truth_cpu_seconds;
    timing.truth_steps += worker->truth_steps;
    for (std::size_t f = 0; f < filters.size(); ++f) {
      timing.filter_seconds[f] += worker->filter_seconds[f];
      timing.filter_cpu_seconds[f] += worker->filter_cpu_seconds[f];
      timing.filter_steps[f] += worker->filter_steps[f];
    }
  }
  timing.aggregation_seconds = seconds_since(aggregation_start);
  timing.wall_seconds = seconds_since(wall_start);
  return result;
}

}  // namespace pfgen_runtime
