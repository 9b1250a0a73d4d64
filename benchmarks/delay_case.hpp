#pragma once
// One delay h of delay_reference: the generated delay-optimal and delay-uncorrected filters for
// that h and grid step, each behind a plain function that runs it over one run's dy.
#include <cmath>
#include <cstddef>
#include <stdexcept>
#include <string>
#include <vector>

namespace pfgen_bench {

// m[k] = the filter's estimate at t_k = k dt, k = 0..dy.size(), for dy_k = y(t_{k+1}) - y(t_k).
using RunDelayFilter = void (*)(const std::vector<double>& dy, double a, double sigma, double dt, std::vector<double>& m);

struct DelayCase {
  const char* tag;
  double h, dt;
  RunDelayFilter optimal, uncorrected;
};

template <class Filter>
void run_generated(const std::vector<double>& dy, double a, double sigma, double dt, std::vector<double>& m) {
  Filter filter;
  filter.params.a = a;
  filter.params.sigma = sigma;
  m.resize(dy.size() + 1);
  m[0] = filter.state[0];
  for (std::size_t k = 0; k < dy.size(); ++k) {
    filter.step(&dy[k]);
    m[k + 1] = filter.state[0];
  }
  // The filter was generated for one grid step; data on another grid would be silently wrong.
  if (!dy.empty() && std::abs(filter.time() - static_cast<double>(dy.size()) * dt) > 1e-9 * filter.time())
    throw std::logic_error("delay_reference: a generated filter's dt differs from its case's (" + std::to_string(dt) + ")");
}

}  // namespace pfgen_bench
