// Guards: non-finite and runaway values stop a run with the right time, P is checked for
// positive semi-definiteness by eigenvalues (singular P0 legal, indefinite P rejected), and the
// deterministic truths of the papers blow up where the mathematics says.
#include <catch2/catch.hpp>

#include <array>
#include <cmath>
#include <limits>

#include "pfgen_runtime/guards.hpp"
#include "pfgen_runtime/simulation.hpp"

using namespace pfgen_runtime;

namespace {

Observation observe_first(std::size_t n) {
  Eigen::MatrixXd A = Eigen::MatrixXd::Zero(1, static_cast<Eigen::Index>(n));
  A(0, 0) = 1;
  return Observation(Eigen::VectorXd::Zero(1), A, Eigen::MatrixXd::Ones(1, 1));
}

// Paper 000's noise-free state x' = 0.1 x^2, exactly 1 / (1/x0 - 0.1 t): infinite at t = 1/0.11.
SdeSystem paper000_noise_free() {
  SdeSystem system;
  system.n = 1;
  system.q = 0;
  system.drift = [](double, const double* x, double* f) { f[0] = 0.1 * x[0] * x[0]; };
  return system;
}

// Paper 001's state (14)-(15): x1' = 0.1 (x1^2 + x2), x2' = 0.1 x2, no process noise (q = 1 with
// g = 0, as the model file gives it).
SdeSystem paper001() {
  SdeSystem system;
  system.n = 2;
  system.q = 1;
  system.drift = [](double, const double* x, double* f) {
    f[0] = 0.1 * (x[0] * x[0] + x[1]);
    f[1] = 0.1 * x[1];
  };
  system.diffusion = [](double, const double*, double* g) { g[0] = g[1] = 0.0; };
  return system;
}

}  // namespace

TEST_CASE("runtime: the divergence guard reports NaN and inf and runaway values", "[runtime][guards][unit]") {
  const DivergenceGuard guard(1e6);
  const double fine[] = {1.0, -1e6, 3.0};
  CHECK_FALSE(guard.check(0.5, fine, 3).has_value());

  const double nan_at_1[] = {1.0, std::numeric_limits<double>::quiet_NaN(), 3.0};
  auto event = guard.check(0.25, nan_at_1, 3);
  REQUIRE(event);
  CHECK(event->kind == DivergenceKind::non_finite);
  CHECK(event->index == 1);
  CHECK(event->t == 0.25);
  CHECK(event->describe().find("t = 0.25") != std::string::npos);

  const double inf_at_0[] = {-std::numeric_limits<double>::infinity(), 0.0};
  event = guard.check(1.0, inf_at_0, 2);
  REQUIRE(event);
  CHECK(event->kind == DivergenceKind::non_finite);
  CHECK(event->index == 0);

  const double runaway[] = {0.0, 0.0, -1.0000001e6};
  event = guard.check(2.0, runaway, 3);
  REQUIRE(event);
  CHECK(event->kind == DivergenceKind::bound_exceeded);
  CHECK(event->index == 2);

  CHECK_THROWS_AS(DivergenceGuard(0.0), std::invalid_argument);
}

TEST_CASE("runtime: a NaN in the truth stops the run at the grid time it appears", "[runtime][guards][unit]") {
  SdeSystem system;
  system.n = 1;
  system.q = 1;
  // The drift turns NaN from t = 0.5 on: the step from t = 0.5 produces it, seen at t = 0.51.
  system.drift = [](double t, const double* x, double* f) {
    f[0] = t >= 0.5 - 1e-12 ? std::numeric_limits<double>::quiet_NaN() : -x[0];
  };
  system.diffusion = [](double, const double*, double* g) { g[0] = 0.1; };
  EulerMaruyama scheme(system);
  Observation observation = observe_first(1);
  const TimeGrid grid = TimeGrid::to_horizon(0.0, 1.0, 0.01);
  const TruthRun run = simulate_truth(scheme, observation, Eigen::VectorXd::Ones(1), grid, 3, 0);
  REQUIRE(run.diverged());
  CHECK(run.divergence->kind == DivergenceKind::non_finite);
  CHECK(run.divergence->t == Approx(0.51).margin(1e-12));
  CHECK(run.completed_steps == 50);
  CHECK(run.x.cols() == 51);
  CHECK(run.dy.cols() == 50);
  CHECK(run.x.allFinite());
  CHECK(run.dy.allFinite());

  // An invalid x0 is reported at t0 and leaves nothing on record.
  const TruthRun bad_start =
      simulate_truth(scheme, observation, Eigen::VectorXd::Constant(1, std::nan("")), grid, 3, 0);
  REQUIRE(bad_start.diverged());
  CHECK(bad_start.divergence->t == 0.0);
  CHECK(bad_start.x.cols() == 0);
}

TEST_CASE("runtime: paper 000's noise-free state blows up at t = 1/0.11", "[runtime][guards][unit]") {
  const double blow_up = 1.0 / 0.11;  // 9.0909...
  Observation observation = observe_first(1);
  const TimeGrid grid = TimeGrid::to_horizon(0.0, 9.2, 1e-4);
  // x exceeds 1e6 at t = 10 (1/1.1 - 1e-6), 1e-5 before the pole.
  for (SchemeKind kind : {SchemeKind::euler_maruyama, SchemeKind::adaptive_euler}) {
    auto scheme = make_scheme(kind, paper000_noise_free());
    const TruthRun run =
        simulate_truth(*scheme, observation, Eigen::VectorXd::Constant(1, 1.1), grid, 1, 0, DivergenceGuard(1e6));
    REQUIRE(run.diverged());
    INFO(to_string(kind) << ": stopped at t = " << run.divergence->t << ", pole at " << blow_up);
    // Euler-Maruyama passes the bound between grid points; the adaptive substeps follow the pole
    // within one grid step, to inf.
    if (kind == SchemeKind::euler_maruyama) CHECK(run.divergence->kind == DivergenceKind::bound_exceeded);
    CHECK(run.divergence->t > blow_up - 2e-3);  // Euler lags a convex solution: it cannot be early
    CHECK(run.divergence->t < blow_up + (kind == SchemeKind::adaptive_euler ? 2e-3 : 2e-2));
    // Before the guard fired the path followed the exact solution.
    const double t = grid.time(50000);  // t = 5
    CHECK(run.x(0, 50000) == Approx(1.0 / (1.0 / 1.1 - 0.1 * t)).epsilon(1e-3));
  }
}

TEST_CASE("runtime: paper 001's truth x2 = 1.1 e^{0.1 t} and x1 blows up near t = 7.01", "[runtime][guards][unit]") {
  Observation observation = observe_first(2);
  const TimeGrid grid = TimeGrid::to_horizon(0.0, 8.0, 1e-4);
  Eigen::VectorXd x0(2);
  x0 << 1.1, 1.1;
  AdaptiveEuler scheme(paper001());
  const TruthRun run = simulate_truth(scheme, observation, x0, grid, 1, 0, DivergenceGuard(1e6));
  REQUIRE(run.diverged());
  auto at = [&](double t) { return run.x.col(static_cast<Eigen::Index>(std::llround(t / grid.dt))); };
  // The figures: x2 = 1.81, 2.00, 2.11 at T = 5, 6, 6.5; x1 = 4.85 and 9.83 at T = 5, 6.
  CHECK(at(5.0)[1] == Approx(1.1 * std::exp(0.5)).epsilon(1e-4));
  CHECK(std::round(at(5.0)[1] * 100) / 100 == Approx(1.81));
  CHECK(std::round(at(6.0)[1] * 100) / 100 == Approx(2.00));
  CHECK(std::round(at(6.5)[1] * 100) / 100 == Approx(2.11));
  INFO("x1(5) = " << at(5.0)[0] << ", x1(6) = " << at(6.0)[0] << ", x1(6.5) = " << at(6.5)[0] << ", stopped at t = "
                  << run.divergence->t);
  CHECK(at(5.0)[0] == Approx(4.85).margin(0.01));
  CHECK(at(6.0)[0] == Approx(9.83).margin(0.02));
  CHECK(run.divergence->t == Approx(7.01).margin(0.01));
  CHECK(run.divergence->index == 0);
}

TEST_CASE("runtime: the covariance guard accepts singular PSD P and rejects indefinite P", "[runtime][guards][unit]") {
  const CovarianceGuard guard;

  // Paper 001's P0: all ones, eigenvalues 0 and 2. Packed filter state [m1, m2, P11, P12, P22].
  const double paper001_state[] = {0.1, 0.1, 1.0, 1.0, 1.0};
  CovarianceCheck check = guard.check_filter_state(paper001_state, 2);
  INFO(check.describe());
  CHECK(check.ok);
  CHECK(std::abs(check.min_eigenvalue) < 1e-12);

  // The same through the general (eigen-solver) path: a singular 3 x 3 all-ones P, rank 1.
  const double all_ones3[] = {0, 0, 0, 1, 1, 1, 1, 1, 1};
  CHECK(guard.check_filter_state(all_ones3, 3).ok);
  CHECK(guard.check_matrix(Eigen::MatrixXd::Ones(4, 4)).ok);

  // Indefinite: [[1, 2], [2, 1]] has eigenvalues -1 and 3.
  const double indefinite[] = {0.0, 0.0, 1.0, 2.0, 1.0};
  check = guard.check_filter_state(indefinite, 2);
  CHECK_FALSE(check.ok);
  CHECK(check.min_eigenvalue == Approx(-1.0));
  CHECK(check.describe().find("not positive semi-definite") != std::string::npos);
  Eigen::Matrix3d indefinite3;
  indefinite3 << 2, 0, 0, 0, 1, 0, 0, 0, -0.01;  // -0.5 % of the largest eigenvalue
  CHECK_FALSE(guard.check_matrix(indefinite3).ok);
  CHECK_FALSE(guard.check_filter_state(std::array<double, 9>{0, 0, 0, 2, 0, 0, 1, 0, -0.01}.data(), 3).ok);

  // Round-off below the tolerance passes; a real negative eigenvalue does not.
  const double tiny_negative[] = {0.0, -1e-14};
  CHECK(guard.check_filter_state(tiny_negative, 1).ok);
  const double negative[] = {0.0, -1e-6};
  CHECK_FALSE(guard.check_filter_state(negative, 1).ok);
  Eigen::Matrix2d nearly_singular;
  nearly_singular << 1, 1 + 1e-7, 1 + 1e-7, 1;  // least eigenvalue -1e-7, inside the 2e-4 tolerance
  CHECK(guard.check_matrix(nearly_singular).ok);
  CHECK_FALSE(CovarianceGuard(1e-9, 1e-12).check_matrix(nearly_singular).ok);  // a stricter guard

  // Non-finite entries and asymmetric full matrices fail.
  const double with_nan[] = {0.0, 0.0, 1.0, std::nan(""), 1.0};
  CHECK_FALSE(guard.check_filter_state(with_nan, 2).ok);
  CHECK_FALSE(guard.check_filter_state(with_nan, 2).finite);
  Eigen::Matrix2d asymmetric;
  asymmetric << 1, 0.5, 0.4, 1;
  CHECK_FALSE(guard.check_matrix(asymmetric).ok);

  // Packing round trip in the generated layout.
  Eigen::Matrix3d P;
  P << 4, 1, 2, 1, 5, 3, 2, 3, 6;
  const Eigen::VectorXd packed = pack_upper(P);
  CHECK(packed.size() == 6);
  CHECK(packed[0] == 4);
  CHECK(packed[1] == 1);
  CHECK(packed[2] == 2);
  CHECK(packed[3] == 5);
  CHECK(packed[4] == 3);
  CHECK(packed[5] == 6);
  CHECK(unpack_symmetric(packed.data(), 3) == Eigen::MatrixXd(P));
}

TEST_CASE("a state-dependent diffusion covariance that loses definiteness stops the truth, reported at that time",
          "[runtime][guards][unit]") {
  // dx = (2 - x) dt with G = 1 - x: x heads for 2, and G < 0 once x > 1.
  SdeSystem system;
  system.n = system.q = 1;
  system.drift = [](double, const double* x, double* f) { f[0] = 2 - x[0]; };
  system.diffusion = diffusion_from_covariance(1, [](double, const double* x, double* G) { G[0] = 1 - x[0]; });
  double g = 0;
  const double inside = 0.75, outside = 1.01;
  system.diffusion(0, &inside, &g);
  CHECK(g == Approx(0.5));
  // Zero is semi-definite; round-off relative to the largest eigenvalue passes too.
  const double one = 1;
  CHECK_NOTHROW(system.diffusion(0, &one, &g));
  CHECK(g == 0);
  auto two_by_two = diffusion_from_covariance(2, [](double, const double*, double* G) {
    G[0] = 1;
    G[1] = G[2] = 0;
    G[3] = -1e-12;  // -1e-12 of the largest eigenvalue 1: round-off
  });
  double g2[4];
  CHECK_NOTHROW(two_by_two(0, &one, g2));
  try {
    system.diffusion(0.5, &outside, &g);
    FAIL("G = -0.01 was taken");
  } catch (const CovarianceIndefinite& e) {
    CHECK(e.t == 0.5);
    CHECK(e.eigenvalue == Approx(-0.01));
  }

  EulerMaruyama scheme(system);
  Observation observation = observe_first(1);
  const TimeGrid grid = TimeGrid::to_horizon(0, 5, 0.01);
  const TruthRun run = simulate_truth(scheme, observation, Eigen::VectorXd::Zero(1), grid, 7, 0);
  REQUIRE(run.diverged());
  CHECK(run.divergence->kind == DivergenceKind::covariance_indefinite);
  CHECK(run.divergence->value < 0);
  CHECK(run.divergence->describe().find("the diffusion covariance G is not positive semi-definite at t = ") == 0);
  // Euler-Maruyama reads G at the start of each step: the last stored state is the first with
  // x > 1, every earlier one had G >= 0, and the step from it is where the run stopped.
  REQUIRE(run.completed_steps < grid.steps);
  const Eigen::Index last = static_cast<Eigen::Index>(run.completed_steps);
  CHECK(run.x(0, last) > 1.0);
  CHECK(run.x.leftCols(last).maxCoeff() <= 1.0);
  CHECK(run.divergence->t == Approx(grid.time(run.completed_steps)));
}
