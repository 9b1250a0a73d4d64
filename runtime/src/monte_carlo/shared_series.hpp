#pragma once
// The series fold of a job whose runs are shared among processes (MonteCarloOptions::share):
// each process folds the record times of its series_range from every process's runs, whose values
// there reach it through the exchange (series_codec) and are put back in run order (run_order).
// The exchange goes in rounds, each over a part of every process's range, so that a process
// receives a round's values (about RunShare::exchange_round_bytes) into the buffers of the round
// before: fresh memory is costly (the kernel clears every page, and a virtual machine's host may
// first have to back it: 20,000 satellite runs on 2 processes received 400 MB a process in one
// round, 1.5 s of a 20 s job).
#include <cstddef>
#include <vector>

#include "pfgen_runtime/monte_carlo.hpp"
#include "plan.hpp"
#include "run_result.hpp"

namespace pfgen_runtime::monte_carlo_detail {

// The rounds of the exchange: from the job alone (its records, runs, filters, reference and the
// share's processes and round bytes), so the same on every process; at least 1, and at most the
// records of the shortest range, so that every round folds a record time on every process.
std::size_t exchange_rounds(const Plan& plan, std::size_t runs, std::size_t filters, bool reference,
                            const RunShare& share);

// Part `round` of `rounds` of a range: contiguous parts of near-equal size, in order, covering it.
RecordRange round_part(RecordRange range, std::size_t round, std::size_t rounds);

struct SharedFoldTiming {
  double exchange_seconds = 0, fold_seconds = 0;  // over the rounds
  std::size_t exchanged_bytes = 0;                // received by this process
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
