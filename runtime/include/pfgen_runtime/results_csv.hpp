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

}  // namespace pfgen_runtime
