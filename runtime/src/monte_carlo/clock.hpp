#pragma once
// The clocks of MonteCarloTiming: elapsed time, and the CPU time of the calling thread (elapsed
// exceeds it when other processes share the cores, so the two are reported side by side).
#include <chrono>

#include <time.h>

namespace pfgen_runtime::monte_carlo_detail {

using Clock = std::chrono::steady_clock;

inline double seconds_since(Clock::time_point start) {
  return std::chrono::duration<double>(Clock::now() - start).count();
}

// std::chrono has no thread clock.
inline double thread_cpu_seconds() {
  timespec now{};
  clock_gettime(CLOCK_THREAD_CPUTIME_ID, &now);
  return static_cast<double>(now.tv_sec) + 1e-9 * static_cast<double>(now.tv_nsec);
}

}  // namespace pfgen_runtime::monte_carlo_detail
