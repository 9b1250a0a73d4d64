#pragma once
// A process's share of the runs as bytes (MonteCarloOptions::share): its runs' RunResults in run
// order and its workers' timing, for another process to fold. Numbers travel as their bytes, so
// a decoded run is bit for bit the run that was made (NaN included); the processes must share
// the number representation (the same architecture, as the plugins already require).
#include <cstddef>
#include <vector>

#include "pfgen_runtime/monte_carlo.hpp"
#include "run_result.hpp"

namespace pfgen_runtime::monte_carlo_detail {

// Timing: threads, the truth's and each filter's seconds, CPU seconds, steps and samples (the
// wall and aggregation times are the folding process's own).
std::vector<char> encode_share(const std::vector<RunResult>& runs, const MonteCarloTiming& timing);

// Appends the block's runs to `runs` and adds its timing to `timing` (threads, seconds and steps
// summed; filter vectors of `filters` entries). std::runtime_error for bytes that are not such a
// block (truncated, another layout, another number of filters).
void decode_share(const std::vector<char>& bytes, std::size_t filters, std::vector<RunResult>& runs,
                  MonteCarloTiming& timing);

}  // namespace pfgen_runtime::monte_carlo_detail
