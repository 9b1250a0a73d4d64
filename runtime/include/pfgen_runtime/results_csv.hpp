#pragma once
// The time series of a Monte Carlo result as CSV, one row per record time.
#include <string>
#include <vector>

#include "pfgen_runtime/monte_carlo.hpp"

namespace pfgen_runtime {

// Columns, with f a filter name and x a state name (in this order):
//   t,
//   truth_x ...                                  the shown run's truth
//   f_m_x ..., f_P_x ..., f_err_x ...            per filter: the shown run's m, P diagonal, x - m
//   truth_x_mean, truth_x_q05, truth_x_q50, truth_x_q95 ..., truth_alive
//   f_err_x_mean, f_err_x_q05, f_err_x_q50, f_err_x_q95 ..., f_alive      per filter
// Numbers in shortest round-trip form; undefined values (a stopped run, no run alive) are empty
// cells. Header fields holding ',', '"' or a line break are quoted (RFC 4180). The file is written
// to path + ".tmp" and renamed, so a failed write leaves no partial file; std::runtime_error naming
// the path on failure, std::invalid_argument unless there is one state name per component.
void write_results_csv(const std::string& path, const MonteCarloResult& result,
                       const std::vector<std::string>& state_names);

// The CSV text itself (what write_results_csv writes).
std::string format_results_csv(const MonteCarloResult& result, const std::vector<std::string>& state_names);

// The header's column names, unquoted, in order (the plot script addresses columns by position).
std::vector<std::string> results_csv_columns(const MonteCarloResult& result,
                                             const std::vector<std::string>& state_names);

// The exponential criterion per filter (MonteCarloOptions::criterion), one row per filter:
//   filter, epsilon, runs, completed, J, J_se, ess, mean_integral, mean_integral_se, stopped,
//   first_stop_t, completed_J, completed_J_se, completed_ess, completed_mean_integral,
//   completed_mean_integral_se
// (the completed_ columns: over the runs that reached T only). J and mean_integral are "inf" when
// a run stopped before T; undefined values are empty cells. std::invalid_argument when the result
// has no criterion. write_criterion_csv writes it atomically like write_results_csv.
std::string format_criterion_csv(const MonteCarloResult& result);
void write_criterion_csv(const std::string& path, const MonteCarloResult& result);

// Every run that stopped before T, one row per event: source, event, run, t, with source "truth"
// (event "diverged": beyond the bound or non-finite, or G lost definiteness: "covariance") or a
// filter's name (event "diverged", which includes too stiff for dt, "unrealisable" where a moment
// filter's moments left the realisable set, or "psd_loss"); truth rows
// first, then each filter's in result order, each in run order. So a study of when a state blows
// up (paper 000 under Stratonovich noise) has every time, not only the first and the median.
// write_stops_csv writes it atomically like write_results_csv.
std::string format_stops_csv(const MonteCarloResult& result);
void write_stops_csv(const std::string& path, const MonteCarloResult& result);

}  // namespace pfgen_runtime
