#include "progress_bar.hpp"

#include <unistd.h>

#include <algorithm>
#include <cstdio>

namespace pfgen::cli {

namespace {
constexpr double kQuietSeconds = 1.0;     // no bar for jobs shorter than this
constexpr double kRedrawSeconds = 0.2;    // at most five redraws a second
constexpr int kBarWidth = 40;
}  // namespace

ProgressBar::ProgressBar(std::string label, std::size_t total)
    : label_(std::move(label)), total_(total), enabled_(isatty(STDERR_FILENO) == 1 && total > 0),
      start_(std::chrono::steady_clock::now()) {}

ProgressBar::~ProgressBar() { finish(); }

void ProgressBar::update(std::size_t done) {
  if (!enabled_) return;
  const double elapsed = std::chrono::duration<double>(std::chrono::steady_clock::now() - start_).count();
  if (elapsed < kQuietSeconds) return;
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
  std::fprintf(stderr, "\r%s [%s] %zu/%zu runs, %.0f s elapsed, ~%.0f s left ", label_.c_str(), bar.c_str(), done,
               total_, elapsed, remaining);
  std::fflush(stderr);
  drawn_ = true;
}

void ProgressBar::finish() {
  std::lock_guard<std::mutex> lock(mutex_);
  if (finished_) return;
  finished_ = true;
  if (drawn_) {
    std::fprintf(stderr, "\r%*s\r", kBarWidth + 60 + static_cast<int>(label_.size()), "");
    std::fflush(stderr);
  }
}

}  // namespace pfgen::cli
