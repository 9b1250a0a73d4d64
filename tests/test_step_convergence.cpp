// The generated `step` (Heun's predictor-corrector) is second order on the
// deterministic part: with a smooth, noise-free observation increment
// dy = y(t+dt) - y(t), halving dt divides the error at T by about 4.
#include <catch2/catch.hpp>

#include <array>
#include <cmath>

#include "generated/basin_skliar_partial/optimal.hpp"

namespace filter = pfgen_models::basin_skliar_partial::optimal;

namespace {

// A smooth observation path y(t); its exact increments drive the filter.
double observation(double t) { return 1.1 * t + 0.3 * std::sin(2 * t); }

std::array<double, filter::state_size> run(double dt, double T) {
  std::array<double, filter::state_size> state{};
  filter::initial_state(state.data());
  const filter::Params<double> params{};
  const long steps = std::lround(T / dt);
  for (long k = 0; k < steps; ++k) {
    const double t = k * dt;
    const double dy[1] = {observation(t + dt) - observation(t)};
    filter::step(state.data(), t, dt, dy, params);
  }
  return state;
}

double distance(const std::array<double, filter::state_size>& a, const std::array<double, filter::state_size>& b) {
  double d = 0;
  for (std::size_t i = 0; i < a.size(); ++i) d = std::max(d, std::abs(a[i] - b[i]));
  return d;
}

}  // namespace

TEST_CASE("generated step converges with order 2 on the deterministic part", "[codegen][step][unit]") {
  const double T = 2.0;
  // Reference: the same scheme at a step 64 times smaller than the finest tested
  // (its own error is ~4000 times smaller than the errors measured).
  const auto reference = run(0.1 / 512, T);
  const double e1 = distance(run(0.1 / 8, T), reference);
  const double e2 = distance(run(0.1 / 16, T), reference);
  const double e3 = distance(run(0.1 / 32, T), reference);
  const double order12 = std::log2(e1 / e2);
  const double order23 = std::log2(e2 / e3);
  INFO("errors " << e1 << " " << e2 << " " << e3 << ", observed orders " << order12 << " " << order23);
  CHECK(e1 > 0);
  CHECK(order12 > 1.8);
  CHECK(order12 < 2.2);
  CHECK(order23 > 1.8);
  CHECK(order23 < 2.2);
}
