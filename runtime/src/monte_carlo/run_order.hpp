#pragma once
// Which process of a shared job (MonteCarloOptions::share) made which run, and the runs the
// processes sent put back in run order, in which every fold reads them.
#include <cstddef>
#include <iterator>
#include <stdexcept>
#include <string>
#include <utility>
#include <vector>

#include "pfgen_runtime/monte_carlo.hpp"

namespace pfgen_runtime::monte_carlo_detail {

// What the processes of a shared job sent must be a block from each of them and every run once.
void check_share_count(std::size_t blocks, std::size_t runs, const RunShare& share, std::size_t expected);

// The process of each chunk of `chunk` runs when they are dealt: chunk c to process c mod processes.
std::vector<std::size_t> dealt_owners(std::size_t runs, std::size_t chunk, std::size_t processes);

// The job's numbers of the runs of `process`, which made the chunks `owners` gives it, in order.
std::vector<std::size_t> runs_of(const std::vector<std::size_t>& owners, std::size_t chunk, std::size_t runs,
                                 std::size_t process);

// The runs each process sent (per_process, in process order), in run order: one block after the
// other, or put back chunk by chunk as `owners` says (then a process that sent more or fewer runs
// than its chunks hold is refused; blocks are counted as a whole by check_share_count).
template <class Run>
std::vector<Run> in_run_order(std::vector<std::vector<Run>> per_process, const RunShare& share, std::size_t runs,
                              const std::vector<std::size_t>& owners) {
  std::vector<Run> ordered;
  if (share.chunk == 0) {
    ordered.reserve(runs);
    for (std::vector<Run>& block : per_process) std::move(block.begin(), block.end(), std::back_inserter(ordered));
    return ordered;
  }
  if (per_process.size() != share.processes)
    throw std::runtime_error("monte carlo: " + std::to_string(per_process.size()) + " processes' shares arrived, not " +
                             std::to_string(share.processes));
  std::vector<std::vector<std::size_t>> numbers(per_process.size());
  for (std::size_t process = 0; process < per_process.size(); ++process) {
    numbers[process] = runs_of(owners, share.chunk, runs, process);
    if (per_process[process].size() != numbers[process].size())
      throw std::runtime_error("monte carlo: process " + std::to_string(process) + " sent " +
                               std::to_string(per_process[process].size()) + " runs, not the " +
                               std::to_string(numbers[process].size()) + " of its chunks");
  }
  // Each process sent as many runs as its chunks hold, so every run number below is taken once.
  ordered.resize(runs);
  for (std::size_t process = 0; process < per_process.size(); ++process)
    for (std::size_t k = 0; k < per_process[process].size(); ++k)
      ordered[numbers[process][k]] = std::move(per_process[process][k]);
  return ordered;
}

}  // namespace pfgen_runtime::monte_carlo_detail
