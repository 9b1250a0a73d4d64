#pragma once
// The engine's only threading: the runs, and then the record times of the aggregation, are
// handed out one index at a time from an atomic counter. Each index writes only its own slot, so
// which thread takes it changes nothing in the result.
#include <atomic>
#include <cstddef>
#include <exception>
#include <mutex>
#include <thread>
#include <vector>

namespace pfgen_runtime::monte_carlo_detail {

// body(i, state) for i in [0, count), taken in turn from an atomic counter by up to `threads`
// threads, each with its own state = make_state(thread number). The first exception stops the
// other threads and is rethrown once all have stopped.
template <class MakeState, class Body>
void parallel_for(std::size_t count, unsigned threads, MakeState make_state, Body body) {
  std::atomic<std::size_t> next{0};
  std::atomic<bool> failed{false};
  std::exception_ptr error;
  std::mutex error_mutex;
  auto work = [&](unsigned thread) {
    try {
      auto state = make_state(thread);
      for (std::size_t i; !failed.load() && (i = next.fetch_add(1)) < count;) body(i, state);
    } catch (...) {
      std::lock_guard<std::mutex> lock(error_mutex);
      if (!error) error = std::current_exception();
      failed = true;
    }
  };
  std::vector<std::thread> pool;
  try {
    for (unsigned t = 1; t < threads; ++t) pool.emplace_back(work, t);
  } catch (...) {  // could not start a thread: stop the others and report
    failed = true;
    for (std::thread& thread : pool) thread.join();
    throw;
  }
  work(0);  // the calling thread works too
  for (std::thread& thread : pool) thread.join();
  if (error) std::rethrow_exception(error);
}

}  // namespace pfgen_runtime::monte_carlo_detail
