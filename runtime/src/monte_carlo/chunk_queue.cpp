#include "chunk_queue.hpp"

#include <stdexcept>
#include <string>

namespace pfgen_runtime::monte_carlo_detail {

std::size_t ChunkQueue::waiting() const {
  std::lock_guard<std::mutex> lock(mutex_);
  return waiting_.size();
}

void ChunkQueue::give(std::size_t chunk) {
  std::lock_guard<std::mutex> lock(mutex_);
  if (chunk >= taken_.size())
    throw std::invalid_argument("monte carlo: chunk " + std::to_string(chunk) + " was handed out, but the job has " +
                                std::to_string(taken_.size()) + " chunks");
  if (taken_[chunk])
    throw std::invalid_argument("monte carlo: chunk " + std::to_string(chunk) + " was handed out twice");
  taken_[chunk] = true;
  given_.push_back(chunk);
  waiting_.push_back(chunk);
  changed_.notify_all();
}

std::size_t ChunkQueue::made() const {
  std::lock_guard<std::mutex> lock(mutex_);
  return made_;
}

void ChunkQueue::finished() {
  std::lock_guard<std::mutex> lock(mutex_);
  ++made_;
}

bool ChunkQueue::stopped() const {
  std::lock_guard<std::mutex> lock(mutex_);
  return stopped_;
}

void ChunkQueue::wait_below(std::size_t below, std::chrono::microseconds timeout) const {
  std::unique_lock<std::mutex> lock(mutex_);
  wake_below_ = below;
  changed_.wait_for(lock, timeout, [&] { return waiting_.size() < below || stopped_; });
  wake_below_ = 0;
}

std::optional<std::size_t> ChunkQueue::take() {
  std::unique_lock<std::mutex> lock(mutex_);
  changed_.wait(lock, [&] { return stopped_ || closed_ || !waiting_.empty(); });
  if (stopped_ || waiting_.empty()) return std::nullopt;
  const std::size_t chunk = waiting_.front();
  waiting_.pop_front();
  // Only when the hand-out waits for this (a wake-up per chunk would take the core from the runs).
  if (waiting_.size() < wake_below_) changed_.notify_all();
  return chunk;
}

void ChunkQueue::close() {
  std::lock_guard<std::mutex> lock(mutex_);
  closed_ = true;
  changed_.notify_all();
}

void ChunkQueue::stop() {
  std::lock_guard<std::mutex> lock(mutex_);
  stopped_ = true;
  changed_.notify_all();
}

std::vector<std::size_t> ChunkQueue::given() const {
  std::lock_guard<std::mutex> lock(mutex_);
  return given_;
}

}  // namespace pfgen_runtime::monte_carlo_detail
