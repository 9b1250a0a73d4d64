#pragma once
// A progress bar on stderr for long Monte Carlo jobs. It draws only when stderr is a terminal and
// the job has run for more than a second (short jobs and redirected output stay clean), and it is
// safe to update from worker threads: each update is one atomic counter write, and drawing is
// rate-limited to a few times a second under a mutex.
#include <atomic>
#include <chrono>
#include <cstddef>
#include <mutex>
#include <string>

namespace pfgen::cli {

class ProgressBar {
 public:
  // `label` prefixes the bar ("simulate"); `total` is the number of units (runs).
  ProgressBar(std::string label, std::size_t total);
  ~ProgressBar();  // finish()
  ProgressBar(const ProgressBar&) = delete;
  ProgressBar& operator=(const ProgressBar&) = delete;

  // `done` units finished so far; callable from any thread.
  void update(std::size_t done);
  // Clears the bar's line if one was drawn. Idempotent.
  void finish();

 private:
  void draw(std::size_t done, double elapsed_seconds);
  std::string label_;
  std::size_t total_;
  bool enabled_;
  std::chrono::steady_clock::time_point start_;
  std::mutex mutex_;
  double last_draw_ = -1;
  bool drawn_ = false;
  bool finished_ = false;
};

}  // namespace pfgen::cli
