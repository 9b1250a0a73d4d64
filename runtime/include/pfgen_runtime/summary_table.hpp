#pragma once
// The plain-text summary of a Monte Carlo result, for stdout.
//
// Deterministic: the same result gives the same bytes (no timing in it; that is format_timing's),
// numbers with 4 significant digits, '-' for every undefined cell, so no "nan" or "inf" is ever
// printed as a result.
#include <string>
#include <vector>

#include "pfgen_runtime/monte_carlo.hpp"

namespace pfgen_runtime {

// A header line (runs, horizon, dt, seed, truth scheme), then one row per filter and state
// component: RMS error over [t0, T] and over each window ("RMS[a,b]"), mean |e| at each report
// time ("|e|@t"), the median and 95 % quantile over completed runs of the peak |e|, divergences (count, earliest and
// median time) and PSD losses (count, earliest time); then how many runs each statistic counted,
// and a line on the truth's divergences. state_names: one per state component
// (std::invalid_argument otherwise).
std::string format_summary_table(const MonteCarloResult& result, const std::vector<std::string>& state_names);

// Wall time, thread seconds and ns per step of the truth and of each filter (varies run to run).
std::string format_timing(const MonteCarloResult& result);

}  // namespace pfgen_runtime
