// FilterStepper: grid steps of a filter are split where one explicit step would be unstable.
#include <catch2/catch.hpp>

#include <cmath>
#include <vector>

#include "pfgen_runtime/filter_stepping.hpp"

using pfgen_runtime::FilterStepControl;
using pfgen_runtime::FilterStepper;

namespace {

// A scalar Kalman-Bucy filter for dx = q^(1/2) dW1, dy = x dt + r^(1/2) dW2, stepped by Heun as
// generated code steps: dm = (P / r)(dy - m dt), dP = (q - P^2 / r) dt.
struct ScalarKalmanBucy {
  double q, r;
  void increment(const double* s, double dt, double dy, double* d) const {
    d[0] = s[1] / r * (dy - s[0] * dt);
    d[1] = (q - s[1] * s[1] / r) * dt;
  }
  void operator()(double* s, double, double dt, const double* dy) const {
    double first[2], predicted[2], second[2];
    increment(s, dt, dy[0], first);
    for (int i = 0; i < 2; ++i) predicted[i] = s[i] + first[i];
    increment(predicted, dt, dy[0], second);
    for (int i = 0; i < 2; ++i) s[i] += 0.5 * (first[i] + second[i]);
  }
};

// P(t) of the Riccati equation P' = q - P^2 / r from P0: sqrt(q r) coth or tanh form.
double riccati(double q, double r, double P0, double t) {
  const double s = std::sqrt(q * r), k = std::sqrt(q / r);
  const double c = (P0 - s) / (P0 + s) * std::exp(-2 * k * t);
  return s * (1 + c) / (1 - c);
}

}  // namespace

TEST_CASE("FilterStepper keeps a stiff Riccati equation stable and accurate where a fixed step explodes", "[runtime][stepping][unit]") {
  const ScalarKalmanBucy filter{1.0, 1e-4};  // P0 = 100: P dt / r = 1e4 at dt = 1e-2
  const double dt = 1e-2, dy = 0.0;
  FilterStepControl fixed;
  fixed.adaptive = false;
  std::vector<double> plain{0.0, 100.0}, refined{0.0, 100.0};
  FilterStepper fixed_stepper(1, 1, fixed), stepper(1, 1, FilterStepControl{});
  for (int k = 0; k < 100; ++k) {
    fixed_stepper.advance(filter, plain.data(), k * dt, dt, &dy);
    stepper.advance(filter, refined.data(), k * dt, dt, &dy);
  }
  CHECK_FALSE(std::abs(plain[1]) < 1e6);  // the explicit step alone diverges (or is non-finite)
  // Stable, but not exact: once P has settled at sqrt(q r) = 0.01, P dt / r = 1 sits at the edge
  // of Heun's stability region, where single steps change P too little to be refined and the
  // approach to the fixed point is slow (3.3 % off at t = 1). The stepper guards stability; dt
  // still sets the accuracy.
  CHECK(refined[1] == Approx(riccati(1.0, 1e-4, 100.0, 1.0)).epsilon(0.05));
  CHECK(stepper.refined_steps() > 0);
  CHECK(stepper.refined_steps() < 100);  // once P has settled, single steps are stable again
}

TEST_CASE("FilterStepper takes exactly the plain step where nothing is stiff", "[runtime][stepping][unit]") {
  const ScalarKalmanBucy filter{0.5, 1.0};
  std::vector<double> a{0.3, 2.0}, b{0.3, 2.0};
  FilterStepControl off;
  off.adaptive = false;
  FilterStepper plain(1, 1, off), adaptive(1, 1, FilterStepControl{});
  for (int k = 0; k < 1000; ++k) {
    const double dy = 0.01 * std::sin(0.37 * k);  // any increments
    plain.advance(filter, a.data(), k * 1e-3, 1e-3, &dy);
    adaptive.advance(filter, b.data(), k * 1e-3, 1e-3, &dy);
  }
  CHECK(a == b);  // bit for bit
  CHECK(adaptive.refined_steps() == 0);
}

TEST_CASE("FilterStepper sub-steps share dy evenly: the estimate follows a constant observation rate", "[runtime][stepping][unit]") {
  // Stiff from the start (P0 = 100, r = 1e-4), observations at the constant rate v: dy = v dt.
  // dm = (P / r)(v - m) dt drives m to v whatever P does, but only if each sub-step of length h
  // gets v h: any other split of dy would move the limit.
  const ScalarKalmanBucy filter{1.0, 1e-4};
  const double dt = 1e-2, v = 2.0, dy = v * dt;
  std::vector<double> s{0.0, 100.0};
  FilterStepper stepper(1, 1, FilterStepControl{});
  for (int k = 0; k < 100; ++k) stepper.advance(filter, s.data(), k * dt, dt, &dy);
  CHECK(stepper.refined_steps() > 0);
  CHECK(s[0] == Approx(v).epsilon(1e-9));
}

TEST_CASE("FilterStepper stops a grid step that would need more sub-steps than its budget", "[runtime][stepping][unit]") {
  // A "filter" whose P doubles on every step, however short: no sub-step is ever acceptable, as
  // for a filter that blows up within the grid step. Without a budget the stepper would take
  // 2^max_depth calls on each grid step.
  std::uint64_t calls = 0;
  auto exploding = [&calls](double* s, double, double, const double*) {
    ++calls;
    s[1] *= 2;
  };
  FilterStepControl control;
  control.max_substeps = 100;
  FilterStepper stepper(1, 1, control);
  std::vector<double> s{0.0, 1.0};
  const double dy = 0;
  CHECK(stepper.advance(exploding, s.data(), 0.0, 0.1, &dy) == 0);  // the run must stop
  CHECK(calls <= control.max_substeps + 1);                          // the first try, then at most the budget
  CHECK(calls > control.max_substeps / 2);

  // A step that settles after a few splits is within the budget and reported as usual.
  ScalarKalmanBucy stiff{1.0, 1e-4};
  FilterStepper fine(1, 1, FilterStepControl{});
  std::vector<double> k{0.0, 1.0};
  CHECK(fine.advance(stiff, k.data(), 0.0, 0.01, &dy) > 1);
}

TEST_CASE("FilterStepper tells equations that are not finite at the state from a step that is too stiff",
          "[runtime][stepping][unit]") {
  FilterStepControl control;
  control.max_substeps = 100;
  const double dy = 0;
  // P doubles on every step, however short: too stiff, but its rates are finite at the state.
  auto exploding = [](double* s, double, double, const double*) { s[1] *= 2; };
  FilterStepper stiff(1, 1, control);
  std::vector<double> a{0.0, 1.0};
  REQUIRE(stiff.advance(exploding, a.data(), 0.0, 0.1, &dy) == 0);
  CHECK(stiff.equations_finite_at_start(exploding, 0.0));
  // A definition 1 / (m - 0.5) at m = 0.5: the rates themselves are not finite, whatever the step.
  auto undefined = [](double* s, double, double dt, const double*) {
    const double r = 1 / (s[0] - 0.5);
    s[0] += r * dt;
    s[1] += r * dt;
  };
  FilterStepper stepper(1, 1, control);
  std::vector<double> b{0.5, 1.0};
  REQUIRE(stepper.advance(undefined, b.data(), 0.0, 0.1, &dy) == 0);
  CHECK_FALSE(stepper.equations_finite_at_start(undefined, 0.0));
}
