// Paper 000's Ito state dx = 0.1 x^2 dt + 0.1 x^2 dW from x0 = 1.1 to T = 9.2 (docs/theory.md §5).
// It does not blow up: z = 10/x obeys dz = (1/z - 1) dt - dW, a Bessel-3-like process that never
// reaches 0. Fixed-step Euler-Maruyama nevertheless overflows on some paths (Hutzenthaler-
// Jentzen-Kloeden), the increment-tamed scheme stays finite but its law is visibly off, and the
// adaptive scheme's law of x(9.2) agrees with an independent simulation of z.
#include <catch2/catch.hpp>

#include <cmath>
#include <vector>

#include "pfgen_runtime/random.hpp"
#include "pfgen_runtime/simulation.hpp"
#include "pfgen_runtime/statistics.hpp"

using namespace pfgen_runtime;

namespace {

constexpr double T = 9.2;
constexpr double x0_value = 1.1;

SdeSystem paper000_ito() {
  SdeSystem system;
  system.n = 1;
  system.q = 1;
  system.drift = [](double, const double* x, double* f) { f[0] = 0.1 * x[0] * x[0]; };
  system.diffusion = [](double, const double* x, double* g) { g[0] = 0.1 * x[0] * x[0]; };
  system.diffusion_jacobian = [](double, const double* x, double* dg) { dg[0] = 0.2 * x[0]; };
  return system;
}

struct Sample {
  std::vector<double> final_x;  // x(T) of the runs that did not diverge
  int diverged = 0;
  int negative = 0;  // x(T) < 0: impossible for the true process
};

// Runs through simulate_truth, observation dy = x dt + dW2 included, guard bound 1e8.
Sample simulate_x(SchemeKind kind, double dt, int runs, std::uint64_t seed) {
  auto scheme = make_scheme(kind, paper000_ito());
  Observation observation(Eigen::VectorXd::Zero(1), Eigen::MatrixXd::Ones(1, 1), Eigen::MatrixXd::Ones(1, 1));
  const TimeGrid grid = TimeGrid::to_horizon(0.0, T, dt);
  const Eigen::VectorXd x0 = Eigen::VectorXd::Constant(1, x0_value);
  Sample sample;
  for (int run = 0; run < runs; ++run) {
    const TruthRun truth = simulate_truth(*scheme, observation, x0, grid, seed, static_cast<std::uint64_t>(run),
                                          DivergenceGuard(1e8));
    if (truth.diverged()) {
      ++sample.diverged;
      continue;
    }
    const double x = truth.x(0, truth.x.cols() - 1);
    sample.final_x.push_back(x);
    if (x < 0) ++sample.negative;
  }
  return sample;
}

// The independent simulation: z = 10/x by the drift-implicit Euler scheme
// z_new = z + (1/z_new - 1) dt - dW, i.e. z_new = (b + sqrt(b^2 + 4 dt)) / 2 with b = z - dt - dW,
// which keeps z > 0 (as for Bessel processes). Its own streams (seed 77) share nothing with the
// x runs.
std::vector<double> simulate_via_z(double dt, int runs) {
  const long steps = std::lround(T / dt);
  const double root_dt = std::sqrt(dt);
  std::vector<double> x;
  for (int run = 0; run < runs; ++run) {
    RandomStream stream(77, static_cast<std::uint64_t>(run));
    double z = 10.0 / x0_value;
    for (long k = 0; k < steps; ++k) {
      const double b = z - dt - root_dt * stream.normal();
      z = 0.5 * (b + std::sqrt(b * b + 4.0 * dt));
    }
    x.push_back(10.0 / z);
  }
  return x;
}

}  // namespace

TEST_CASE("runtime: paper 000's Ito state makes fixed-step Euler overflow but not tamed or adaptive Euler", "[runtime][superlinear][statistical]") {
  const int runs = 2000;
  const Sample em = simulate_x(SchemeKind::euler_maruyama, 1e-3, runs, 5);
  const Sample tamed = simulate_x(SchemeKind::tamed_euler, 1e-3, runs, 5);
  const Sample adaptive = simulate_x(SchemeKind::adaptive_euler, 1e-3, runs, 5);
  INFO("diverged (|x| > 1e8 or non-finite) of " << runs << ": euler-maruyama " << em.diverged << ", tamed "
                                                << tamed.diverged << ", adaptive " << adaptive.diverged
                                                << "; negative x(T): " << em.negative << ", " << tamed.negative
                                                << ", " << adaptive.negative);
  // The true process reaches 1e8 with probability ~1e-7 per path: Euler-Maruyama's ~2.5 % of
  // overflowing paths are spurious.
  CHECK(em.diverged >= 10);
  CHECK(tamed.diverged == 0);
  CHECK(adaptive.diverged == 0);
  // x never changes sign; the adaptive substeps keep it so.
  CHECK(adaptive.negative == 0);
}

TEST_CASE("runtime: adaptive Euler's law of x(9.2) agrees with the simulation of z = 10/x", "[runtime][superlinear][statistical]") {
  // Two-sample Kolmogorov-Smirnov tests at level alpha = 0.001. The reference: 10000 runs of z.
  const std::vector<double> reference = simulate_via_z(1e-3, 10000);
  const double reference_median = quantile(reference, 0.5);

  // The grid is coarse (dt = 0.01: 920 observation steps); the adaptive substeps carry the
  // accuracy. 10000 runs resolve a KS distance of ~0.03.
  const Sample coarse = simulate_x(SchemeKind::adaptive_euler, 1e-2, 10000, 6);
  REQUIRE(coarse.diverged == 0);
  const KolmogorovSmirnovResult coarse_test = ks_two_sample(coarse.final_x, reference);
  // And on a finer grid, fewer runs.
  const Sample fine = simulate_x(SchemeKind::adaptive_euler, 1e-3, 1000, 7);
  REQUIRE(fine.diverged == 0);
  const KolmogorovSmirnovResult fine_test = ks_two_sample(fine.final_x, reference);

  // The first 400 runs alone: their median x(9.2), 4.57 (docs/theory.md §5), near the z median.
  const std::vector<double> first400(coarse.final_x.begin(), coarse.final_x.begin() + 400);
  const double median400 = quantile(first400, 0.5), median = quantile(coarse.final_x, 0.5);
  INFO("z reference median " << reference_median << "; adaptive (dt 0.01) median " << median << ", first 400 runs "
                             << median400 << ", quantiles 5/95 % " << quantile(coarse.final_x, 0.05) << " / "
                             << quantile(coarse.final_x, 0.95) << " against " << quantile(reference, 0.05) << " / "
                             << quantile(reference, 0.95));
  INFO("KS dt 0.01: D = " << coarse_test.statistic << ", p = " << coarse_test.p_value << "; dt 0.001: D = "
                          << fine_test.statistic << ", p = " << fine_test.p_value);
  CHECK(coarse_test.p_value > 0.001);
  CHECK(fine_test.p_value > 0.001);
  CHECK(reference_median > 4.2);
  CHECK(reference_median < 4.8);
  CHECK(median400 > 3.9);
  CHECK(median400 < 5.0);
  CHECK(std::abs(median - reference_median) < 0.2);

  // The same test has the power to see a wrong law: the increment-tamed scheme at dt = 1e-3
  // (stays finite, but ~3 % of its paths overshoot to x < 0) is rejected.
  const Sample tamed = simulate_x(SchemeKind::tamed_euler, 1e-3, 6000, 8);
  const KolmogorovSmirnovResult tamed_test = ks_two_sample(tamed.final_x, reference);
  INFO("tamed dt 0.001: D = " << tamed_test.statistic << ", p = " << tamed_test.p_value << ", negative x(T) "
                              << tamed.negative);
  CHECK(tamed.negative > 0);
  CHECK(tamed_test.p_value < 0.001);
}

TEST_CASE("runtime: quantiles and the two-sample Kolmogorov-Smirnov test", "[runtime][superlinear][unit]") {
  CHECK(quantile({4, 1, 3, 2}, 0.5) == 2.5);
  CHECK(quantile({4, 1, 3, 2}, 0.0) == 1.0);
  CHECK(quantile({4, 1, 3, 2}, 1.0) == 4.0);
  CHECK(quantile({10, 20}, 0.25) == 12.5);
  CHECK_THROWS_AS(quantile({}, 0.5), std::invalid_argument);
  CHECK_THROWS_AS(quantile({1, std::nan("")}, 0.5), std::invalid_argument);

  const KolmogorovSmirnovResult same = ks_two_sample({1, 2, 3, 4, 5}, {1, 2, 3, 4, 5});
  CHECK(same.statistic == 0.0);
  CHECK(same.p_value == 1.0);
  std::vector<double> low, high;
  for (int i = 0; i < 50; ++i) {
    low.push_back(i);
    high.push_back(100 + i);
  }
  const KolmogorovSmirnovResult apart = ks_two_sample(low, high);
  CHECK(apart.statistic == 1.0);
  CHECK(apart.p_value < 1e-10);
  // The Kolmogorov tail at its textbook points: Q(1.3581) = 0.05, Q(1.6276) = 0.01.
  CHECK(kolmogorov_tail(1.3581) == Approx(0.05).margin(1e-4));
  CHECK(kolmogorov_tail(1.6276) == Approx(0.01).margin(1e-4));
  // Two samples of one law: uniform draws from different streams.
  std::vector<double> a, b;
  RandomStream sa(3, 0), sb(3, 1);
  for (int i = 0; i < 2000; ++i) {
    a.push_back(sa.uniform());
    b.push_back(sb.uniform());
  }
  CHECK(ks_two_sample(a, b).p_value > 0.001);
  // And a shifted one is told apart.
  for (double& v : b) v += 0.1;
  CHECK(ks_two_sample(a, b).p_value < 1e-6);
}

TEST_CASE("runtime: adaptive Euler stops a grid step short when it would need more substeps than allowed",
          "[runtime][superlinear][unit]") {
  // Paper 000's state; a grid step of 50 from x = 1.1 crosses the noise-free blow-up at t = 9.09.
  pfgen_runtime::SdeSystem system;
  system.n = 1;
  system.q = 1;
  system.drift = [](double, const double* x, double* f) { f[0] = 0.1 * x[0] * x[0]; };
  system.diffusion = [](double, const double* x, double* g) { g[0] = 0.1 * x[0] * x[0]; };
  pfgen_runtime::AdaptiveEuler::Options options;
  options.max_substeps = 1000;
  pfgen_runtime::AdaptiveEuler scheme(system, options);
  scheme.start_run(1, 0);
  Eigen::VectorXd x(1), dW(1);
  x << 1.1;
  dW << 0.0;
  scheme.step(0.0, x, 50.0, dW);
  CHECK(scheme.last_step_incomplete());
  CHECK(scheme.substeps() <= options.max_substeps);
  // An ordinary step is complete, and the next step starts a new budget.
  x << 1.1;
  scheme.step(0.0, x, 1e-3, dW);
  CHECK_FALSE(scheme.last_step_incomplete());
}
