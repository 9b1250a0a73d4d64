#pragma once
// Folds the per-run results into a MonteCarloResult's statistics and series. It reads the runs
// in run order only after all have finished, so every sum and every sample for the quantiles is
// the same whichever thread made which run.
#include <vector>

#include "pfgen_runtime/monte_carlo.hpp"
#include "plan.hpp"
#include "run_result.hpp"

namespace pfgen_runtime::monte_carlo_detail {

// Fills result.truth_divergences, truth_reports, filters and series; the rest of `result` is the
// caller's. The series' record times are shared among up to `threads` threads, without changing
// a bit.
void aggregate(const Plan& plan, const std::vector<FilterModel>& filters, const std::vector<RunResult>& runs,
               const MonteCarloOptions& options, unsigned threads, MonteCarloResult& result);

}  // namespace pfgen_runtime::monte_carlo_detail
