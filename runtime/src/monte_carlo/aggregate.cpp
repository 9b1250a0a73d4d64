#include "aggregate.hpp"

#include <algorithm>
#include <cmath>
#include <limits>
#include <stdexcept>
#include <string>
#include <tuple>
#include <utility>

#include "parallel_for.hpp"
#include "pfgen_runtime/statistics.hpp"

namespace pfgen_runtime::monte_carlo_detail {

namespace {

// Mean and 5/50/95 % quantiles of `values` into row `row`, column `i`; NaN when empty.
void summarize(std::vector<double>& values, SeriesStatistics& out, Eigen::Index row, Eigen::Index i) {
  if (values.empty()) {
    out.mean(row, i) = out.q05(row, i) = out.q50(row, i) = out.q95(row, i) = nan;
    return;
  }
  double sum = 0;
  for (double v : values) sum += v;  // in run order
  out.mean(row, i) = sum / static_cast<double>(values.size());
  std::vector<double> q;
  quantiles_in_place(values, {0.05, 0.50, 0.95}, q);  // reorders values, after the sum
  out.q05(row, i) = q[0];
  out.q50(row, i) = q[1];
  out.q95(row, i) = q[2];
}

SeriesStatistics make_series_statistics(std::size_t records, std::size_t n) {
  const auto rows = static_cast<Eigen::Index>(records), cols = static_cast<Eigen::Index>(n);
  return {Eigen::MatrixXd(rows, cols), Eigen::MatrixXd(rows, cols), Eigen::MatrixXd(rows, cols),
          Eigen::MatrixXd(rows, cols)};
}

// The shown run's record vector as records x n; a vector of another length can only come from a
// process's share that was not what it claims (the runs made here always have the plan's length).
Eigen::MatrixXd records_matrix(const std::vector<double>& values, std::size_t records, std::size_t n) {
  if (values.size() != records * n)
    throw std::runtime_error("monte carlo: a process's share of the runs is malformed (the shown run has " +
                             std::to_string(values.size()) + " recorded values, not " + std::to_string(records * n) +
                             ")");
  Eigen::MatrixXd matrix(static_cast<Eigen::Index>(records), static_cast<Eigen::Index>(n));
  for (std::size_t r = 0; r < records; ++r)
    for (std::size_t i = 0; i < n; ++i)
      matrix(static_cast<Eigen::Index>(r), static_cast<Eigen::Index>(i)) = values[r * n + i];
  return matrix;
}

// Mean and standard error (sample standard deviation / sqrt(count)) of values, in run order.
std::pair<double, double> mean_and_error(const std::vector<double>& values) {
  if (values.empty()) return {nan, nan};
  double sum = 0;
  for (double v : values) sum += v;
  const double count = static_cast<double>(values.size()), mean = sum / count;
  if (values.size() < 2) return {mean, nan};
  double squares = 0;
  for (double v : values) squares += (v - mean) * (v - mean);
  return {mean, std::sqrt(squares / (count - 1) / count)};
}

// RMSE(s) (which 0, 1) or MRAE(s) (2, 3) of component i of one filter's run.
double run_metric(const FilterRunResult& filter, std::size_t i, std::size_t which) {
  const double mean = filter.sample_sums[4 * i + which] / static_cast<double>(filter.samples);
  return which < 2 ? std::sqrt(mean) : mean;
}

bool complete(const FilterRunResult& filter, std::ptrdiff_t steps) { return filter.last == steps && filter.samples > 0; }

// Filter f minus filter 0, run by run, over the runs both completed.
void paired_differences(const std::vector<RunResult>& runs, std::size_t f, std::ptrdiff_t steps, std::size_t p,
                        SampledMetrics& metrics) {
  std::vector<std::size_t> both;
  for (std::size_t r = 0; r < runs.size(); ++r)
    if (complete(runs[r].filters[f], steps) && complete(runs[r].filters[0], steps)) both.push_back(r);
  metrics.paired_runs = both.size();
  const std::pair<std::vector<double>*, std::vector<double>*> outputs[4] = {
      {&metrics.diff_rmse_clean, &metrics.diff_rmse_clean_se}, {&metrics.diff_rmse_noisy, &metrics.diff_rmse_noisy_se},
      {&metrics.diff_mrae_clean, &metrics.diff_mrae_clean_se}, {&metrics.diff_mrae_noisy, &metrics.diff_mrae_noisy_se}};
  std::vector<double> values;
  for (std::size_t i = 0; i < p; ++i)
    for (std::size_t which = 0; which < 4; ++which) {
      values.clear();
      for (std::size_t r : both)
        values.push_back(run_metric(runs[r].filters[f], i, which) - run_metric(runs[r].filters[0], i, which));
      const auto [mean, error] = mean_and_error(values);
      outputs[which].first->push_back(mean);
      outputs[which].second->push_back(error);
    }
}

// Paper 003's AvRMSE and AvMRAE in both readings, over the runs that absorbed every sample.
SampledMetrics sampled_metrics(const std::vector<RunResult>& runs, std::size_t f, std::ptrdiff_t steps,
                               std::size_t p) {
  SampledMetrics metrics;
  std::vector<const FilterRunResult*> complete;
  for (const RunResult& run : runs) {
    const FilterRunResult& filter = run.filters[f];
    metrics.update_failures += filter.update_failed;
    if (filter.last == steps && filter.samples > 0) {
      complete.push_back(&filter);
      metrics.samples = filter.samples;
    }
  }
  metrics.runs = complete.size();
  std::vector<double> values;
  const std::pair<std::vector<double>*, std::vector<double>*> outputs[4] = {
      {&metrics.rmse_clean, &metrics.rmse_clean_se}, {&metrics.rmse_noisy, &metrics.rmse_noisy_se},
      {&metrics.mrae_clean, &metrics.mrae_clean_se}, {&metrics.mrae_noisy, &metrics.mrae_noisy_se}};
  for (std::size_t i = 0; i < p; ++i)
    for (std::size_t which = 0; which < 4; ++which) {
      values.clear();
      for (const FilterRunResult* filter : complete) {
        const double mean = filter->sample_sums[4 * i + which] / static_cast<double>(filter->samples);
        values.push_back(which < 2 ? std::sqrt(mean) : mean);  // RMSE(s) or MRAE(s)
      }
      const auto [mean, error] = mean_and_error(values);
      outputs[which].first->push_back(mean);
      outputs[which].second->push_back(error);
    }
  if (f > 0) paired_differences(runs, f, steps, p, metrics);
  return metrics;
}

// When run r stopped before T for this filter: the filter's own event (divergence, or a PSD loss
// that stopped it), else the truth's; t0 when the truth was refused at its first point.
double stop_time(const RunResult& run, const FilterRunResult& filter, const TimeGrid& grid, bool stop_on_psd_loss) {
  if (filter.diverged) return filter.divergence_t;
  if (filter.psd_lost && stop_on_psd_loss) return filter.psd_t;
  if (run.truth_diverged) return run.truth_divergence_t;
  return grid.t0;
}

// J of filter f over every run and over the runs that reached T (docs/theory.md, "The
// exponential criterion J"); the integrals folded in run order.
CriterionStatistics criterion_statistics(const std::vector<RunResult>& runs, std::size_t f, const TimeGrid& grid,
                                         double epsilon, bool stop_on_psd_loss) {
  CriterionStatistics out;
  out.epsilon = epsilon;
  std::vector<double> completed;
  for (std::size_t r = 0; r < runs.size(); ++r) {
    const FilterRunResult& filter = runs[r].filters[f];
    if (filter.last == static_cast<std::ptrdiff_t>(grid.steps)) {
      out.integrals.push_back(filter.integral);
      completed.push_back(filter.integral);
    } else {
      out.integrals.push_back(nan);
      out.stopped.events.push_back({r, stop_time(runs[r], filter, grid, stop_on_psd_loss)});
    }
  }
  out.completed = estimate_criterion(completed, epsilon);
  if (out.stopped.count() == 0) {
    out.all = out.completed;
  } else {
    const double inf = std::numeric_limits<double>::infinity();
    out.all.runs = runs.size();
    out.all.J = out.all.mean_integral = inf;
    out.all.J_se = out.all.ess = out.all.mean_integral_se = nan;
  }
  return out;
}

// Mean and standard error (sample sd / sqrt(count)) of values, in their order; NaN where undefined.
std::pair<double, double> mean_and_standard_error(const std::vector<double>& values) {
  if (values.empty()) return {nan, nan};
  const double count = static_cast<double>(values.size());
  double sum = 0;
  for (double v : values) sum += v;
  const double mean = sum / count;
  if (values.size() < 2) return {mean, nan};
  double squares = 0;  // about the mean: differences of near-equal mean squares are common
  for (double v : values) squares += (v - mean) * (v - mean);
  return {mean, std::sqrt(squares / (count - 1) / count)};
}

// The standard error of sqrt(mean of values) by the delta method: se(mean) / (2 sqrt(mean)).
double rms_standard_error(const std::vector<double>& squares) {
  const auto [mean, se] = mean_and_standard_error(squares);
  return mean > 0 ? se / (2 * std::sqrt(mean)) : nan;
}

// The reference's own statistics: x - m_ref over the runs it reached T in, its stops, resamplings.
ReferenceStatistics reference_statistics(const Plan& plan, const std::vector<RunResult>& runs, std::size_t particles) {
  const std::size_t n = plan.n;
  const auto steps = static_cast<std::ptrdiff_t>(plan.grid.steps);
  ReferenceStatistics out;
  out.particles = particles;
  WindowStatistics& horizon = out.horizon;
  horizon.first = 0;
  horizon.last = plan.grid.steps;
  horizon.a = plan.grid.t0;
  horizon.b = plan.grid.end();
  std::vector<double> sum(n, 0.0);
  std::uint64_t resamplings = 0;
  std::size_t referenced = 0;
  for (std::size_t r = 0; r < runs.size(); ++r) {
    const ReferenceRunResult& reference = runs[r].reference;
    if (reference.stopped) out.stopped.events.push_back({r, reference.stop_t});
    if (reference.last >= 0) ++referenced;
    resamplings += reference.resamplings;
    if (reference.last != steps) continue;
    ++horizon.runs;
    for (std::size_t i = 0; i < n; ++i) sum[i] += reference.mean_square[i];
  }
  for (std::size_t i = 0; i < n; ++i) {
    horizon.rms.push_back(horizon.runs > 0 ? std::sqrt(sum[i] / static_cast<double>(horizon.runs)) : nan);
    std::vector<double> squares;
    for (const RunResult& run : runs)
      if (run.reference.last == steps) squares.push_back(run.reference.mean_square[i]);
    horizon.rms_se.push_back(rms_standard_error(squares));
  }
  // Its Monte Carlo error from the second particle set: E (m_ref - m_ref')^2 = 2 Var m_ref.
  std::vector<double> spread(n, 0.0);
  for (const RunResult& run : runs) {
    const std::vector<double>& square = run.reference.spread_square;
    if (square.size() != n || !std::isfinite(square[0])) continue;
    ++out.error_runs;
    for (std::size_t i = 0; i < n; ++i) spread[i] += square[i];
  }
  for (std::size_t i = 0; i < n; ++i)
    out.error.push_back(out.error_runs > 0 ? std::sqrt(spread[i] / static_cast<double>(out.error_runs) / 2) : nan);
  out.mean_resamplings = referenced > 0 ? static_cast<double>(resamplings) / static_cast<double>(referenced) : nan;
  return out;
}

// Filter f against the reference over the runs where both reached T.
ReferenceComparison reference_comparison(const Plan& plan, const std::vector<RunResult>& runs, std::size_t f) {
  const std::size_t n = plan.n;
  const auto steps = static_cast<std::ptrdiff_t>(plan.grid.steps);
  ReferenceComparison out;
  std::vector<double> distance(n, 0.0), filter(n, 0.0), reference(n, 0.0);
  for (const RunResult& run : runs) {
    const FilterRunResult& result = run.filters[f];
    if (result.last != steps || run.reference.last != steps) continue;
    ++out.runs;
    for (std::size_t i = 0; i < n; ++i) {
      distance[i] += result.reference_square[i];
      filter[i] += result.mean_square[i];
      reference[i] += run.reference.mean_square[i];
    }
  }
  const double runs_counted = static_cast<double>(out.runs);
  std::vector<double> distances, filters, references;
  for (std::size_t i = 0; i < n; ++i) {
    out.distance.push_back(out.runs > 0 ? std::sqrt(distance[i] / runs_counted) : nan);
    out.filter_rms.push_back(out.runs > 0 ? std::sqrt(filter[i] / runs_counted) : nan);
    out.reference_rms.push_back(out.runs > 0 ? std::sqrt(reference[i] / runs_counted) : nan);
    distances.clear();
    filters.clear();
    references.clear();
    for (const RunResult& run : runs) {
      const FilterRunResult& result = run.filters[f];
      if (result.last != steps || run.reference.last != steps) continue;
      distances.push_back(result.reference_square[i]);
      filters.push_back(result.mean_square[i]);
      references.push_back(run.reference.mean_square[i]);
    }
    out.distance_se.push_back(rms_standard_error(distances));
    out.filter_rms_se.push_back(rms_standard_error(filters));
    out.reference_rms_se.push_back(rms_standard_error(references));
  }
  return out;
}

// Per component, the filter with the smallest RMS(m - m_ref), and its paired margin over the next.
std::vector<ClosestToReference> closest_to_reference(const Plan& plan, const std::vector<RunResult>& runs,
                                                     const std::vector<FilterStatistics>& filters) {
  const std::size_t n = plan.n;
  const auto steps = static_cast<std::ptrdiff_t>(plan.grid.steps);
  std::vector<ClosestToReference> out;
  for (std::size_t i = 0; i < n; ++i) {
    // Filters by distance, in filter order among equals; a filter with no run counted comes last.
    std::vector<std::size_t> order;
    for (std::size_t f = 0; f < filters.size(); ++f)
      if (filters[f].reference && std::isfinite(filters[f].reference->distance[i])) order.push_back(f);
    std::stable_sort(order.begin(), order.end(), [&](std::size_t a, std::size_t b) {
      return filters[a].reference->distance[i] < filters[b].reference->distance[i];
    });
    ClosestToReference c;
    if (order.empty()) {
      out.push_back(c);
      continue;
    }
    c.closest = order[0];
    std::vector<double> differences;
    for (std::size_t k = 1; k < order.size(); ++k) {
      PairedDistance paired;
      paired.filter = order[k];
      differences.clear();
      for (const RunResult& run : runs) {
        const FilterRunResult &a = run.filters[c.closest], &b = run.filters[paired.filter];
        if (a.last != steps || b.last != steps || run.reference.last != steps) continue;
        differences.push_back(b.reference_square[i] - a.reference_square[i]);
      }
      paired.runs = differences.size();
      std::tie(paired.difference, paired.difference_se) = mean_and_standard_error(differences);
      c.others.push_back(paired);
    }
    if (!c.others.empty()) {
      c.runner_up = c.others.front().filter;
      c.runs = c.others.front().runs;
      c.difference = c.others.front().difference;
      c.difference_se = c.others.front().difference_se;
    }
    out.push_back(c);
  }
  return out;
}

// sqrt of the mean of the squares of `values`; NaN when empty. In run order.
double root_mean_square(const std::vector<double>& values) {
  if (values.empty()) return nan;
  double sum = 0;
  for (double v : values) sum += v * v;
  return std::sqrt(sum / static_cast<double>(values.size()));
}

// Window w's standard error of filter f's RMS and its pairing with filter 0, per component, in run order.
void window_errors(const std::vector<RunResult>& runs, std::size_t f, std::size_t w, WindowStatistics& window) {
  const std::size_t n = window.rms.size();
  const auto reached = [&window](const FilterRunResult& filter) {
    return filter.last >= static_cast<std::ptrdiff_t>(window.last);
  };
  std::vector<double> squares, differences;
  for (std::size_t i = 0; i < n; ++i) {
    squares.clear();
    differences.clear();
    for (const RunResult& run : runs) {
      if (!reached(run.filters[f])) continue;
      squares.push_back(run.filters[f].mean_square[w * n + i]);
      if (f > 0 && reached(run.filters[0]))
        differences.push_back(run.filters[f].mean_square[w * n + i] - run.filters[0].mean_square[w * n + i]);
    }
    const double square_se = mean_and_standard_error(squares).second;
    window.rms_se.push_back(window.rms[i] > 0 ? square_se / (2 * window.rms[i]) : nan);
    if (f == 0) continue;
    window.paired_runs = differences.size();
    const auto [mean, se] = mean_and_standard_error(differences);
    window.paired_difference.push_back(mean);
    window.paired_difference_se.push_back(se);
  }
}

// Report q's |e| of filter f paired with filter 0's, per component, over the runs both have alive.
void report_pairs(const std::vector<RunResult>& runs, std::size_t f, std::size_t q, std::size_t n,
                  ReportStatistics& report) {
  if (f == 0) return;
  const auto alive = [&report](const FilterRunResult& filter) {
    return filter.last >= static_cast<std::ptrdiff_t>(report.index);
  };
  std::vector<double> differences;
  for (std::size_t i = 0; i < n; ++i) {
    differences.clear();
    for (const RunResult& run : runs)
      if (alive(run.filters[f]) && alive(run.filters[0]))
        differences.push_back(std::abs(run.filters[f].report_error[q * n + i]) -
                              std::abs(run.filters[0].report_error[q * n + i]));
    report.paired_alive = differences.size();
    const auto [mean, se] = mean_and_standard_error(differences);
    report.paired_abs_difference.push_back(mean);
    report.paired_abs_difference_se.push_back(se);
  }
}

// The mean NEES per state dimension of filter f at each report time and at T, over the runs alive
// there whose P was positive definite, with its 95 % band (Bar-Shalom, Li & Kirubarajan 2001).
void nees_statistics(const std::vector<RunResult>& runs, std::size_t f, const Plan& plan, FilterStatistics& stats) {
  const std::size_t points = plan.reports.size() + 1;
  for (std::size_t q = 0; q < points; ++q) {
    const std::size_t index = q < plan.reports.size() ? plan.reports[q] : plan.grid.steps;
    std::size_t counted = 0;
    double sum = 0;
    for (const RunResult& run : runs) {
      const FilterRunResult& filter = run.filters[f];
      if (filter.last < static_cast<std::ptrdiff_t>(index) || filter.nees.size() != points ||
          !std::isfinite(filter.nees[q]))
        continue;
      ++counted;
      sum += filter.nees[q];
    }
    const NeesBand band = nees_band(counted, plan.n);
    stats.nees_runs.push_back(counted);
    stats.nees.push_back(counted > 0 ? sum / static_cast<double>(counted) / static_cast<double>(plan.n) : nan);
    stats.nees_low.push_back(band.low);
    stats.nees_high.push_back(band.high);
  }
}

}  // namespace

void aggregate(const Plan& plan, const std::vector<FilterModel>& filters, const std::vector<RunResult>& runs,
               const MonteCarloOptions& options, MonteCarloResult& result) {
  const std::size_t n = plan.n, records = plan.records.size();
  const auto steps = static_cast<std::ptrdiff_t>(plan.grid.steps);
  std::vector<double> values;
  values.reserve(runs.size());

  for (std::size_t r = 0; r < runs.size(); ++r)
    if (runs[r].truth_diverged) {
      result.truth_divergences.events.push_back({r, runs[r].truth_divergence_t});
      if (runs[r].truth_covariance_indefinite)
        result.truth_covariance_losses.events.push_back({r, runs[r].truth_divergence_t});
    }

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
      std::vector<double> q = {nan, nan, nan};
      if (!values.empty()) quantiles_in_place(values, {0.05, 0.5, 0.95}, q);
      report.q05.push_back(q[0]);
      report.q50.push_back(q[1]);
      report.q95.push_back(q[2]);
    }
    result.truth_reports.push_back(std::move(report));
  }

  for (std::size_t f = 0; f < filters.size(); ++f) {
    FilterStatistics stats;
    stats.name = filters[f].name;
    stats.grid_stepped = filters[f].timing->refines_steps();
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
      window_errors(runs, f, w, window);
      if (w == 0)
        stats.horizon = std::move(window);
      else
        stats.windows.push_back(std::move(window));
    }
    for (std::size_t q = 0; q < plan.reports.size(); ++q) {
      ReportStatistics report;
      report.index = plan.reports[q];
      report.t = plan.grid.time(report.index);
      std::vector<double> sum_abs(n, 0.0), sum_square(n, 0.0), sum(n, 0.0);
      for (const RunResult& run : runs) {
        const FilterRunResult& filter = run.filters[f];
        if (filter.last < static_cast<std::ptrdiff_t>(report.index)) continue;
        ++report.alive;
        for (std::size_t i = 0; i < n; ++i) {
          const double e = filter.report_error[q * n + i];
          sum_abs[i] += std::abs(e);
          sum_square[i] += e * e;
          sum[i] += e;
        }
      }
      const double alive = static_cast<double>(report.alive);
      // Standard error of a mean whose values' squares sum to sum_square: e^2 = |e|^2, so one sum
      // serves the signed and the absolute error.
      auto standard_error = [&](double mean, double squares) {
        if (report.alive < 2) return nan;
        const double variance = (squares - alive * mean * mean) / (alive - 1);
        return std::sqrt(std::max(variance, 0.0) / alive);
      };
      report_pairs(runs, f, q, n, report);
      for (std::size_t i = 0; i < n; ++i) {
        report.mean_abs.push_back(report.alive > 0 ? sum_abs[i] / alive : nan);
        report.rms.push_back(report.alive > 0 ? std::sqrt(sum_square[i] / alive) : nan);
        report.mean_error.push_back(report.alive > 0 ? sum[i] / alive : nan);
        report.mean_error_se.push_back(standard_error(report.mean_error.back(), sum_square[i]));
        report.mean_abs_se.push_back(standard_error(report.mean_abs.back(), sum_square[i]));
      }
      stats.reports.push_back(std::move(report));
    }
    for (std::size_t i = 0; i < n; ++i) {
      values.clear();
      for (const RunResult& run : runs)
        if (run.filters[f].last == steps) values.push_back(run.filters[f].peak[i]);
      std::vector<double> q = {nan, nan};
      if (!values.empty()) quantiles_in_place(values, {0.5, 0.95}, q);
      stats.peak_median.push_back(q[0]);
      stats.peak_q95.push_back(q[1]);
    }
    for (std::size_t r = 0; r < runs.size(); ++r) {
      const FilterRunResult& filter = runs[r].filters[f];
      if (filter.diverged) stats.divergences.events.push_back({r, filter.divergence_t});
      if (filter.psd_lost) stats.psd_losses.events.push_back({r, filter.psd_t});
      stats.refined_steps += filter.refined_steps;
      stats.refined_runs += filter.refined_steps > 0;
      stats.too_stiff_runs += filter.too_stiff;
      stats.undefined_runs += filter.undefined;
      if (filter.unrealisable) stats.unrealisable.events.push_back({r, filter.divergence_t});
    }
    nees_statistics(runs, f, plan, stats);
    if (filters[f].timing->takes_samples()) stats.sampled = sampled_metrics(runs, f, steps, filters[f].p);
    if (options.criterion) stats.criterion = criterion_statistics(runs, f, plan.grid, options.criterion->epsilon,
                                                                 options.filter_guards.stop_on_psd_loss);
    if (options.reference) stats.reference = reference_comparison(plan, runs, f);
    result.filters.push_back(std::move(stats));
  }

  if (options.reference) {
    result.reference = reference_statistics(plan, runs, options.reference->particles);
    result.reference->closest = closest_to_reference(plan, runs, result.filters);
  }

  MonteCarloSeries& series = result.series;
  series.index = plan.records;
  for (std::size_t k : plan.records) series.t.push_back(plan.grid.time(k));
  series.shown_run = options.shown_run;
  const RunResult& shown = runs[options.shown_run];
  series.truth = records_matrix(shown.truth_record, records, n);
  for (std::size_t f = 0; f < filters.size(); ++f) {
    FilterSeries& filter = series.filters[f];
    filter.m = records_matrix(shown.filters[f].m_record, records, n);
    filter.P_diagonal = records_matrix(shown.filters[f].P_record, records, n);
    if (options.reference) filter.reference_distance = records_matrix(shown.filters[f].reference_record, records, n);
  }
  if (options.reference) series.reference_m = records_matrix(shown.reference.m_record, records, n);
}

void start_series(const Plan& plan, std::size_t filters, bool reference, MonteCarloSeries& series) {
  const std::size_t n = plan.n, records = plan.records.size();
  const auto rows = static_cast<Eigen::Index>(records), cols = static_cast<Eigen::Index>(n);
  series.truth_statistics = make_series_statistics(records, n);
  series.truth_alive.assign(records, 0);
  series.filters.assign(filters, FilterSeries{});
  for (FilterSeries& filter : series.filters) {
    filter.error = make_series_statistics(records, n);
    filter.alive.assign(records, 0);
    filter.error_rms.resize(rows, cols);
    filter.nees.resize(rows, 1);
    filter.nees_runs.assign(records, 0);
    if (reference) filter.reference_distance_rms.resize(rows, cols);
  }
  if (reference) series.reference_error_rms.resize(rows, cols);
}

void fold_series(const Plan& plan, std::size_t filters, const std::vector<RunRows>& runs, RecordRange range,
                 bool reference, unsigned threads, MonteCarloSeries& series) {
  const std::size_t n = plan.n;
  // Across runs at each record time. Record times are independent (each writes its own rows), so
  // blocks of them are shared among threads without changing a bit. A block's values are gathered
  // run by run, each run's records of the block read in one sweep (not one run per value, which
  // misses the cache once per value), into one column per (record, state) that holds the runs in
  // run order, as the statistics read them.
  constexpr std::size_t kBlock = 16;
  const std::size_t blocks = (range.size() + kBlock - 1) / kBlock;
  auto scratch = [&runs, n](unsigned) {
    std::vector<std::vector<double>> columns(kBlock * n);
    for (auto& column : columns) column.reserve(runs.size());
    return columns;
  };
  parallel_for(blocks, threads, scratch, [&](std::size_t block, std::vector<std::vector<double>>& columns) {
    const std::size_t r0 = range.first + block * kBlock, r1 = std::min(range.last, r0 + kBlock);
    auto column = [&](std::size_t r, std::size_t i) -> std::vector<double>& { return columns[(r - r0) * n + i]; };
    // columns(r, i) = value(run, r * n + i) of every run with alive(run, record index of r), in
    // run order; a run's record vectors start at the range's first record.
    auto gather = [&](auto alive, auto value) {
      for (auto& c : columns) c.clear();
      for (const RunRows& run : runs)
        for (std::size_t r = r0; r < r1; ++r)
          if (alive(run, static_cast<std::ptrdiff_t>(plan.records[r])))
            for (std::size_t i = 0; i < n; ++i) column(r, i).push_back(value(run, (r - range.first) * n + i));
    };
    gather([](const RunRows& run, std::ptrdiff_t index) { return run.truth_last >= index; },
           [](const RunRows& run, std::size_t at) { return row_value(run.truth, at); });
    for (std::size_t r = r0; r < r1; ++r) {
      series.truth_alive[r] = column(r, 0).size();
      for (std::size_t i = 0; i < n; ++i)
        summarize(column(r, i), series.truth_statistics, static_cast<Eigen::Index>(r), static_cast<Eigen::Index>(i));
    }
    for (std::size_t f = 0; f < filters; ++f) {
      FilterSeries& filter = series.filters[f];
      gather([f](const RunRows& run, std::ptrdiff_t index) { return run.filters[f].last >= index; },
             [f](const RunRows& run, std::size_t at) { return row_value(run.filters[f].error, at); });
      for (std::size_t r = r0; r < r1; ++r) {
        filter.alive[r] = column(r, 0).size();
        for (std::size_t i = 0; i < n; ++i) {
          const auto row = static_cast<Eigen::Index>(r), entry = static_cast<Eigen::Index>(i);
          filter.error_rms(row, entry) = root_mean_square(column(r, i));  // before summarize reorders it
          summarize(column(r, i), filter.error, row, entry);
        }
      }
      // NEES per state dimension: one value a record, in the first state's column of the block.
      for (auto& c : columns) c.clear();
      for (const RunRows& run : runs)
        for (std::size_t r = r0; r < r1; ++r)
          if (run.filters[f].last >= static_cast<std::ptrdiff_t>(plan.records[r])) {
            const double value = row_value(run.filters[f].nees, r - range.first);
            if (std::isfinite(value)) column(r, 0).push_back(value);
          }
      for (std::size_t r = r0; r < r1; ++r) {
        const std::vector<double>& values = column(r, 0);
        double sum = 0;
        for (double v : values) sum += v;  // in run order
        filter.nees_runs[r] = values.size();
        filter.nees(static_cast<Eigen::Index>(r), 0) =
            values.empty() ? nan : sum / static_cast<double>(values.size()) / static_cast<double>(n);
      }
    }
    if (!reference) return;
    gather([](const RunRows& run, std::ptrdiff_t index) { return run.reference_last >= index; },
           [](const RunRows& run, std::size_t at) { return row_value(run.reference_error, at); });
    for (std::size_t r = r0; r < r1; ++r)
      for (std::size_t i = 0; i < n; ++i)
        series.reference_error_rms(static_cast<Eigen::Index>(r), static_cast<Eigen::Index>(i)) =
            root_mean_square(column(r, i));
    for (std::size_t f = 0; f < filters; ++f) {
      gather([f](const RunRows& run, std::ptrdiff_t index) {
               return run.reference_last >= index && run.filters[f].last >= index;
             },
             [f](const RunRows& run, std::size_t at) { return row_value(run.filters[f].reference, at); });
      for (std::size_t r = r0; r < r1; ++r)
        for (std::size_t i = 0; i < n; ++i)
          series.filters[f].reference_distance_rms(static_cast<Eigen::Index>(r), static_cast<Eigen::Index>(i)) =
              root_mean_square(column(r, i));
    }
  });
}

}  // namespace pfgen_runtime::monte_carlo_detail
