#include "pfgen_runtime/summary_table.hpp"

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <cstdio>
#include <sstream>
#include <stdexcept>

namespace pfgen_runtime {

namespace {

// printf-style formatting of one finite number; '-' for anything undefined.
std::string number(double value, const char* format = "%.4g") {
  if (!std::isfinite(value)) return "-";
  char buffer[64];
  std::snprintf(buffer, sizeof buffer, format, value);
  return buffer;
}

std::string time(double t) { return number(t, "%.6g"); }

std::string count(std::size_t value) { return std::to_string(value); }

// A mean with its standard error, and a paired difference (signed) with its standard error: the
// cells of every table below.
std::string cell(double mean, double error) { return number(mean) + " ± " + number(error, "%.2g"); }
std::string difference_cell(double mean, double error) {
  return number(mean, "%+.4g") + " ± " + number(error, "%.2g");
}

// Rows of cells, first column left-aligned, the rest right-aligned, two spaces between.
std::string align(const std::vector<std::vector<std::string>>& rows) {
  std::vector<std::size_t> width;
  for (const auto& row : rows)
    for (std::size_t c = 0; c < row.size(); ++c) {
      if (width.size() <= c) width.push_back(0);
      width[c] = std::max(width[c], row[c].size());
    }
  std::ostringstream out;
  for (const auto& row : rows) {
    std::string line;
    for (std::size_t c = 0; c < row.size(); ++c) {
      const std::string pad(width[c] - row[c].size(), ' ');
      if (c > 0) line += "  ";
      line += c == 0 ? row[c] + pad : pad + row[c];
    }
    while (!line.empty() && line.back() == ' ') line.pop_back();
    out << line << '\n';
  }
  return out.str();
}

std::string events_line(const char* what, const EventSummary& events, std::size_t runs) {
  std::ostringstream out;
  out << what << ": ";
  if (events.count() == 0)
    out << "no run";
  else
    out << events.count() << " of " << runs << " runs, first at t = " << time(events.earliest())
        << ", median t = " << time(events.median());
  return out.str();
}

// "  optimal: 17 at 8.346, 143 at 8.721, ... (67 runs)": the first few runs in run order.
std::string run_list(const std::string& label, const EventSummary& events) {
  constexpr std::size_t shown = 8;
  std::ostringstream out;
  out << label << ":";
  for (std::size_t k = 0; k < events.events.size() && k < shown; ++k)
    out << (k ? ", " : " ") << events.events[k].run << " at " << time(events.events[k].t);
  if (events.events.size() > shown) out << ", ... (" << events.events.size() << " runs)";
  return out.str();
}

// Allahyani & Date's metrics of the sampled filters, each as "mean ± standard error" over the runs.
std::string sampled_section(const MonteCarloResult& result) {
  std::vector<std::vector<std::string>> rows{{"filter", "output", "runs", "samples", "AvRMSE clean", "AvMRAE clean",
                                              "AvRMSE noisy", "AvMRAE noisy"}};
  std::ostringstream failures;
  for (const FilterStatistics& filter : result.filters) {
    if (!filter.sampled) continue;
    const SampledMetrics& m = *filter.sampled;
    for (std::size_t i = 0; i < m.rmse_clean.size(); ++i)
      rows.push_back({filter.name, "y" + std::to_string(i + 1), count(m.runs), count(m.samples),
                      cell(m.rmse_clean[i], m.rmse_clean_se[i]), cell(m.mrae_clean[i], m.mrae_clean_se[i]),
                      cell(m.rmse_noisy[i], m.rmse_noisy_se[i]), cell(m.mrae_noisy[i], m.mrae_noisy_se[i])});
    if (m.update_failures > 0) failures << "  " << filter.name << ": " << m.update_failures << " runs\n";
  }
  if (rows.size() == 1) return "";
  const bool nonlinear = std::any_of(result.filters.begin(), result.filters.end(),
                                     [](const FilterStatistics& f) { return f.sampled && f.sampled->nonlinear; });
  std::string out =
      std::string(nonlinear ? "\nAt the samples t_k (Allahyani & Date's metrics; Yhat = c(m(t_k|t_k)), which for a nonlinear c is "
                              "not the filter's E[c]; clean: Y = c(x(t_k)), noisy: Y = y_k; "
                            : "\nAt the samples t_k (Allahyani & Date's metrics; Yhat = C0 + C m(t_k|t_k); clean: Y = C0 + C x(t_k), noisy: Y = y_k; ") +
      "mean over the runs that absorbed every sample ± standard error):\n" + align(rows);
  // The same metrics paired run by run against the first filter: the standard error of a
  // difference, without the spread the runs share.
  std::vector<std::vector<std::string>> paired{{"filter", "output", "runs", "dAvRMSE clean", "dAvMRAE clean",
                                                "dAvRMSE noisy", "dAvMRAE noisy"}};
  for (const FilterStatistics& filter : result.filters) {
    if (!filter.sampled || filter.sampled->diff_rmse_clean.empty()) continue;
    const SampledMetrics& m = *filter.sampled;
    for (std::size_t i = 0; i < m.diff_rmse_clean.size(); ++i)
      paired.push_back({filter.name, "y" + std::to_string(i + 1), count(m.paired_runs),
                        difference_cell(m.diff_rmse_clean[i], m.diff_rmse_clean_se[i]),
                        difference_cell(m.diff_mrae_clean[i], m.diff_mrae_clean_se[i]),
                        difference_cell(m.diff_rmse_noisy[i], m.diff_rmse_noisy_se[i]),
                        difference_cell(m.diff_mrae_noisy[i], m.diff_mrae_noisy_se[i])});
  }
  if (paired.size() > 1)
    out += "\nPaired against " + result.filters.front().name +
           " (per run: this filter's RMSE(s) or MRAE(s) minus its, over the runs both completed; mean ± standard "
           "error):\n" +
           align(paired);
  if (!failures.str().empty())
    out += "\nRuns stopped by an update whose C P C^T + Uv Uv^T was not positive definite (counted as diverged):\n" +
           failures.str();
  return out;
}

// The main table's RMS and |e|@t with their standard errors, and each filter paired run by run with
// the first: whether 0.2189 and 0.2156 differ is the paired difference against its standard error,
// without the spread the runs share.
std::string precision_section(const MonteCarloResult& result, const std::vector<std::string>& state_names) {
  const FilterStatistics& first = result.filters.front();
  auto window_header = [](const char* what, const WindowStatistics& w) {
    return what + ("[" + time(w.a) + "," + time(w.b) + "]");
  };
  std::vector<std::vector<std::string>> errors{{"filter", "state", window_header("RMS", first.horizon)}};
  std::vector<std::vector<std::string>> paired{{"filter", "state", "runs", window_header("dMS", first.horizon)}};
  for (const WindowStatistics& w : first.windows) {
    errors.front().push_back(window_header("RMS", w));
    paired.front().push_back(window_header("dMS", w));
  }
  for (const ReportStatistics& r : first.reports) {
    errors.front().push_back("|e|@" + time(r.t));
    paired.front().push_back("d|e|@" + time(r.t));
  }
  for (const FilterStatistics& filter : result.filters)
    for (std::size_t i = 0; i < result.n; ++i) {
      std::vector<std::string> row{filter.name, state_names[i], cell(filter.horizon.rms[i], filter.horizon.rms_se[i])};
      for (const WindowStatistics& w : filter.windows) row.push_back(cell(w.rms[i], w.rms_se[i]));
      for (const ReportStatistics& r : filter.reports) row.push_back(cell(r.mean_abs[i], r.mean_abs_se[i]));
      errors.push_back(std::move(row));
      if (filter.horizon.paired_difference.empty()) continue;
      std::vector<std::string> pair{filter.name, state_names[i], count(filter.horizon.paired_runs),
                                    difference_cell(filter.horizon.paired_difference[i], filter.horizon.paired_difference_se[i])};
      for (const WindowStatistics& w : filter.windows)
        pair.push_back(difference_cell(w.paired_difference[i], w.paired_difference_se[i]));
      for (const ReportStatistics& r : filter.reports)
        pair.push_back(difference_cell(r.paired_abs_difference[i], r.paired_abs_difference_se[i]));
      paired.push_back(std::move(pair));
    }
  std::string out =
      "\nWith standard errors over the runs counted (RMS: the delta method on the runs' mean squares; |e|@t: of the "
      "mean):\n" +
      align(errors);
  if (paired.size() > 1)
    out += "\nPaired against " + first.name +
           " run by run (dMS: this filter's mean square error over the window minus its, over the runs both "
           "completed; d|e|@t: |e| minus its, over the runs both have at t; mean ± standard error; the first "
           "runs column counts the horizon):\n" +
           align(paired);
  return out;
}

// The consistency of each filter's P against its errors (Bar-Shalom, Li & Kirubarajan 2001's NEES
// test) at the report times and at T.
std::string consistency_section(const MonteCarloResult& result) {
  std::vector<std::vector<std::string>> rows{{"filter", "t", "runs", "NEES/n", "95 % band", "P is"}};
  for (const FilterStatistics& filter : result.filters)
    for (std::size_t q = 0; q < filter.nees.size(); ++q) {
      const double t = q < filter.reports.size() ? filter.reports[q].t : result.grid.end();
      // T once, when it is also a report time; nothing where no run had a definite P (a
      // deterministic truth's P = 0, or every run stopped).
      const bool repeated = q == filter.reports.size() && q > 0 && filter.reports[q - 1].t == t;
      if (repeated || filter.nees_runs[q] == 0) continue;
      const double nees = filter.nees[q], low = filter.nees_low[q], high = filter.nees_high[q];
      const std::string verdict = !std::isfinite(nees) ? "-"
                                  : nees > high        ? "too small"
                                  : nees < low         ? "too large"
                                                       : "consistent";
      rows.push_back({filter.name, time(t), count(filter.nees_runs[q]), number(nees),
                      number(low, "%.3g") + " - " + number(high, "%.3g"), verdict});
    }
  if (rows.size() == 1) return "";
  return "\nConsistency of P (NEES/n: (x - m)^T P^-1 (x - m) / n averaged over the runs alive whose P is positive "
         "definite; for a consistent filter runs x n x NEES/n is chi-square with runs x n degrees of freedom, whose "
         "two-sided 95 % interval is the band; above it P is too small for the errors, below it too large):\n" +
         align(rows);
}

// How L was weighted: "M = identity" or the matrix row by row.
std::string weight_text(const Eigen::MatrixXd& weight) {
  if (weight.size() == 0) return "M = identity";
  std::string text = "M = [";
  for (Eigen::Index i = 0; i < weight.rows(); ++i) {
    text += i ? "; " : "";
    for (Eigen::Index j = 0; j < weight.cols(); ++j) text += (j ? ", " : "") + number(weight(i, j), "%.6g");
  }
  return text + "]";
}

// J may be infinite on purpose (a run stopped before T): "inf", not '-'.
std::string criterion_number(double value) { return std::isinf(value) ? "inf" : number(value); }

std::vector<std::string> criterion_cells(const CriterionEstimate& e) {
  return {count(e.runs), criterion_number(e.J), number(e.J_se, "%.2g"), number(e.ess, "%.4g"),
          criterion_number(e.mean_integral), number(e.mean_integral_se, "%.2g")};
}

// The exponential criterion per filter (docs/theory.md, "The exponential criterion J"); empty when
// it was not asked for, so other tables keep their bytes.
std::string criterion_section(const MonteCarloResult& result) {
  if (!result.criterion || result.filters.empty() || !result.filters.front().criterion) return "";
  const double epsilon = result.filters.front().criterion->epsilon;
  std::vector<std::vector<std::string>> rows{
      {"filter", "runs", "J", "se", "ESS", "mean int L", "se", "stopped", "first stop t"}};
  std::vector<std::vector<std::string>> conditional{{"filter", "runs", "J", "se", "ESS", "mean int L", "se"}};
  for (const FilterStatistics& filter : result.filters) {
    const CriterionStatistics& c = *filter.criterion;
    std::vector<std::string> row{filter.name};
    for (std::string& cell : criterion_cells(c.all)) row.push_back(std::move(cell));
    row.push_back(count(c.stopped.count()));
    row.push_back(time(c.stopped.earliest()));
    rows.push_back(std::move(row));
    if (c.stopped.count() > 0) {
      std::vector<std::string> only{filter.name};
      for (std::string& cell : criterion_cells(c.completed)) only.push_back(std::move(cell));
      conditional.push_back(std::move(only));
    }
  }
  std::string out = "\nExponential criterion J = eps log E[exp(int_0^T L dt / eps)], eps = " + number(epsilon, "%.6g") +
                    ", L = (x - m)^T M (x - m), " + weight_text(result.criterion->weight) +
                    " (int L per run by the trapezoid rule on the grid; se: delta method; ESS: effective sample "
                    "size; J = inf when a run stopped before T):\n" +
                    align(rows);
  if (conditional.size() > 1)
    out += "\nThe same over the runs that reached T only (conditional on no stop; not J):\n" + align(conditional);
  return out;
}

// How far each filter's m is from the particle reference's m_ref (docs/theory.md §7.4); empty
// without a reference, so other tables keep their bytes.
std::string reference_section(const MonteCarloResult& result, const std::vector<std::string>& state_names) {
  if (!result.reference) return "";
  const ReferenceStatistics& reference = *result.reference;
  std::vector<std::vector<std::string>> rows{
      {"filter", "state", "runs", "RMS(m - m_ref)", "m_ref's own error", "RMS(x - m)", "RMS(x - m_ref)"}};
  const auto own_error = [&reference](std::size_t i) {
    return i < reference.error.size() ? number(reference.error[i]) : std::string("-");
  };
  for (const FilterStatistics& filter : result.filters) {
    if (!filter.reference) continue;
    const ReferenceComparison& c = *filter.reference;
    for (std::size_t i = 0; i < result.n; ++i)
      rows.push_back({filter.name, state_names[i], count(c.runs), cell(c.distance[i], c.distance_se[i]), own_error(i),
                      cell(c.filter_rms[i], c.filter_rms_se[i]), cell(c.reference_rms[i], c.reference_rms_se[i])});
  }
  for (std::size_t i = 0; i < result.n; ++i)
    rows.push_back({"reference", state_names[i], count(reference.horizon.runs), "", own_error(i), "",
                    cell(reference.horizon.rms[i], reference.horizon.rms_se[i])});
  std::ostringstream out;
  out << "\nDistance to the particle reference (N = " << reference.particles
      << " particles, bootstrap filter from the filters' prior; RMS over the runs and grid points of [" << time(result.grid.t0)
      << ", " << time(result.grid.end()) << "] where the filter and the reference reached T, ± standard error over "
      << "runs; reference: every run it reached T in; m_ref's own error: its Monte Carlo error, RMS(m_ref - m_ref') / "
      << "sqrt(2) with m_ref' a second, independent set of N particles, over the " << reference.error_runs
      << " runs both reached T in):\n"
      << align(rows);
  // A distance d measured against m_ref is about sqrt(d^2 + e^2) with e the reference's own error:
  // where e is not small against the smallest distance, the distances say more about N than about
  // the filters.
  for (std::size_t i = 0; i < reference.closest.size() && i < result.n && i < reference.error.size(); ++i) {
    if (reference.closest[i].closest >= result.filters.size()) continue;
    const FilterStatistics& closest = result.filters[reference.closest[i].closest];
    if (!closest.reference) continue;
    const double distance = closest.reference->distance[i], error = reference.error[i];
    if (std::isfinite(distance) && std::isfinite(error) && 3 * error > distance)
      out << "Note: in " << state_names[i] << " the reference's own error " << number(error)
          << " is not small against the smallest distance (" << closest.name << "'s " << number(distance)
          << "), which it inflates to about sqrt(d^2 + " << number(error) << "^2): use more particles (the error falls "
          << "as 1/sqrt(N))\n";
  }
  // Which filter is closest, said only where the paired difference to the next one exceeds twice
  // its standard error: 0.119 against 0.138 may be one seed's luck.
  for (std::size_t i = 0; i < reference.closest.size() && i < result.n; ++i) {
    const ClosestToReference& c = reference.closest[i];
    if (!c.runner_up) continue;
    const std::string& closest = result.filters[c.closest].name;
    const std::string& next = result.filters[*c.runner_up].name;
    out << "Closest in " << state_names[i] << ": ";
    if (c.significant())
      out << closest << " (" << next << "'s mean squared distance is larger by " << number(c.difference) << " ± "
          << number(c.difference_se, "%.2g") << ", paired over " << c.runs << " runs)\n";
    else
      out << "no filter significantly (" << closest << " and " << next << " differ by " << number(c.difference)
          << " ± " << number(c.difference_se, "%.2g") << " in mean squared distance, paired over " << c.runs
          << " runs: within 2 standard errors)\n";
  }
  out << events_line("Reference stopped (every particle diverged)", reference.stopped, result.runs)
      << "; resampled " << number(reference.mean_resamplings, "%.1f") << " times per run\n";
  // Every filter against the closest, so that the farthest is called worse only where it is.
  std::vector<std::vector<std::string>> paired{{"filter", "state", "closest", "runs", "dMS(m - m_ref)", "worse"}};
  for (std::size_t i = 0; i < reference.closest.size() && i < result.n; ++i)
    for (const PairedDistance& other : reference.closest[i].others)
      paired.push_back({result.filters[other.filter].name, state_names[i],
                        result.filters[reference.closest[i].closest].name, count(other.runs),
                        difference_cell(other.difference, other.difference_se),
                        other.significant() ? "yes" : "not significantly"});
  if (paired.size() > 1)
    out << "\nPaired against the closest to the reference run by run (dMS: this filter's mean squared distance to "
           "m_ref minus the closest's, over the runs where both and the reference reached T; mean ± standard error; "
           "worse: beyond 2 standard errors):\n"
        << align(paired);
  return out.str();
}

// Which stepping the main table's figures are of (docs/guide/simulation.md, "How a job runs", 4):
// refined splits a grid step the generated step() would take whole, so where it did, the table is
// not quite the deployed code's; empty when no filter steps on the grid (sampled, delayed).
std::string stepping_line(const MonteCarloResult& result) {
  std::uint64_t refined = 0;
  bool any = false;
  for (const FilterStatistics& filter : result.filters)
    if (filter.grid_stepped) {
      any = true;
      refined += filter.refined_steps;
    }
  if (!any) return "";
  if (!result.refined_stepping)
    return "Stepping: generated (one step() call per grid step, as the generated code runs)\n";
  if (refined == 0)
    return "Stepping: refined, no grid step split (these are the figures of the generated step() as it runs)\n";
  return "Stepping: refined (grid steps split into sub-steps where P would change too fast, listed below; the "
         "generated step() never splits one: --stepping generated measures it as it runs)\n";
}

}  // namespace

std::string format_summary_table(const MonteCarloResult& result, const std::vector<std::string>& state_names) {
  if (state_names.size() != result.n)
    throw std::invalid_argument("summary table: need one name per state component");
  std::ostringstream out;
  out << "Monte Carlo: " << result.runs << " runs, t in [" << time(result.grid.t0) << ", " << time(result.grid.end())
      << "], dt = " << time(result.grid.dt) << " (" << result.grid.steps << " steps), seed " << result.seed
      << ", truth scheme " << result.scheme << (result.x0_from_prior ? ", truth x0 drawn from N(m0, P0) per run" : "")
      << "\n";
  if (result.filters.empty()) {
    out << "(no filters)\n";
  } else {
    // Column headers from the first filter: every filter has the same windows and report times.
    const FilterStatistics& first = result.filters.front();
    auto window_header = [](const WindowStatistics& w) { return "RMS[" + time(w.a) + "," + time(w.b) + "]"; };
    std::vector<std::string> header{"filter", "state", window_header(first.horizon)};
    for (const WindowStatistics& w : first.windows) header.push_back(window_header(w));
    for (const ReportStatistics& r : first.reports) header.push_back("|e|@" + time(r.t));
    for (const char* h : {"peak|e| med", "peak|e| q95", "diverged", "div first t", "div median t", "PSD loss", "PSD first t"})
      header.push_back(h);
    std::vector<std::vector<std::string>> rows{header};
    std::vector<std::vector<std::string>> counts{{"filter", "completed"}};
    for (const WindowStatistics& w : first.windows) counts.front().push_back(window_header(w));
    for (const ReportStatistics& r : first.reports) counts.front().push_back("|e|@" + time(r.t));

    for (const FilterStatistics& filter : result.filters) {
      for (std::size_t i = 0; i < result.n; ++i) {
        std::vector<std::string> row{filter.name, state_names[i], number(filter.horizon.rms[i])};
        for (const WindowStatistics& w : filter.windows) row.push_back(number(w.rms[i]));
        for (const ReportStatistics& r : filter.reports) row.push_back(number(r.mean_abs[i]));
        row.push_back(number(filter.peak_median[i]));
        row.push_back(number(filter.peak_q95[i]));
        row.push_back(count(filter.divergences.count()));
        row.push_back(time(filter.divergences.earliest()));
        row.push_back(time(filter.divergences.median()));
        row.push_back(count(filter.psd_losses.count()));
        row.push_back(time(filter.psd_losses.earliest()));
        rows.push_back(std::move(row));
      }
      std::vector<std::string> row{filter.name, count(filter.horizon.runs)};
      for (const WindowStatistics& w : filter.windows) row.push_back(count(w.runs));
      for (const ReportStatistics& r : filter.reports) row.push_back(count(r.alive));
      counts.push_back(std::move(row));
    }
    out << align(rows);
    out << stepping_line(result);
    out << "\nRuns counted (truth and filter alive to the window's end, or at the report time):\n" << align(counts);
    out << precision_section(result, state_names);
    out << consistency_section(result);
    // Which runs stopped, so that one can be looked at (--shown-run) and replayed.
    std::ostringstream stopped;
    for (const FilterStatistics& filter : result.filters)
      if (filter.divergences.count() > 0) stopped << run_list("  " + filter.name, filter.divergences) << "\n";
    if (!stopped.str().empty()) out << "\nDiverged runs (run index at t):\n" << stopped.str();
    std::ostringstream refined;
    for (const FilterStatistics& filter : result.filters)
      if (filter.refined_steps > 0)
        refined << "  " << filter.name << ": " << filter.refined_steps << " steps in " << filter.refined_runs << " runs\n";
    if (!refined.str().empty())
      out << "\nGrid steps integrated in sub-steps (one step would have changed P by more than its tolerance):\n"
          << refined.str();
    // Runs stopped for a reason of their own, a section each: "  name: N runs" per filter with any.
    auto stopped_runs = [&](const std::string& heading, auto runs_of) {
      std::ostringstream lines;
      for (const FilterStatistics& filter : result.filters)
        if (runs_of(filter) > 0) lines << "  " << filter.name << ": " << runs_of(filter) << " runs\n";
      if (!lines.str().empty()) out << "\n" << heading << ":\n" << lines.str();
    };
    stopped_runs("Runs stopped as too stiff for dt (a grid step needed more filter sub-steps than allowed; counted as "
                 "diverged)",
                 [](const FilterStatistics& f) { return f.too_stiff_runs; });
    stopped_runs("Runs stopped where the filter's equations were not finite at its own state (a definition, such as "
                 "a Cholesky entry, could not be computed there; counted as diverged; no smaller step would help)",
                 [](const FilterStatistics& f) { return f.undefined_runs; });
    stopped_runs("Runs stopped where a moment filter's moments left the realisable set (P not positive definite, "
                 "or a state's kurtosis below Pearson's bound 1 + skewness^2; counted as diverged; the closure's "
                 "known failure, docs/theory.md §2.10)",
                 [](const FilterStatistics& f) { return f.unrealisable.count(); });
    out << reference_section(result, state_names);
    out << sampled_section(result);
    out << criterion_section(result);
  }
  out << "\n" << events_line("Truth diverged", result.truth_divergences, result.runs) << "\n";
  if (result.truth_covariance_losses.count() > 0)
    out << events_line("  of which stopped where the diffusion covariance G lost positive semi-definiteness",
                       result.truth_covariance_losses, result.runs)
        << "\n";
  if (!result.truth_reports.empty()) {
    std::vector<std::vector<std::string>> rows{{"truth at", "state", "runs", "mean", "q05", "median", "q95"}};
    for (const TruthReportStatistics& report : result.truth_reports)
      for (std::size_t i = 0; i < result.n; ++i)
        rows.push_back({"t = " + time(report.t), state_names[i], count(report.alive), number(report.mean[i]),
                        number(report.q05[i]), number(report.q50[i]), number(report.q95[i])});
    out << "\nTruth at the report times (over the runs whose truth is alive there):\n" << align(rows);
  }
  return out.str();
}

std::string format_report_errors(const MonteCarloResult& result, const std::vector<std::string>& state_names) {
  if (state_names.size() != result.n)
    throw std::invalid_argument("report errors: need one name per state component");
  if (result.filters.empty() || result.filters.front().reports.empty()) return "";
  std::vector<std::vector<std::string>> rows{{"filter", "state", "t", "runs", "mean e", "se", "mean |e|", "se"}};
  for (const FilterStatistics& filter : result.filters)
    for (const ReportStatistics& r : filter.reports)
      for (std::size_t i = 0; i < result.n; ++i)
        rows.push_back({filter.name, state_names[i], time(r.t), count(r.alive), number(r.mean_error[i]),
                        number(r.mean_error_se[i], "%.2g"), number(r.mean_abs[i]), number(r.mean_abs_se[i], "%.2g")});
  return "\nErrors at the report times (e = x - m over the runs counted; se: standard error over runs):\n" + align(rows);
}

std::string format_timing(const MonteCarloResult& result) {
  const MonteCarloTiming& timing = result.timing;
  // "1.234 thread-s, 56.7 ns/step (CPU 55.1 ns/step)": elapsed and CPU time per step.
  auto phase = [](double seconds, double cpu_seconds, std::uint64_t steps) {
    std::string text = number(seconds, "%.3f") + " thread-s";
    if (steps > 0) {
      const double per_step = 1e9 / static_cast<double>(steps);
      text += ", " + number(seconds * per_step, "%.1f") + " ns/step (CPU " + number(cpu_seconds * per_step, "%.1f") +
              " ns/step)";
    }
    return text;
  };
  std::ostringstream out;
  out << "Timing: " << number(timing.wall_seconds, "%.3f") << " s wall on " << timing.threads << " thread"
      << (timing.threads == 1 ? "" : "s") << "\n  truth: "
      << phase(timing.truth_seconds, timing.truth_cpu_seconds, timing.truth_steps) << "\n";
  for (std::size_t f = 0; f < result.filters.size() && f < timing.filter_seconds.size(); ++f) {
    out << "  " << result.filters[f].name << ": "
        << phase(timing.filter_seconds[f], timing.filter_cpu_seconds[f], timing.filter_steps[f]);
    // Sampled filters: the time per sample, predictions, update and the grid's bookkeeping included.
    if (f < timing.filter_samples.size() && timing.filter_samples[f] > 0)
      out << ", " << number(timing.filter_seconds[f] * 1e6 / static_cast<double>(timing.filter_samples[f]), "%.3f")
          << " us/sample (CPU "
          << number(timing.filter_cpu_seconds[f] * 1e6 / static_cast<double>(timing.filter_samples[f]), "%.3f") << ")";
    out << "\n";
  }
  if (result.reference)
    out << "  particle reference (N = " << result.reference->particles << "): "
        << phase(timing.reference_seconds, timing.reference_cpu_seconds, timing.reference_steps)
        << " (a step: one particle's)\n";
  out << "  statistics: " << number(timing.aggregation_seconds, "%.3f") << " s\n";
  return out.str();
}

}  // namespace pfgen_runtime
