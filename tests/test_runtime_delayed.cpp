// Delayed observations in the runtime: the truth's dy reads x(t - h) on the grid (with the
// pre-history x(s) = x(0), s < 0), checked against a path known in closed form; h must be a
// whole number of steps; a filter with extra state and a fixed grid step (a delayed filter's
// calling convention) is stepped exactly once per grid step, never refined, only on its own grid,
// and gives the same bits in run_filter and in the Monte Carlo engine on any number of threads;
// a checked-in generated delayed filter plugs in through make_delayed_filter_model.
#include <catch2/catch.hpp>

#include <cmath>
#include <cstring>
#include <limits>
#include <stdexcept>
#include <vector>

#include "generated/delay_linear/delay_optimal.hpp"
#include "pfgen_runtime/monte_carlo.hpp"
#include "pfgen_runtime/random.hpp"
#include "pfgen_runtime/simulation.hpp"

using namespace pfgen_runtime;

namespace {

// dx = 0.5 dt from x0 = 1: Euler's path is x(t) = 1 + 0.5 t up to round-off.
SdeSystem constant_drift() {
  SdeSystem system;
  system.n = 1;
  system.q = 0;
  system.drift = [](double, const double*, double* f) { f[0] = 0.5; };
  return system;
}

// dy = (t + 3 x(t - h)) dt + 0.5 dW2: A0 depends on t, so the test also sees that the
// coefficients are taken at t, not t - h.
Observation delayed_observation(double h) {
  Observation observation(1, 1, 1, [](double t, Eigen::VectorXd& A0, Eigen::MatrixXd& A, Eigen::MatrixXd& B) {
    A0 << t;
    A << 3.0;
    B << 0.5;
  });
  observation.set_delay(h);
  return observation;
}

// A scalar filter in a delayed filter's calling convention: state [m, P, steps taken, ring of
// the last D values of m]. It reads m D steps back (m0 before the start), and makes itself
// NaN when called off the grid or more than once per grid step, so a refined step shows.
// P halves every step: FilterStepper would refine such a step (its limit is a 2 % change).
constexpr std::size_t kD = 4;
constexpr double kDt = 0.01;
constexpr double kM0 = 0.25;

FilterModel ring_filter(double fixed_dt = kDt) {
  FilterModel filter;
  filter.name = "ring";
  filter.n = 1;
  filter.p = 1;
  filter.initial_state = [](double* state) {
    state[0] = kM0;
    state[1] = 4.0;
    state[2] = 0.0;
    for (std::size_t j = 0; j < kD; ++j) state[3 + j] = kM0;
  };
  const FilterStepFunction step = [](double* state, double t, double dt, const double* dy) {
    const double k = std::round(t / kDt);
    if (state[2] != k || dt != kDt) state[0] = std::numeric_limits<double>::quiet_NaN();
    double* ring = state + 3;
    const std::size_t slot = static_cast<std::size_t>(k) % kD;
    const double m_delayed = ring[slot];  // m at grid index k - D (m0 before t = 0)
    ring[slot] = state[0];
    state[0] += 0.5 * state[1] * (dy[0] - (t + 3.0 * m_delayed) * dt);
    state[1] *= 0.5;
    state[2] += 1.0;
  };
  filter.timing = std::make_unique<FixedSteps>(step, fixed_dt, 1 + kD);
  return filter;
}

bool same_bits(const Eigen::MatrixXd& a, const Eigen::MatrixXd& b) {
  return a.rows() == b.rows() && a.cols() == b.cols() &&
         (a.size() == 0 || std::memcmp(a.data(), b.data(), static_cast<std::size_t>(a.size()) * sizeof(double)) == 0);
}

bool same_bits(const std::vector<double>& a, const std::vector<double>& b) {
  return a.size() == b.size() && (a.empty() || std::memcmp(a.data(), b.data(), a.size() * sizeof(double)) == 0);
}

}  // namespace

TEST_CASE("runtime delayed: dy reads x(t - h) on the grid, x(0) before t = 0", "[runtime][delayed][unit]") {
  const double h = 0.05, dt = 0.01;  // D = 5
  Observation observation = delayed_observation(h);
  REQUIRE(observation.delay_steps(dt) == 5);
  EulerMaruyama scheme(constant_drift());
  const TimeGrid grid = TimeGrid::to_horizon(0.0, 0.2, dt);
  const TruthRun run = simulate_truth(scheme, observation, Eigen::VectorXd::Ones(1), grid, 9, 3);
  REQUIRE(run.completed_steps == 20);

  auto x = [](double s) { return 1.0 + 0.5 * std::max(s, 0.0); };  // the path and its pre-history
  RandomStream noise(9, 3, substream::observation_noise);
  Eigen::VectorXd dW2(1);
  for (std::size_t k = 0; k < grid.steps; ++k) {
    noise.wiener_increment(dt, dW2);
    const double t = grid.time(k);
    CHECK(run.x(0, static_cast<Eigen::Index>(k)) == Approx(x(t)).margin(1e-14));
    // Trapezoid over [t, t + dt] of A0(t) + A x(t - h), B at the left end.
    const double expected = 0.5 * ((t + 3.0 * x(t - h)) + (t + dt + 3.0 * x(t + dt - h))) * dt + 0.5 * dW2[0];
    INFO("k = " << k);
    CHECK(run.dy(0, static_cast<Eigen::Index>(k)) == Approx(expected).margin(1e-14));
  }
  // The first D steps see only the pre-history: 3 x(0) dt each, plus t and the noise.
  noise = RandomStream(9, 3, substream::observation_noise);
  noise.wiener_increment(dt, dW2);
  CHECK(run.dy(0, 0) == Approx(0.5 * (0.0 + dt) * dt + 3.0 * dt + 0.5 * dW2[0]).margin(1e-15));

  // The same run without a delay draws the same noise: the difference is A (x(t - h) - x(t)) only.
  Observation undelayed = delayed_observation(0.0);
  EulerMaruyama scheme0(constant_drift());
  const TruthRun run0 = simulate_truth(scheme0, undelayed, Eigen::VectorXd::Ones(1), grid, 9, 3);
  CHECK(same_bits(run0.x, run.x));
  for (std::size_t k = 0; k < grid.steps; ++k) {
    const auto c = static_cast<Eigen::Index>(k);
    const double t = grid.time(k);
    const double shift = 1.5 * (x(t - h) - x(t) + x(t + dt - h) - x(t + dt)) * dt;
    CHECK(run.dy(0, c) - run0.dy(0, c) == Approx(shift).margin(1e-14));
  }
}

TEST_CASE("runtime delayed: h must be a whole number of steps, at most 10^7 of them", "[runtime][delayed][unit]") {
  Observation observation = delayed_observation(0.3);
  CHECK(observation.delay_steps(0.1) == 3);  // 0.3 / 0.1 = 2.9999999999999996: within 1e-9
  CHECK(observation.delay_steps(0.3) == 1);
  CHECK_THROWS_WITH(observation.delay_steps(0.07),
                    Catch::Contains("delay h = 0.29999999999999999 is not a whole number of steps dt = 0.070000000000000007"));
  CHECK_THROWS_AS(observation.delay_steps(0.6), std::invalid_argument);  // half a step
  CHECK_THROWS_WITH(observation.delay_steps(1e-8), Catch::Contains("more than 10000000 steps"));
  CHECK(delayed_observation(0.0).delay_steps(0.07) == 0);
  CHECK_THROWS_AS(observation.set_delay(-0.1), std::invalid_argument);
  CHECK_THROWS_AS(observation.set_delay(std::numeric_limits<double>::infinity()), std::invalid_argument);

  // The engine refuses such a grid before any run starts.
  EulerMaruyama scheme(constant_drift());
  MonteCarloOptions options;
  options.grid = TimeGrid::to_horizon(0.0, 1.4, 0.07);
  options.runs = 2;
  CHECK_THROWS_WITH(run_monte_carlo(scheme, observation, Eigen::VectorXd::Ones(1), {}, options),
                    Catch::Contains("not a whole number of steps"));
}

TEST_CASE("runtime delayed: a fixed-step filter with extra state is stepped once per grid step, on its grid only", "[runtime][delayed][unit]") {
  Observation observation = delayed_observation(kD * kDt);
  EulerMaruyama scheme(constant_drift());
  const TimeGrid grid = TimeGrid::to_horizon(0.0, 0.5, kDt);
  const TruthRun truth = simulate_truth(scheme, observation, Eigen::VectorXd::Ones(1), grid, 4, 1);
  const FilterModel filter = ring_filter();
  REQUIRE(filter.state_size() == 2 + 1 + kD);

  const FilterRun result = run_filter(filter, truth);
  CHECK_FALSE(result.stopped);  // a refined or repeated step would have made m NaN
  CHECK(result.completed_steps == grid.steps);
  CHECK(result.refined_steps == 0);
  CHECK(result.state.rows() == 2);  // m and P only: the extra state is the filter's own
  CHECK(result.state(1, 50) == Approx(4.0 * std::pow(0.5, 50)));

  // The same filter by hand, reading m D steps back.
  double m = kM0, P = 4.0;
  std::vector<double> history(grid.steps + 1, kM0);
  for (std::size_t k = 0; k < grid.steps; ++k) {
    history[k] = m;
    const double m_delayed = k >= kD ? history[k - kD] : kM0;
    m += 0.5 * P * (truth.dy(0, static_cast<Eigen::Index>(k)) - (grid.time(k) + 3.0 * m_delayed) * kDt);
    P *= 0.5;
  }
  CHECK(result.state(0, 50) == Approx(m).epsilon(1e-12));

  // Extra state belongs to a fixed step (FixedSteps), which needs a grid step.
  CHECK_THROWS_WITH(ring_filter(0.0), Catch::Contains("a fixed-step filter needs a finite grid step > 0"));
  CHECK_THROWS_WITH(run_filter(ring_filter(0.02), truth), Catch::Contains("was generated for the grid"));
  TruthRun shifted = truth;
  shifted.grid.t0 = 1.0;
  CHECK_THROWS_WITH(run_filter(filter, shifted), Catch::Contains("starts after 0"));
}

TEST_CASE("runtime delayed: Monte Carlo runs equal run_filter's, bitwise, on 1 and 2 threads", "[runtime][delayed][montecarlo][unit]") {
  Observation observation = delayed_observation(kD * kDt);
  SdeSystem system = constant_drift();
  system.q = 1;
  system.diffusion = [](double, const double*, double* g) { g[0] = 0.3; };
  EulerMaruyama scheme(system);
  MonteCarloOptions options;
  options.grid = TimeGrid::to_horizon(0.0, 0.4, kDt);
  options.runs = 7;
  options.seed = 12;
  options.record_points = 100;  // every grid point
  options.shown_run = 5;
  options.report_times = {0.2, 0.4};
  const std::vector<FilterModel> filters{ring_filter()};
  const Eigen::VectorXd x0 = Eigen::VectorXd::Ones(1);

  options.threads = 1;
  const MonteCarloResult one = run_monte_carlo(scheme, observation, x0, filters, options);
  options.threads = 2;
  const MonteCarloResult two = run_monte_carlo(scheme, observation, x0, filters, options);
  REQUIRE(one.filters.size() == 1);
  CHECK(one.filters[0].divergences.count() == 0);
  CHECK(one.filters[0].refined_steps == 0);
  CHECK(same_bits(one.filters[0].horizon.rms, two.filters[0].horizon.rms));
  for (std::size_t r = 0; r < 2; ++r) CHECK(same_bits(one.filters[0].reports[r].rms, two.filters[0].reports[r].rms));
  CHECK(same_bits(one.series.filters[0].error.mean, two.series.filters[0].error.mean));
  CHECK(same_bits(one.series.filters[0].m, two.series.filters[0].m));
  CHECK(same_bits(one.series.truth, two.series.truth));

  // The shown run is simulate_truth + run_filter of run 5, bit for bit.
  EulerMaruyama single(system);
  const TruthRun truth = simulate_truth(single, observation, x0, options.grid, options.seed, 5);
  const FilterRun run = run_filter(filters[0], truth);
  REQUIRE(one.series.index.size() == options.grid.steps + 1);
  for (std::size_t j = 0; j <= options.grid.steps; ++j) {
    INFO("grid index " << j);
    const auto c = static_cast<Eigen::Index>(j);
    CHECK(std::memcmp(&one.series.truth(c, 0), &truth.x(0, c), sizeof(double)) == 0);
    CHECK(std::memcmp(&one.series.filters[0].m(c, 0), &run.state(0, c), sizeof(double)) == 0);
  }
}

TEST_CASE("runtime delayed: a generated delayed filter plugs in and steps as its own Filter object", "[runtime][delayed][unit]") {
  // examples/delay_linear.yaml: dx = -0.5 x dt + 0.3 dW1, dy = x(t - 0.5) dt + 0.2 dW2, dt = 0.01.
  namespace F = pfgen_models::delay_linear::delay_optimal;
  const FilterModel filter =
      make_delayed_filter_model("delay-optimal", F::n, F::p, F::state_size, F::history_size, F::dt<double>(),
                                &F::initial_state<double>, &F::initial_history<double>, &F::step<double>);
  CHECK(dynamic_cast<const FixedSteps&>(*filter.timing).fixed_dt() == 0.01);
  CHECK(filter.state_size() == F::state_size + F::history_size);
  SdeSystem system;
  system.n = 1;
  system.q = 1;
  system.drift = [](double, const double* x, double* f) { f[0] = -0.5 * x[0]; };
  system.diffusion = [](double, const double*, double* g) { g[0] = 0.3; };
  EulerMaruyama scheme(system);
  Observation observation(Eigen::VectorXd::Zero(1), Eigen::MatrixXd::Ones(1, 1),
                                Eigen::MatrixXd::Constant(1, 1, 0.2));
  observation.set_delay(F::delay<double>());
  const TimeGrid grid = TimeGrid::to_horizon(0.0, 2.0, F::dt<double>());
  const TruthRun truth = simulate_truth(scheme, observation, Eigen::VectorXd::Ones(1), grid, 3, 2);
  const FilterRun run = run_filter(filter, truth);
  REQUIRE(run.completed_steps == grid.steps);

  F::Filter<double> direct;
  for (std::size_t k = 0; k < grid.steps; ++k) {
    direct.step(truth.dy.col(static_cast<Eigen::Index>(k)).data());
    const auto c = static_cast<Eigen::Index>(k + 1);
    INFO("step " << k);
    REQUIRE(std::memcmp(&run.state(0, c), &direct.state[0], sizeof(double)) == 0);
    REQUIRE(std::memcmp(&run.state(1, c), &direct.state[1], sizeof(double)) == 0);
  }
  CHECK(run.state(1, static_cast<Eigen::Index>(grid.steps)) < 0.25);  // the observations taught it something
}
