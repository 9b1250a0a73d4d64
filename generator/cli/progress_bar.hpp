#pragma once
// A progress bar for long Monte Carlo jobs. The command draws it on stderr only when stderr is a
// terminal and the job has run for more than a second (short jobs and redirected output stay
// clean); the API's caller may ask for its text instead (pfgen::api::SimulationOptions::progress).
// It is safe to update from worker threads: an update never waits (it draws only when it gets
// the bar's mutex at once), and drawing is rate-limited to five times a second.
#include <chrono>
#include <cstddef>
#include <functional>
#include <mutex>
#include <string>

namespace pfgen::cli {

// Where a bar goes: each draw is "\r" and the line, the last write clears the line; and how long
// a job runs before the first draw.
struct ProgressOutput {
  std::function<void(const std::string& text)> write;  // empty: no bar
  double quiet_seconds = 0;

  // The command's: stderr when it is a terminal, after a second.
  static ProgressOutput terminal();
  // A caller's own, who asked for it: from the first finished unit on.
  static ProgressOutput to(std::function<void(const std::string& text)> write);
  static ProgressOutput none() { return {}; }
};

class ProgressBar {
 public:
  // `label` prefixes the bar ("simulate"); `total` is the number of units (runs).
  ProgressBar(std::string label, std::size_t total, ProgressOutput output = ProgressOutput::terminal());
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
  ProgressOutput output_;
  std::chrono::steady_clock::time_point start_;
  std::mutex mutex_;
  double last_draw_ = -1;
  bool drawn_ = false;
  bool finished_ = false;
};

}  // namespace pfgen::cli
