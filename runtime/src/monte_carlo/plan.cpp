#include "plan.hpp"

#include <algorithm>
#include <cmath>
#include <sstream>
#include <stdexcept>

namespace pfgen_runtime::monte_carlo_detail {

namespace {

std::size_t snap(const TimeGrid& grid, double t, const char* what) {
  const double position = (t - grid.t0) / grid.dt;
  // Half a step of slack either side: "T" typed by a user may differ from t0 + steps dt in the
  // last bit.
  if (!std::isfinite(position) || position < -0.5 || position > static_cast<double>(grid.steps) + 0.5) {
    std::ostringstream message;
    message << "monte carlo: " << what << " t = " << t << " is outside [" << grid.t0 << ", " << grid.end() << "]";
    throw std::invalid_argument(message.str());
  }
  return static_cast<std::size_t>(std::llround(std::max(0.0, position)));
}

}  // namespace

Plan make_plan(std::size_t n, std::size_t p, const MonteCarloOptions& options) {
  Plan plan;
  plan.n = n;
  plan.p = p;
  plan.grid = options.grid;
  const std::size_t steps = options.grid.steps;
  const std::size_t stride = std::max<std::size_t>(1, steps / options.record_points);
  for (std::size_t k = 0; k <= steps; k += stride) plan.records.push_back(k);
  if (plan.records.back() != steps) plan.records.push_back(steps);
  for (double t : options.report_times) plan.reports.push_back(snap(options.grid, t, "report time"));
  for (const auto& [a, b] : options.windows) {
    if (!(a < b)) throw std::invalid_argument("monte carlo: a window [a, b] needs a < b");
    const std::size_t first = snap(options.grid, a, "window start"), last = snap(options.grid, b, "window end");
    if (first >= last) throw std::invalid_argument("monte carlo: a window is shorter than a grid step");
    plan.windows.emplace_back(first, last);
  }
  for (std::size_t r = 0; r < plan.records.size(); ++r) plan.events.push_back({plan.records[r], Plan::Kind::record, r});
  for (std::size_t q = 0; q < plan.reports.size(); ++q) plan.events.push_back({plan.reports[q], Plan::Kind::report, q});
  for (std::size_t w = 0; w < plan.windows.size(); ++w) {
    plan.events.push_back({plan.windows[w].second, Plan::Kind::window_close, w});
    plan.opens.emplace_back(plan.windows[w].first, w);
  }
  std::stable_sort(plan.events.begin(), plan.events.end(),
                   [](const Plan::Event& x, const Plan::Event& y) { return x.index < y.index; });
  std::stable_sort(plan.opens.begin(), plan.opens.end());
  return plan;
}

RecordRange series_range(std::size_t records, std::size_t process, std::size_t processes) {
  // floor(records k / processes), without forming the product records k.
  const auto bound = [&](std::size_t k) { return records / processes * k + records % processes * k / processes; };
  return {bound(process), bound(process + 1)};
}

}  // namespace pfgen_runtime::monte_carlo_detail
