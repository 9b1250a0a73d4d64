#pragma once
// Folds the per-run results into a MonteCarloResult's statistics and series. It reads the runs
// in run order only after all have finished, so every sum and every sample for the quantiles is
// the same whichever thread (or process) made which run.
#include <vector>

#include "pfgen_runtime/monte_carlo.hpp"
#include "plan.hpp"
#include "run_result.hpp"
#include "series_rows.hpp"

namespace pfgen_runtime::monte_carlo_detail {

// The series' statistics across runs, at the record times, in three steps (the runs of a job
// shared among processes are folded a range of record times on each process, series_codec.hpp):
// start_series sizes their matrices (records x n); fold_series fills the rows `range` from
// `runs`, every run's rows of the range in run order (series_rows.hpp), the record times shared
// among up to `threads` threads without changing a bit.
void start_series(const Plan& plan, std::size_t filters, bool reference, MonteCarloSeries& series);
void fold_series(const Plan& plan, std::size_t filters, const std::vector<RunRows>& runs, RecordRange range,
                 bool reference, unsigned threads, MonteCarloSeries& series);

// Fills result.truth_divergences, truth_reports, filters, and the series' times and the shown
// run's paths (of a series that start_series sized); the rest of `result` is the caller's. Only
// the shown run's record vectors are read.
void aggregate(const Plan& plan, const std::vector<FilterModel>& filters, const std::vector<RunResult>& runs,
               const MonteCarloOptions& options, MonteCarloResult& result);

}  // namespace pfgen_runtime::monte_carlo_detail
