#include "shared_series.hpp"

#include <utility>

#include "aggregate.hpp"
#include "clock.hpp"
#include "run_order.hpp"
#include "series_codec.hpp"
#include "series_rows.hpp"

namespace pfgen_runtime::monte_carlo_detail {

SharedFoldTiming fold_shared_series(const Plan& plan, std::size_t filters, const std::vector<RunResult>& runs,
                                    bool reference, unsigned threads, std::size_t total_runs,
                                    const std::vector<std::size_t>& owners, const RunShare& share,
                                    MonteCarloSeries& series) {
  SharedFoldTiming timing;
  const auto range = [&](std::size_t process) { return series_range(plan.records.size(), process, share.processes); };
  // Every process sends every other its runs' values at that process's range, from the runs'
  // record vectors and the slices' heads (series_slice), unchanged until the exchange returns; its
  // own range is taken from its runs directly below.
  std::vector<SeriesSlice> slices(share.processes);
  std::vector<PiecedBlock> outgoing(share.processes);
  for (std::size_t process = 0; process < share.processes; ++process)
    if (process != share.process) {
      slices[process] = series_slice(runs, range(process), plan.n);
      outgoing[process] = std::move(slices[process].pieces);
    }
  const Clock::time_point exchange_start = Clock::now();
  const std::vector<std::vector<char>> received = share.exchange(outgoing);
  timing.exchange_seconds = seconds_since(exchange_start);
  // The rows stay where they are (series_rows.hpp): in the received bytes and in this process's own
  // runs, both unchanged until the fold is done.
  std::vector<SliceRows> sent(received.size());
  std::vector<std::vector<RunRows>> per_process(received.size());
  for (std::size_t process = 0; process < received.size(); ++process) {
    timing.exchanged_bytes += received[process].size();
    sent[process] = process == share.process
                        ? rows_of(runs, range(share.process), plan.n, filters)
                        : read_series_slice(received[process], filters, range(share.process), plan.n);
    per_process[process] = sent[process].runs;
  }
  const std::vector<RunRows> slice = in_run_order(std::move(per_process), share, total_runs, owners);
  check_share_count(received.size(), slice.size(), share, total_runs);
  const Clock::time_point fold_start = Clock::now();
  fold_series(plan, filters, slice, range(share.process), reference, threads, series);
  timing.fold_seconds = seconds_since(fold_start);
  return timing;
}

}  // namespace pfgen_runtime::monte_carlo_detail
