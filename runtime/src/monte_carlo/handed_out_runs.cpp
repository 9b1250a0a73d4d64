#include "handed_out_runs.hpp"

#include <algorithm>
#include <exception>
#include <mutex>
#include <stdexcept>
#include <string>
#include <thread>

#include "chunk_queue.hpp"

namespace pfgen_runtime::monte_carlo_detail {

namespace {

// The table hand_out returned must name a process for every chunk, and this process for exactly
// the chunks it was given.
void check_owners(const std::vector<std::size_t>& owners, std::vector<std::size_t> given, const RunShare& share,
                  std::size_t chunks) {
  if (owners.size() != chunks)
    throw std::runtime_error("monte carlo: the hand-out's table has " + std::to_string(owners.size()) +
                             " chunks, not the job's " + std::to_string(chunks));
  std::vector<std::size_t> mine;
  for (std::size_t c = 0; c < chunks; ++c) {
    if (owners[c] >= share.processes)
      throw std::runtime_error("monte carlo: the hand-out's table gives chunk " + std::to_string(c) + " to process " +
                               std::to_string(owners[c]) + " of " + std::to_string(share.processes));
    if (owners[c] == share.process) mine.push_back(c);
  }
  std::sort(given.begin(), given.end());
  if (given != mine)
    throw std::runtime_error("monte carlo: process " + std::to_string(share.process) + " was given " +
                             std::to_string(given.size()) + " chunks, and the hand-out's table says " +
                             std::to_string(mine.size()) + " (or other ones)");
}

}  // namespace

HandedOutRuns make_handed_out_runs(const RunShare& share, std::size_t runs, unsigned threads, std::size_t batch,
                                   const std::function<Worker*(unsigned)>& make_worker,
                                   const std::function<void()>& on_run) {
  const std::size_t chunk = share.chunk, chunks = chunk_count(runs, chunk);
  HandedOutRuns result;
  result.made.resize(chunks);
  ChunkQueue queue(chunks);
  std::exception_ptr error;
  std::mutex error_mutex;
  auto work = [&](unsigned thread) {
    try {
      Worker* worker = make_worker(thread);
      while (const std::optional<std::size_t> c = queue.take()) {
        const std::size_t first = *c * chunk, size = std::min(chunk, runs - first);
        std::vector<RunResult>& out = result.made[*c];  // this thread's alone: a chunk is given once
        out.resize(size);
        for (std::size_t k = 0; k < size; k += batch) {
          const std::size_t count = std::min(batch, size - k);
          worker->run(first + k, count, out.data() + k);
          for (std::size_t r = 0; r < count; ++r) on_run();
        }
        queue.finished();
      }
    } catch (...) {
      std::lock_guard<std::mutex> lock(error_mutex);
      if (!error) error = std::current_exception();
      queue.stop();
    }
  };
  std::vector<std::thread> pool;
  try {
    for (unsigned t = 0; t < threads; ++t) pool.emplace_back(work, t);
  } catch (...) {  // could not start a thread: stop the others and report
    queue.stop();
    for (std::thread& thread : pool) thread.join();
    throw;
  }
  std::exception_ptr hand_out_error;
  try {
    result.owners = share.hand_out(queue);
  } catch (...) {
    hand_out_error = std::current_exception();
    queue.stop();
  }
  queue.close();
  for (std::thread& thread : pool) thread.join();
  if (error) std::rethrow_exception(error);
  if (hand_out_error) std::rethrow_exception(hand_out_error);
  check_owners(result.owners, queue.given(), share, chunks);
  return result;
}

}  // namespace pfgen_runtime::monte_carlo_detail
