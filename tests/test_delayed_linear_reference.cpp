// The augmented-state Kalman filter of tests/support/delayed_linear_reference.hpp, the exact
// reference the delay filter kinds are measured against (docs/reproductions/basin-rodriguez-gonzalez-martinez-zuniga-2004.md), checked
// against what does not share its code: the scalar Kalman filter written out here (no delay),
// and its own truth simulation (its error variance must be its P).
#include <catch2/catch.hpp>

#include <algorithm>
#include <cmath>
#include <cstddef>
#include <vector>

#include "support/delayed_linear_reference.hpp"

using pfgen_test::AugmentedKalman;
using pfgen_test::AugmentedKalmanGain;
using pfgen_test::AugmentedMean;
using pfgen_test::DelayedLinearModel;
using pfgen_test::DelayedObservationRule;

TEST_CASE("delayed linear reference: with D = 0 and the left-point rule it is the scalar Kalman filter",
          "[delay][reference][unit]") {
  for (const double a : {-1.0, 0.7}) {
    DelayedLinearModel model;
    model.a = a;
    model.sigma = 0.8;
    model.dt = 0.05;
    model.D = 0;
    model.m0 = 0.3;
    model.P0 = 2.0;
    model.rule = DelayedObservationRule::left_point;
    const std::size_t steps = 200;
    const auto path = pfgen_test::simulate_delayed_linear(model, steps, 11, 0);
    AugmentedKalman reference(model);
    // dy_k = dt x_k + v_k, Var v_k = dt: update x_k with dy_k, then predict x_{k+1}.
    const double F = std::exp(a * model.dt);
    const double Q = model.sigma * model.sigma * (std::exp(2 * a * model.dt) - 1) / (2 * a);
    double m = model.m0, P = model.P0;
    for (std::size_t k = 0; k < steps; ++k) {
      const double S = model.dt * model.dt * P + model.dt;
      const double K = P * model.dt / S;
      m += K * (path.dy[k] - model.dt * m);
      P -= K * K * S;
      m = F * m;
      P = F * F * P + Q;
      reference.step(path.dy[k]);
      INFO("a = " << a << ", step " << k);
      REQUIRE(std::abs(reference.mean() - m) < 1e-12 * (1 + std::abs(m)));
      REQUIRE(reference.variance() == Approx(P).epsilon(1e-12));
    }
    // The filter has learnt something: its variance is below the prior's stationary value.
    const double prior = a < 0 ? model.sigma * model.sigma / (-2 * a) : 1e300;
    CHECK(reference.variance() < prior);
  }
}

TEST_CASE("delayed linear reference: its error variance over its own truths is its P (D = 3, both rules)",
          "[delay][reference][statistical]") {
  const std::size_t runs = 20000, steps = 40;
  const std::vector<std::size_t> checkpoints = {2, 10, 40};  // step 2 is inside the pre-history
  for (const double a : {-1.0, 0.5}) {
    for (const auto rule : {DelayedObservationRule::trapezoid, DelayedObservationRule::left_point}) {
      DelayedLinearModel model;
      model.a = a;
      model.sigma = 1.0;
      model.dt = 0.1;
      model.D = 3;
      model.m0 = 0.5;
      model.P0 = 1.0;
      model.rule = rule;
      AugmentedKalmanGain gain(model);
      std::vector<AugmentedMean> means(runs, AugmentedMean(model));
      std::vector<pfgen_test::DelayedLinearPath> paths;
      paths.reserve(runs);
      for (std::size_t r = 0; r < runs; ++r) paths.push_back(pfgen_test::simulate_delayed_linear(model, steps, 5, r));
      for (std::size_t k = 0; k < steps; ++k) {
        gain.advance();
        double sum = 0, sum_squares = 0;
        for (std::size_t r = 0; r < runs; ++r) {
          means[r].advance(gain, paths[r].dy[k]);
          const double e = paths[r].x[k + 1] - means[r].mean();
          sum += e;
          sum_squares += e * e;
        }
        if (std::find(checkpoints.begin(), checkpoints.end(), k + 1) == checkpoints.end()) continue;
        const double P = gain.variance(), n = static_cast<double>(runs);
        INFO("a = " << a << ", rule " << (rule == DelayedObservationRule::trapezoid ? "trapezoid" : "left point")
                    << ", step " << k + 1 << ": P = " << P << ", mean e^2 = " << sum_squares / n);
        // Gaussian errors: the mean square's standard error is P sqrt(2/n) (1 %); allow 5 of them.
        CHECK(std::abs(sum_squares / n - P) < 5 * P * std::sqrt(2 / n));
        CHECK(std::abs(sum / n) < 5 * std::sqrt(P / n));
      }
    }
  }
}

TEST_CASE("delayed linear reference: a delay costs information, P grows with D", "[delay][reference][unit]") {
  // The same data arrive later with a larger D, so the conditional variance of x_k cannot be
  // smaller; with a stable a it is bounded by the prior's stationary variance σ²/(−2a).
  double previous = 0;
  for (const std::size_t D : {0, 1, 5, 20, 50}) {
    DelayedLinearModel model;
    model.a = -1.0;
    model.dt = 0.02;
    model.D = D;
    AugmentedKalmanGain gain(model);
    for (int k = 0; k < 500; ++k) gain.advance();
    INFO("D = " << D << ": P = " << gain.variance());
    CHECK(gain.variance() > previous);
    CHECK(gain.variance() < 0.5 * model.sigma * model.sigma / 1.0);
    previous = gain.variance();
  }
}

TEST_CASE("delayed linear reference: its steady P tends to the continuous-time value as dt shrinks", "[delay][reference][unit]") {
  // For dx = a x dt + σ dW1, dy = x(t − h) dt + dW2 the data up to t are those of the undelayed
  // problem up to t − h, so Var[x(t) | Y(t)] = e^{2ah} P_KB + σ² (e^{2ah} − 1)/(2a), with the
  // Kalman–Bucy P_KB = a + sqrt(a² + σ²): a formula that shares nothing with the recursion.
  for (const double a : {-1.0, 0.5}) {
    const double h = 0.5, sigma = 1.0;
    const double P_kb = a + std::sqrt(a * a + sigma * sigma);
    const double expected = std::exp(2 * a * h) * P_kb + sigma * sigma * std::expm1(2 * a * h) / (2 * a);
    double previous_gap = 1e300;
    for (const double dt : {0.05, 0.01}) {
      DelayedLinearModel model;
      model.a = a;
      model.sigma = sigma;
      model.dt = dt;
      model.D = static_cast<std::size_t>(std::llround(h / dt));
      AugmentedKalmanGain gain(model);
      for (int k = 0; k < static_cast<int>(std::llround(20 / dt)); ++k) gain.advance();
      const double gap = std::abs(gain.variance() - expected);
      INFO("a = " << a << ", dt = " << dt << ": P = " << gain.variance() << ", continuous " << expected);
      CHECK(gap < 1e-3 * expected);
      CHECK(gap < previous_gap);
      previous_gap = gap;
    }
  }
}
