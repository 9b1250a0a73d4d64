#pragma once
// The truth's grid: the times every Monte Carlo run, truth and filter, steps over.
#include <cmath>
#include <cstddef>
#include <stdexcept>

namespace pfgen_runtime {

struct TimeGrid {
  double t0 = 0;
  double dt = 0;
  std::size_t steps = 0;
  // Grid times are t0 + k dt (no accumulated round-off).
  double time(std::size_t k) const { return t0 + static_cast<double>(k) * dt; }
  double end() const { return time(steps); }
  // round((T - t0) / dt) steps; std::invalid_argument unless dt > 0 and T > t0.
  static TimeGrid to_horizon(double t0, double T, double dt) {
    if (!(dt > 0) || !(T > t0) || !std::isfinite(T) || !std::isfinite(t0))
      throw std::invalid_argument("time grid: need dt > 0 and a finite T > t0");
    TimeGrid grid;
    grid.t0 = t0;
    grid.dt = dt;
    grid.steps = static_cast<std::size_t>(std::llround((T - t0) / dt));
    if (grid.steps == 0) grid.steps = 1;
    return grid;
  }
};

}  // namespace pfgen_runtime
