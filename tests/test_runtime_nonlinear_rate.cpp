// A continuous observation with a nonlinear rate h(t, x) (a FunctionRate, the polynomial
// observation's truth and particle weights, docs/theory.md §2.9 and §7.4): the truth's increments
// are the trapezoid of h plus B dW2; a rate that is A0 + A x written as a function gives the affine
// observation's increments and particle reference bit for bit; the rate and the delay are
// independent axes, while a delay of samples is refused.
#include <catch2/catch.hpp>

#include <cstring>
#include <stdexcept>

#include <Eigen/Core>

#include "pfgen_runtime/particle_reference.hpp"
#include "pfgen_runtime/schemes.hpp"
#include "pfgen_runtime/simulation.hpp"
#include "support/scalar_linear_system.hpp"

using namespace pfgen_runtime;
using pfgen_test::ScalarLinear;

namespace {

bool same_bits(const Eigen::MatrixXd& a, const Eigen::MatrixXd& b) {
  return a.rows() == b.rows() && a.cols() == b.cols() &&
         std::memcmp(a.data(), b.data(), sizeof(double) * static_cast<std::size_t>(a.size())) == 0;
}

// dy = 2 x dt + r dW2, linear, and the same with its rate given as a function of (t, x).
Observation linear(double r) {
  return Observation(Eigen::VectorXd::Zero(1), Eigen::MatrixXd::Constant(1, 1, 2.0), Eigen::MatrixXd::Constant(1, 1, r));
}
Observation as_function(double r) {
  // 0 + 2 x: the affine rate's own order of operations (A0 first, then A x).
  return Observation::continuous(
      std::make_unique<FunctionRate>(1, 1, [](double, const double* x, double* h) { h[0] = 0.0 + 2.0 * x[0]; }),
      ObservationNoise(1, 1, [r](double, Eigen::MatrixXd& B) { B(0, 0) = r; }));
}

}  // namespace

TEST_CASE("nonlinear observation rate: the truth's increment is the trapezoid of h plus B dW2", "[runtime][unit]") {
  Observation observation = Observation::continuous(std::make_unique<FunctionRate>(2, 2,
                                                                                    [](double t, const double* x, double* h) {
                                                                                      h[0] = x[0] * x[0] + x[1] * x[1];
                                                                                      h[1] = t * x[0] * x[1] * x[1];
                                                                                    }),
                                                    ObservationNoise(2, 1, [](double t, Eigen::MatrixXd& B) {
                                                      B(0, 0) = 0.5;
                                                      B(1, 0) = t;
                                                    }));
  CHECK_FALSE(observation.rate().affine());
  CHECK(linear(0.5).rate().affine());
  Eigen::VectorXd start(2), end(2), dW(1), dy(2);
  start << 1.0, -2.0;
  end << 1.5, 0.5;
  dW << 0.25;
  observation.increment(0.5, 0.1, start, end, dW, dy);
  CHECK(dy[0] == Approx(0.5 * (5.0 + 2.5) * 0.1 + 0.5 * 0.25).epsilon(1e-15));
  CHECK(dy[1] == Approx(0.5 * (0.5 * 4.0 + 0.6 * 0.375) * 0.1 + 0.5 * 0.25).epsilon(1e-15));
  Eigen::VectorXd rate(2);
  observation.rate().value(0.6, end.data(), rate.data());
  CHECK(rate[0] == 2.5);
  CHECK(rate[1] == Approx(0.6 * 0.375).epsilon(1e-15));
}

TEST_CASE("observation axes: a delay composes with any rate, not with samples", "[runtime][unit]") {
  // dy over the step ending at t = 0.3 reads x(0.3 - h) = x(0.1) and x(0.2 - h) = x(0): the
  // function rate's increment on the delayed path equals the affine one's.
  ScalarLinear model;
  EulerMaruyama scheme(pfgen_test::scalar_linear_system(model));
  Observation line = linear(model.r), function = as_function(model.r);
  line.set_delay(0.2);
  function.set_delay(0.2);
  CHECK(function.delay_steps(0.1) == 2);
  const TimeGrid grid = TimeGrid::to_horizon(0.0, 1.0, 0.1);
  const TruthRun a = simulate_truth(scheme, line, Eigen::VectorXd::Constant(1, 0.3), grid, 5, 1);
  const TruthRun b = simulate_truth(scheme, function, Eigen::VectorXd::Constant(1, 0.3), grid, 5, 1);
  REQUIRE(a.completed_steps == grid.steps);
  CHECK(same_bits(a.dy, b.dy));
  Observation samples = Observation::sampled(std::make_unique<AffineRate>(Eigen::VectorXd::Zero(1),
                                                                          Eigen::MatrixXd::Identity(1, 1)),
                                             ObservationNoise(Eigen::MatrixXd::Identity(1, 1)), 0.5);
  CHECK_THROWS_WITH(samples.set_delay(0.1), Catch::Contains("a delay needs continuous observations"));
  // Each timing answers for itself: samples draw no increment noise in the truth's loop, and
  // increments have no samples.
  CHECK(samples.increment_noise() == 0);
  CHECK(samples.steps_per_sample(0.1) == 5);
  CHECK(line.increment_noise() == 1);
  CHECK_THROWS_WITH(line.steps_per_sample(0.1), Catch::Contains("no samples"));
}

TEST_CASE("nonlinear observation rate: A0 + A x as a function gives the linear truth and particle reference bit for bit",
          "[particles][runtime][unit]") {
  ScalarLinear model;
  EulerMaruyama scheme(pfgen_test::scalar_linear_system(model));
  Observation line = linear(model.r), function = as_function(model.r);
  const TimeGrid grid = TimeGrid::to_horizon(0.0, 1.0, 0.01);
  const TruthRun a = simulate_truth(scheme, line, Eigen::VectorXd::Constant(1, 0.3), grid, 5, 1);
  const TruthRun b = simulate_truth(scheme, function, Eigen::VectorXd::Constant(1, 0.3), grid, 5, 1);
  REQUIRE(a.completed_steps == grid.steps);
  CHECK(same_bits(a.x, b.x));
  CHECK(same_bits(a.dy, b.dy));

  ParticleReferenceOptions options;
  options.particles = 200;
  options.m0 = Eigen::VectorXd::Constant(1, model.m0);
  options.P0 = Eigen::MatrixXd::Constant(1, 1, model.P0);
  ParticleReference from_line(scheme, line, options, 1e8), from_function(scheme, function, options, 1e8);
  Eigen::MatrixXd mean_line(1, grid.steps + 1), mean_function(1, grid.steps + 1);
  const auto last = static_cast<std::ptrdiff_t>(grid.steps);
  const ParticleReferenceRun ra = from_line.run(grid, a.dy, last, 5, 1, mean_line);
  const ParticleReferenceRun rb = from_function.run(grid, a.dy, last, 5, 1, mean_function);
  CHECK(ra.last == last);
  CHECK(ra.resamplings > 0);  // the weights moved: the rate was used
  CHECK(ra.resamplings == rb.resamplings);
  CHECK(same_bits(mean_line, mean_function));
}
