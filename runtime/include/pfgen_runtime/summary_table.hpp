#pragma once
// The plain-text summary of a Monte Carlo result, for stdout.
//
// Deterministic: the same result gives the same bytes (no timing in it; that is format_timing's),
// numbers with 4 significant digits, '-' for every undefined cell, so no "nan" or "inf" is ever
// printed as a result; the one exception is the exponential criterion J, which is infinite, and
// printed "inf", when a run stopped before T.
#include <string>
#include <vector>

#include "pfgen_runtime/monte_carlo.hpp"

namespace pfgen_runtime {

// A header line (runs, horizon, dt, seed, truth scheme), then one row per filter and state
// component: RMS error over [t0, T] and over each window ("RMS[a,b]"), mean |e| at each report
// time ("|e|@t"), the median and 95 % quantile over completed runs of the peak |e|, divergences (count, earliest and
// median time) and PSD losses (count, earliest time); then how many runs each statistic counted,
// and a line on the truth's divergences. When the result carries the exponential criterion
// (MonteCarloOptions::criterion), a section with one row per filter follows the filters' tables:
// eps and the L used, then J, its standard error, the effective sample size, mean int L and its
// standard error, the runs stopped before T and the first stop time ("inf" for J and mean int L
// then, and the same figures over the completed runs in a second table). state_names: one per state component
// (std::invalid_argument otherwise).
std::string format_summary_table(const MonteCarloResult& result, const std::vector<std::string>& state_names);

// The errors at the report times in full, one row per filter, state component and report time:
// the runs counted, the signed mean of e = x - m and the mean |e|, each with its standard error
// over runs. Not part of format_summary_table (whose bytes stay as they were); `pfgen simulate`
// prints it after the table for delayed observations, where a paper's printed estimates are
// compared through mean m = x - mean e. Empty when there are no filters or no report times.
std::string format_report_errors(const MonteCarloResult& result, const std::vector<std::string>& state_names);

// Wall time, thread seconds and ns per step of the truth and of each filter (varies run to run).
std::string format_timing(const MonteCarloResult& result);

}  // namespace pfgen_runtime
