#pragma once
// A process's share of the runs as bytes (MonteCarloOptions::share): its runs' RunResults in run
// order, its workers' timing and the rows of the record series it folded (series_codec.hpp), for
// the folding process. Numbers travel as their bytes, so
// a decoded run is bit for bit the run that was made (NaN included); the processes must share
// the number representation (the same architecture, as the plugins already require).
#include <cstddef>
#include <vector>

#include "pfgen_runtime/monte_carlo.hpp"
#include "run_result.hpp"

namespace pfgen_runtime::monte_carlo_detail {

// Timing: threads, the truth's and each filter's seconds, CPU seconds, steps and samples (the
// wall and aggregation times are the folding process's own).
std::vector<char> encode_share(const std::vector<RunResult>& runs, const MonteCarloTiming& timing,
                               const std::vector<char>& series_rows);

// Appends the block's runs to `runs`, adds its timing to `timing` (threads, seconds and steps
// summed; filter vectors of `filters` entries) and returns its series rows. std::runtime_error
// for bytes that are not such a block (truncated, another layout, another number of filters).
std::vector<char> decode_share(const std::vector<char>& bytes, std::size_t filters, std::vector<RunResult>& runs,
                               MonteCarloTiming& timing);

}  // namespace pfgen_runtime::monte_carlo_detail
