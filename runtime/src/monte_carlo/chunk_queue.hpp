#pragma once
// The chunks handed to this process (RunShare::hand_out) on their way to its threads: the
// hand-out gives them on one thread, the threads take them in the order given. A chunk is given
// at most once, so no two threads make the same runs.
#include <chrono>
#include <condition_variable>
#include <cstddef>
#include <deque>
#include <mutex>
#include <optional>
#include <vector>

#include "pfgen_runtime/monte_carlo.hpp"

namespace pfgen_runtime::monte_carlo_detail {

class ChunkQueue final : public ChunkFeed {
 public:
  explicit ChunkQueue(std::size_t chunks) : taken_(chunks, false) {}

  std::size_t waiting() const override;
  std::size_t made() const override;
  // std::invalid_argument for a chunk that is not the job's or was given before.
  void give(std::size_t chunk) override;
  bool stopped() const override;
  void wait_below(std::size_t below, std::chrono::microseconds timeout) const override;

  // The threads' side: the next chunk to make; nullopt once the runs have stopped, or the hand-out
  // has ended and no chunk waits.
  std::optional<std::size_t> take();
  // A thread finished a chunk it took.
  void finished();
  // The hand-out has ended: no chunk comes after those waiting.
  void close();
  // A thread failed: the others stop at their next chunk, and the hand-out winds down.
  void stop();
  // Every chunk given, in the order given.
  std::vector<std::size_t> given() const;

 private:
  mutable std::mutex mutex_;
  mutable std::condition_variable changed_;
  std::deque<std::size_t> waiting_;
  std::vector<std::size_t> given_;
  std::vector<bool> taken_;  // per chunk of the job: given already
  std::size_t made_ = 0;
  bool closed_ = false, stopped_ = false;
  mutable std::size_t wake_below_ = 0;  // wait_below's `below` while it waits, else 0
};

}  // namespace pfgen_runtime::monte_carlo_detail
