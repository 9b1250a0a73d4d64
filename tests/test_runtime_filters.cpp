// Stepping filters on a truth run's observation increments: observations are generated as
// documented, a hand-written Kalman-Bucy filter's error variance matches its P (an end-to-end
// check of truth, observations and stepping), the filter guards stop runs at the right time, and
// a checked-in generated header plugs in through plain function pointers.
#include <catch2/catch.hpp>

#include <algorithm>
#include <cmath>
#include <vector>

#include "generated/basin_skliar_partial/optimal.hpp"
#include "pfgen_runtime/random.hpp"
#include "pfgen_runtime/simulation.hpp"
#include "support/scalar_linear_system.hpp"

using namespace pfgen_runtime;
using pfgen_test::ScalarLinear;
using pfgen_test::scalar_linear_system;

namespace {

// The Kalman-Bucy filter written out by hand, in the generated calling convention.
void kalman_bucy_initial(double* state) {
  const ScalarLinear model;
  state[0] = model.m0;
  state[1] = model.P0;
}

void kalman_bucy_step(double* state, double, double dt, const double* dy, const ScalarLinear& model) {
  const double m = state[0], P = state[1];
  const double K = P / (model.r * model.r);
  state[0] = m - model.a * m * dt + K * (dy[0] - m * dt);
  state[1] = P + (-2 * model.a * P + model.s * model.s - P * P / (model.r * model.r)) * dt;
}


// A filter whose P drift is -1: P = P0 - t becomes negative at t = P0.
void shrinking_initial(double* state) {
  state[0] = 0.0;
  state[1] = 0.5;
}
void shrinking_step(double* state, double, double dt, const double*, const int&) { state[1] -= dt; }

// A filter whose estimate blows up: m' = m^2 from m0 = 1, m = 1 / (1 - t).
void runaway_initial(double* state) {
  state[0] = 1.0;
  state[1] = 1.0;
}
void runaway_step(double* state, double, double dt, const double*, const int&) {
  state[0] += state[0] * state[0] * dt;
}

// A moment filter's shape: m, P and one entry of extra state (a higher moment) that falls as 0.35 - t, whose margin
// is that entry. P falls fast (P' = -40 P), so that every grid step of 0.01 is refined into sub-steps: the extra
// entry must be saved and restored with m and P, or the rejected steps would leave their decrements in it.
void moment_initial(double* state) {
  state[0] = 0.0;
  state[1] = 1.0;
  state[2] = 0.35;
}
void moment_step(double* state, double, double dt, const double*) {
  state[1] -= 40 * state[1] * dt;
  state[2] -= dt;
}

TruthRun quiet_truth(double T, double dt) {
  SdeSystem system;
  system.n = 1;
  system.q = 0;
  system.drift = [](double, const double*, double* f) { f[0] = 0.0; };
  EulerMaruyama scheme(system);
  Observation observation(Eigen::VectorXd::Zero(1), Eigen::MatrixXd::Ones(1, 1), Eigen::MatrixXd::Ones(1, 1));
  return simulate_truth(scheme, observation, Eigen::VectorXd::Zero(1), TimeGrid::to_horizon(0.0, T, dt), 1, 0);
}

}  // namespace

TEST_CASE("runtime: observations dy = (A0 + A x) dt + B dW2 on the truth's grid", "[runtime][filters][unit]") {
  // Time-varying A0, A, B; the truth is deterministic (x = e^t), so dy - drift part is B dW2
  // with dW2 from the run's observation stream.
  SdeSystem system;
  system.n = 1;
  system.q = 0;
  system.drift = [](double, const double* x, double* f) { f[0] = x[0]; };
  AdaptiveEuler scheme(system, AdaptiveEuler::Options{1e-4, 1.0, 40});  // accurate: x = e^t to ~1e-4
  Observation observation(2, 1, 2, [](double t, Eigen::VectorXd& A0, Eigen::MatrixXd& A, Eigen::MatrixXd& B) {
    A0 << 1.0, t;
    A << 2.0, -1.0;
    B << 0.5, 0.0, 0.1 * t, 1.0;
  });
  const TimeGrid grid = TimeGrid::to_horizon(0.0, 1.0, 0.01);
  const TruthRun run = simulate_truth(scheme, observation, Eigen::VectorXd::Ones(1), grid, 21, 4);
  REQUIRE(run.completed_steps == 100);
  CHECK(run.x(0, 100) == Approx(std::exp(1.0)).epsilon(1e-3));

  RandomStream noise(21, 4, substream::observation_noise);
  Eigen::VectorXd dW2(2);
  for (std::size_t k = 0; k < grid.steps; ++k) {
    noise.wiener_increment(grid.dt, dW2);
    const double t = grid.time(k), x0 = run.x(0, static_cast<Eigen::Index>(k)),
                 x1 = run.x(0, static_cast<Eigen::Index>(k + 1));
    // Trapezoid drift, B at the left end.
    const double dy0 = 0.5 * ((1.0 + 2.0 * x0) + (1.0 + 2.0 * x1)) * grid.dt + 0.5 * dW2[0];
    const double dy1 = 0.5 * ((t - x0) + (t + grid.dt - x1)) * grid.dt + 0.1 * t * dW2[0] + dW2[1];
    CHECK(run.dy(0, static_cast<Eigen::Index>(k)) == Approx(dy0).margin(1e-14));
    CHECK(run.dy(1, static_cast<Eigen::Index>(k)) == Approx(dy1).margin(1e-14));
  }
}

TEST_CASE("runtime: a Kalman-Bucy filter stepped on simulated observations has error variance P", "[runtime][filters][statistical]") {
  const ScalarLinear model;
  const FilterModel filter = make_filter_model("kalman-bucy", 1, 1, &kalman_bucy_initial, &kalman_bucy_step, model);
  CHECK(filter.state_size() == 2);
  EulerMaruyama scheme(scalar_linear_system(model));
  Observation observation(Eigen::VectorXd::Zero(1), Eigen::MatrixXd::Ones(1, 1),
                                Eigen::MatrixXd::Constant(1, 1, model.r));
  const TimeGrid grid = TimeGrid::to_horizon(0.0, 3.0, 1e-3);
  const int runs = 2000;
  double sum_error = 0, sum_square = 0, P_end = 0;
  for (int run = 0; run < runs; ++run) {
    // The truth starts from the filter's prior N(m0, P0), drawn from the run's own stream.
    RandomStream initial(8, static_cast<std::uint64_t>(run), substream::initial_state);
    const Eigen::VectorXd x0 = Eigen::VectorXd::Constant(1, model.m0 + std::sqrt(model.P0) * initial.normal());
    const TruthRun truth = simulate_truth(scheme, observation, x0, grid, 8, static_cast<std::uint64_t>(run));
    REQUIRE_FALSE(truth.diverged());
    const FilterRun result = run_filter(filter, truth);
    REQUIRE_FALSE(result.stopped);
    REQUIRE(result.completed_steps == grid.steps);
    REQUIRE(result.state.cols() == static_cast<Eigen::Index>(grid.steps + 1));
    const double error = truth.x(0, truth.x.cols() - 1) - result.state(0, result.state.cols() - 1);
    sum_error += error;
    sum_square += error * error;
    P_end = result.state(1, result.state.cols() - 1);
  }
  const double P_inf = model.P_inf();
  const double mean = sum_error / runs, mse = sum_square / runs;
  INFO("P(3) = " << P_end << " (stationary " << P_inf << "), Monte Carlo error mean " << mean << ", mean square " << mse);
  CHECK(P_end == Approx(P_inf).epsilon(1e-3));
  // runs * mse / P ~ chi-square(runs): relative standard deviation sqrt(2 / runs) = 0.032; 5 of them.
  CHECK(std::abs(mse / P_end - 1) < 5 * std::sqrt(2.0 / runs));
  CHECK(std::abs(mean) < 5 * std::sqrt(P_end / runs));
}

TEST_CASE("runtime: filter guards stop runs at the time P loses definiteness or m runs away", "[runtime][filters][unit]") {
  const TruthRun truth = quiet_truth(2.0, 0.01);
  REQUIRE(truth.completed_steps == 200);

  // P = 0.5 - t: zero (legal, within round-off) at t = 0.5, negative from t = 0.51. By default
  // the loss is recorded and the run goes on; with stop_on_psd_loss it stops there.
  const FilterModel shrinking = make_filter_model<int>("shrinking", 1, 1, &shrinking_initial, &shrinking_step);
  FilterRun run = run_filter(shrinking, truth);
  REQUIRE(run.psd_loss);
  CHECK(run.psd_loss->t == Approx(0.51).margin(1e-9));
  CHECK(run.psd_loss->check.min_eigenvalue == Approx(-0.01).margin(1e-9));
  CHECK_FALSE(run.stopped);
  CHECK_FALSE(run.divergence);
  CHECK(run.completed_steps == 200);

  FilterGuardOptions stop;
  stop.stop_on_psd_loss = true;
  run = run_filter(shrinking, truth, stop);
  REQUIRE(run.psd_loss);
  CHECK(run.psd_loss->t == Approx(0.51).margin(1e-9));
  CHECK(run.stopped);
  CHECK(run.completed_steps == 51);
  CHECK(run.state.cols() == 52);  // the state that failed is kept: it is finite

  // m = 1 / (1 - t) passes 1e8 just before t = 1 (Euler lags the pole slightly).
  const FilterModel runaway = make_filter_model<int>("runaway", 1, 1, &runaway_initial, &runaway_step);
  run = run_filter(runaway, truth);
  REQUIRE(run.divergence);
  CHECK(run.divergence->kind == DivergenceKind::bound_exceeded);
  CHECK(run.divergence->index == 0);
  CHECK(run.divergence->t > 0.99);
  CHECK(run.divergence->t < 1.2);
  CHECK(run.stopped);
  CHECK(run.state.cols() == static_cast<Eigen::Index>(run.completed_steps + 1));
  CHECK(run.state.allFinite());
  CHECK(run.state.row(0).maxCoeff() <= 1e8);
}

TEST_CASE("runtime: a generated filter plugs in and paper 001's singular P0 is legal at t = 0", "[runtime][filters][unit]") {
  namespace F = pfgen_models::basin_skliar_partial::optimal;
  const FilterModel filter = make_filter_model("optimal", F::n, F::p, &F::initial_state<double>, &F::step<double>);
  REQUIRE(filter.state_size() == F::state_size);

  SdeSystem system;
  system.n = 2;
  system.q = 0;
  system.drift = [](double, const double* x, double* f) {
    f[0] = 0.1 * (x[0] * x[0] + x[1]);
    f[1] = 0.1 * x[1];
  };
  AdaptiveEuler scheme(system);
  Observation observation(Eigen::VectorXd::Zero(1), (Eigen::MatrixXd(1, 2) << 1, 0).finished(),
                                Eigen::MatrixXd::Ones(1, 1));
  Eigen::VectorXd x0(2);
  x0 << 1.1, 1.1;
  const TruthRun truth = simulate_truth(scheme, observation, x0, TimeGrid::to_horizon(0.0, 6.5, 1e-3), 1, 0);
  REQUIRE_FALSE(truth.diverged());

  const FilterRun run = run_filter(filter, truth);
  // P0 = [[1, 1], [1, 1]] is singular: a Cholesky test would have stopped the run at t = 0.
  CHECK(run.state(2, 0) == 1.0);
  CHECK(run.state(3, 0) == 1.0);
  CHECK(run.state(4, 0) == 1.0);
  // Without process noise P keeps rank 1; its least eigenvalue stays 0 up to the integrator's
  // O(dt^2) error, far inside the guard's tolerance.
  double worst = 0;
  const CovarianceGuard exact(0.0, 0.0);
  for (Eigen::Index k = 0; k < run.state.cols(); ++k) {
    const CovarianceCheck c = exact.check_filter_state(run.state.col(k).data(), 2);
    worst = std::min(worst, c.min_eigenvalue / c.max_abs_eigenvalue);
  }
  INFO("least eigenvalue / largest over the run: " << worst << "; PSD loss reported at t = "
                                                    << (run.psd_loss ? run.psd_loss->t : -1.0));
  CHECK(worst > -1e-6);
  CHECK_FALSE(run.psd_loss);
  CHECK_FALSE(run.divergence);
  REQUIRE(run.completed_steps == truth.completed_steps);
  const Eigen::Index last = run.state.cols() - 1;
  INFO("x(6.5) = " << truth.x.col(last).transpose() << ", m(6.5) = " << run.state.col(last).head(2).transpose());
  // The optimal filter tracks the measured x1 closely by t = 6.5.
  CHECK(std::abs(truth.x(0, last) - run.state(0, last)) < 1.0);
}

TEST_CASE("runtime: a moment filter's extra state is refined with m and P, and a margin not positive stops the run",
          "[runtime][filters][unit]") {
  const TruthRun truth = quiet_truth(1.0, 0.01);
  FilterModel filter("moments", 1, 1, &moment_initial,
                     std::make_unique<GridSteps>(&moment_step, FilterStepFunction{}, 0, 1));
  REQUIRE(filter.state_size() == 3);
  // Without margins the run goes to the end, its steps refined.
  FilterRun run = run_filter(filter, truth);
  CHECK_FALSE(run.stopped);
  CHECK(run.refined_steps > 30);  // every grid step while P = exp(-40 t) is above the stepper's floor
  // With the margin: stops at the first grid time where 0.35 - t <= 0 (t = 0.35, or 0.36 after round-off).
  filter.realisability.margins = [](const double* state, double* margins) { margins[0] = state[2]; };
  filter.realisability.names = {"the extra entry"};
  run = run_filter(filter, truth);
  REQUIRE(run.divergence);
  CHECK(run.divergence->kind == DivergenceKind::unrealisable);
  CHECK(run.divergence->t >= 0.35 - 1e-12);
  CHECK(run.divergence->t <= 0.36 + 1e-12);
  CHECK(run.divergence->value <= 1e-12);
  CHECK(run.divergence->value > -0.01 - 1e-12);  // restored on every rejected step: off by at most one grid step
  CHECK(run.stopped);
  CHECK(run.divergence->describe().find("the moments left the realisable set") != std::string::npos);
  CHECK(run.divergence->describe().find("the extra entry") != std::string::npos);
}

TEST_CASE("runtime: a moment filter whose margins pass stops where its P is not a covariance",
          "[runtime][filters][unit]") {
  // Three states with positive variances and positive leading 2 x 2 minor, so margins on those pass, but P is
  // indefinite (its 3 x 3 determinant is negative): the check still stops, naming P's least eigenvalue.
  RealisabilityCheck check;
  check.margins = [](const double* state, double* margins) {
    margins[0] = state[3];
    margins[1] = state[3] * state[6] - state[4] * state[4];
  };
  check.names = {"variance of x1", "P's leading 2 x 2 minor"};
  check.n = 3;
  // m (3), then P's upper triangle row by row: P11 P12 P13 P22 P23 P33.
  const std::vector<double> indefinite = {0, 0, 0, 1, 0.9, 0.9, 1, 0.1, 1};
  std::vector<double> margins;
  const auto event = check_realisability(check, 0.5, indefinite.data(), margins);
  REQUIRE(event);
  CHECK(event->kind == DivergenceKind::unrealisable);
  CHECK(event->what == "P's least eigenvalue");
  CHECK(event->value < -0.1);
  CHECK(event->t == 0.5);
  const std::vector<double> definite = {0, 0, 0, 1, 0.5, 0.2, 1, 0.1, 1};
  CHECK_FALSE(check_realisability(check, 0.5, definite.data(), margins));
  check.n = 0;  // P not checked
  CHECK_FALSE(check_realisability(check, 0.5, indefinite.data(), margins));
}
