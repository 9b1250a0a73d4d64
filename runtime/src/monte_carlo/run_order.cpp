#include "run_order.hpp"

#include <algorithm>

namespace pfgen_runtime::monte_carlo_detail {

void check_share_count(std::size_t blocks, std::size_t runs, const RunShare& share, std::size_t expected) {
  if (blocks != share.processes)
    throw std::runtime_error("monte carlo: " + std::to_string(blocks) + " processes' shares arrived, not " +
                             std::to_string(share.processes));
  if (runs != expected)
    throw std::runtime_error("monte carlo: the processes' shares hold " + std::to_string(runs) + " runs, not " +
                             std::to_string(expected));
}

std::vector<std::size_t> dealt_owners(std::size_t runs, std::size_t chunk, std::size_t processes) {
  std::vector<std::size_t> owners(chunk_count(runs, chunk));
  for (std::size_t c = 0; c < owners.size(); ++c) owners[c] = c % processes;
  return owners;
}

std::vector<std::size_t> runs_of(const std::vector<std::size_t>& owners, std::size_t chunk, std::size_t runs,
                                 std::size_t process) {
  std::vector<std::size_t> numbers;
  for (std::size_t c = 0; c < owners.size(); ++c)
    if (owners[c] == process)
      for (std::size_t r = c * chunk; r < std::min(runs, (c + 1) * chunk); ++r) numbers.push_back(r);
  return numbers;
}

}  // namespace pfgen_runtime::monte_carlo_detail
