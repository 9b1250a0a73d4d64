#pragma once
// The series fold of a job whose runs are shared among processes (MonteCarloOptions::share):
// each process folds the record times of its series_range from every process's runs, whose values
// there reach it in one exchange (series_codec), and puts them back in run order (run_order).
#include <cstddef>
#include <vector>

#include "pfgen_runtime/monte_carlo.hpp"
#include "plan.hpp"
#include "run_result.hpp"

namespace pfgen_runtime::monte_carlo_detail {

struct SharedFoldTiming {
  double exchange_seconds = 0, fold_seconds = 0;
  std::size_t exchanged_bytes = 0;  // received by this process
};

// Folds this process's range of the series (fold_series) from every process's runs: this
// process's own `runs` and, through share.exchange, the others'; `owners` (the process of each
// chunk, with chunks) puts them back in run order. std::runtime_error for what another process
// sent that is not its share.
SharedFoldTiming fold_shared_series(const Plan& plan, std::size_t filters, const std::vector<RunResult>& runs,
                                    bool reference, unsigned threads, std::size_t total_runs,
                                    const std::vector<std::size_t>& owners, const RunShare& share,
                                    MonteCarloSeries& series);

}  // namespace pfgen_runtime::monte_carlo_detail
