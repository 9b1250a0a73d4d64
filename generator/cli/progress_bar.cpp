#include "progress_bar.hpp"

#include <unistd.h>

#include <algorithm>
#include <cstdio>
#include <utility>

namespace pfgen::cli {

namespace {
constexpr double kQuietSeconds = 1.0;     // no bar for jobs shorter than this
constexpr double kRedrawSeconds = 0.2;    // at most five redraws a second
constexpr int kBarWidth = 40;
}  // namespace

ProgressOutput ProgressOutput::terminal() {
  if (isatty(STDERR_FILENO) != 1) return none();
  return {[](const std::string& text) {
            std::fputs(text.c_str(), stderr);
            std::fflush(stderr);
          },
          kQuietSeconds};
}

ProgressOutput ProgressOutput::to(std::function<void(const std::string& text)> write) { return {std::move(write), 0}; }

ProgressBar::ProgressBar(std::string label, std::size_t total, ProgressOutput output)
    : label_(std::move(label)), total_(total), output_(std::move(output)), start_(std::chrono::steady_clock::now()) {
  if (total_ == 0) output_ = ProgressOutput::none();
}

ProgressBar::~ProgressBar() { finish(); }

void ProgressBar::update(std::size_t done) {
  if (!output_.write) return;
  const double elapsed = std::chrono::duration<double>(std::chrono::steady_clock::now() - start_).count();
  if (elapsed < output_.quiet_seconds) return;
  std::unique_lock<std::mutex> lock(mutex_, std::try_to_lock);
  if (!lock.owns_lock() || finished_) return;  // another thread is drawing: skip, never wait
  if (last_draw_ >= 0 && elapsed - last_draw_ < kRedrawSeconds && done < total_) return;
  last_draw_ = elapsed;
  draw(done, elapsed);
}

void ProgressBar::draw(std::size_t done, double elapsed) {
  done = std::min(done, total_);  // an estimated total (an MPI rank's share of handed-out runs) may be passed
  const double fraction = total_ ? static_cast<double>(done) / static_cast<double>(total_) : 1.0;
  const int filled = static_cast<int>(fraction * kBarWidth);
  std::string bar(static_cast<std::size_t>(filled), '#');
  bar.resize(kBarWidth, '.');
  const double remaining = done > 0 ? elapsed * (1.0 / fraction - 1.0) : 0.0;
  char numbers[128];
  std::snprintf(numbers, sizeof numbers, "] %zu/%zu runs, %.0f s elapsed, ~%.0f s left ", done, total_, elapsed,
                remaining);
  output_.write("\r" + label_ + " [" + bar + numbers);
  drawn_ = true;
}

void ProgressBar::finish() {
  std::lock_guard<std::mutex> lock(mutex_);
  if (finished_) return;
  finished_ = true;
  if (drawn_) output_.write("\r" + std::string(kBarWidth + 60 + label_.size(), ' ') + "\r");
}

}  // namespace pfgen::cli
