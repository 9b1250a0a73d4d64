#include "shared_series.hpp"

#include <algorithm>
#include <cmath>
#include <utility>

#include "aggregate.hpp"
#include "clock.hpp"
#include "run_order.hpp"
#include "series_codec.hpp"
#include "series_rows.hpp"

namespace pfgen_runtime::monte_carlo_detail {

std::size_t exchange_rounds(const Plan& plan, std::size_t runs, std::size_t filters, bool reference,
                            const RunShare& share) {
  const std::size_t shortest = plan.records.size() / std::max<std::size_t>(1, share.processes);
  if (share.processes < 2 || share.exchange_round_bytes == 0 || shortest < 2) return 1;
  // The bytes a process receives, about: the other processes' runs' values at its range, of the
  // truth and every filter's error, and with the reference every filter's distance to it and the
  // reference's own error. In doubles: a large job's product can pass 2^64.
  const double processes = static_cast<double>(share.processes);
  const double series = 1.0 + static_cast<double>(filters) + (reference ? static_cast<double>(filters) + 1.0 : 0.0);
  const double bytes = static_cast<double>(runs) * (processes - 1.0) / processes *
                       (static_cast<double>(plan.records.size()) / processes) * static_cast<double>(plan.n) * series *
                       static_cast<double>(sizeof(double));
  const double rounds = std::ceil(bytes / static_cast<double>(share.exchange_round_bytes));
  return static_cast<std::size_t>(std::clamp(rounds, 1.0, static_cast<double>(shortest)));
}

RecordRange round_part(RecordRange range, std::size_t round, std::size_t rounds) {
  const RecordRange part = series_range(range.size(), round, rounds);
  return {range.first + part.first, range.first + part.last};
}

SharedFoldTiming fold_shared_series(const Plan& plan, std::size_t filters, const std::vector<RunResult>& runs,
                                    bool reference, unsigned threads, std::size_t total_runs,
                                    const std::vector<std::size_t>& owners, const RunShare& share,
                                    MonteCarloSeries& series) {
  SharedFoldTiming timing;
  const std::size_t rounds = exchange_rounds(plan, total_runs, filters, reference, share);
  const auto range = [&](std::size_t process) { return series_range(plan.records.size(), process, share.processes); };
  std::vector<std::vector<char>> received(share.processes);  // kept from round to round
  for (std::size_t round = 0; round < rounds; ++round) {
    const auto part = [&](std::size_t process) { return round_part(range(process), round, rounds); };
    // Every process sends every other its runs' values at that process's part, from the runs'
    // record vectors and the slices' heads (series_slice), unchanged until the exchange returns;
    // its own part is taken from its runs directly below.
    std::vector<SeriesSlice> slices(share.processes);
    std::vector<PiecedBlock> outgoing(share.processes);
    for (std::size_t process = 0; process < share.processes; ++process)
      if (process != share.process) {
        slices[process] = series_slice(runs, part(process), plan.n);
        outgoing[process] = std::move(slices[process].pieces);
      }
    const Clock::time_point exchange_start = Clock::now();
    share.exchange(outgoing, received);
    timing.exchange_seconds += seconds_since(exchange_start);
    // The rows stay where they are (series_rows.hpp): in the received bytes and in this process's
    // own runs, both unchanged until this round's fold is done.
    std::vector<SliceRows> sent(received.size());
    std::vector<std::vector<RunRows>> per_process(received.size());
    for (std::size_t process = 0; process < received.size(); ++process) {
      timing.exchanged_bytes += received[process].size();
      sent[process] = process == share.process
                          ? rows_of(runs, part(share.process), plan.n, filters)
                          : read_series_slice(received[process], filters, part(share.process), plan.n);
      per_process[process] = sent[process].runs;
    }
    const std::vector<RunRows> slice = in_run_order(std::move(per_process), share, total_runs, owners);
    check_share_count(received.size(), slice.size(), share, total_runs);
    const Clock::time_point fold_start = Clock::now();
    fold_series(plan, filters, slice, part(share.process), reference, threads, series);
    timing.fold_seconds += seconds_since(fold_start);
  }
  return timing;
}

}  // namespace pfgen_runtime::monte_carlo_detail
