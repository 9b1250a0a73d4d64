// The Monte Carlo engine with sampled observations (run_monte_carlo with a Observation):
// sample times exact, every period gets exactly `substeps` predictions at the right times
// whatever the grid, the samples are C0 + C x(t_k) + Uv v_k from the run's observation stream,
// results are the same for any thread count, and the metrics of paper 003 are the defined ones.
#include <catch2/catch.hpp>

#include <cmath>
#include <mutex>
#include <vector>

#include <Eigen/Core>

#include "pfgen_runtime/monte_carlo.hpp"
#include "pfgen_runtime/random.hpp"
#include "pfgen_runtime/schemes.hpp"
#include "pfgen_runtime/simulation.hpp"
#include "pfgen_runtime/summary_table.hpp"

using namespace pfgen_runtime;

namespace {

// dx = 0 (x stays at x0 = 2): samples y_k = 1 + 3 x + 0.5 v_k.
SdeSystem constant_system() {
  SdeSystem system;
  system.n = 1;
  system.q = 0;
  system.drift = [](double, const double*, double* f) { f[0] = 0.0; };
  return system;
}

Observation measurement(double period) {
  return Observation::sampled(1, 1, 1, period, [](double, double* C0, double* C, double* Uv) {
    C0[0] = 1.0;
    C[0] = 3.0;
    Uv[0] = 0.5;
  });
}

struct Log {
  std::mutex mutex;
  std::vector<std::pair<double, double>> predictions;  // (t, dt)
  std::vector<double> update_times, samples;
};

// m stays 2 (so Yhat = 7 exactly), P is untouched; every call is logged.
FilterModel logging_filter(Log& log, std::size_t substeps) {
  FilterModel filter;
  filter.name = "log";
  filter.n = 1;
  filter.p = 1;
  filter.initial_state = [](double* state) {
    state[0] = 2.0;
    state[1] = 1.0;
  };
  filter.timing = std::make_unique<SampledSteps>(
      substeps,
      [&log](double*, double t, double dt) {
        std::lock_guard<std::mutex> lock(log.mutex);
        log.predictions.push_back({t, dt});
      },
      [&log](double*, double t, const double* y) {
        std::lock_guard<std::mutex> lock(log.mutex);
        log.update_times.push_back(t);
        log.samples.push_back(y[0]);
        return true;
      });
  return filter;
}

}  // namespace

TEST_CASE("sampled Monte Carlo: exact sample times, substeps predictions per period on any grid, samples from the observation stream", "[runtime][sampled][unit]") {
  const SdeSystem system = constant_system();
  const auto scheme = make_scheme(SchemeKind::euler_maruyama, system);
  // T = 0.7, dt = 0.1: N = 7 grid steps per period, 3 predictions of 0.7/3 each (3 does not divide 7).
  Log log;
  MonteCarloOptions options;
  options.grid = TimeGrid::to_horizon(0.0, 7.0, 0.1);
  options.runs = 1;
  options.seed = 5;
  const MonteCarloResult result = run_monte_carlo(*scheme, measurement(0.7), Eigen::VectorXd::Constant(1, 2.0),
                                                  {logging_filter(log, 3)}, options);
  REQUIRE(log.update_times.size() == 10);
  REQUIRE(log.predictions.size() == 30);
  RandomStream noise(5, 0, substream::observation_noise);
  for (std::size_t k = 0; k < 10; ++k) {
    CHECK(log.update_times[k] == static_cast<double>(k + 1) * 0.7);  // t_k = k T, not a sum of dt
    CHECK(log.samples[k] == 1.0 + 3.0 * 2.0 + 0.5 * noise.normal());  // the run's stream, in order
    for (std::size_t u = 0; u < 3; ++u) {
      CHECK(log.predictions[3 * k + u].first == static_cast<double>(k) * 0.7 + static_cast<double>(u) * (0.7 / 3));
      CHECK(log.predictions[3 * k + u].second == 0.7 / 3);
    }
  }
  // Yhat = 7 = the noise-free value: AvRMSE clean 0; noisy: the RMS of 0.5 v_k.
  REQUIRE(result.filters.front().sampled);
  const SampledMetrics& m = *result.filters.front().sampled;
  CHECK(m.runs == 1);
  CHECK(m.samples == 10);
  CHECK(m.rmse_clean[0] == 0.0);
  double squares = 0, relative = 0;
  for (double y : log.samples) {
    squares += (y - 7.0) * (y - 7.0);
    relative += std::abs(y - 7.0) / std::abs(y);
  }
  CHECK(m.rmse_noisy[0] == Approx(std::sqrt(squares / 10)).epsilon(1e-12));
  CHECK(m.mrae_noisy[0] == Approx(relative / 10).epsilon(1e-12));
  CHECK(format_summary_table(result, {"x"}).find("AvRMSE clean") != std::string::npos);
}

TEST_CASE("sampled Monte Carlo: a period that is not a whole number of steps is refused", "[runtime][sampled][unit]") {
  const auto scheme = make_scheme(SchemeKind::euler_maruyama, constant_system());
  Log log;
  MonteCarloOptions options;
  options.grid = TimeGrid::to_horizon(0.0, 3.0, 0.3);
  options.runs = 1;
  CHECK_THROWS_WITH(run_monte_carlo(*scheme, measurement(1.0), Eigen::VectorXd::Constant(1, 2.0),
                                    {logging_filter(log, 1)}, options),
                    Catch::Contains("not a whole number of steps"));
}

TEST_CASE("sampled Monte Carlo: bitwise the same for 1 and 3 threads", "[runtime][sampled][unit]") {
  SdeSystem system;
  system.n = 1;
  system.q = 1;
  system.drift = [](double, const double* x, double* f) { f[0] = -0.5 * x[0]; };
  system.diffusion = [](double, const double*, double* g) { g[0] = 1.0; };
  const auto scheme = make_scheme(SchemeKind::euler_maruyama, system);
  // A scalar Kalman filter of dx = -x/2 dt + dW, exact prediction.
  FilterModel kalman;
  kalman.name = "kalman";
  kalman.n = kalman.p = 1;
  kalman.initial_state = [](double* s) {
    s[0] = 0.0;
    s[1] = 1.0;
  };
  kalman.timing = std::make_unique<SampledSteps>(
      2,
      [](double* s, double, double dt) {
        const double e = std::exp(-0.5 * dt);
        s[0] *= e;
        s[1] = e * e * s[1] + (1 - e * e);
      },
      [](double* s, double, const double* y) {
        const double S = 9 * s[1] + 0.25, K = 3 * s[1] / S;
        s[0] += K * (y[0] - 1 - 3 * s[0]);
        s[1] = (1 - 3 * K) * (1 - 3 * K) * s[1] + K * K * 0.25;
        return true;
      });
  auto run = [&](unsigned threads) {
    MonteCarloOptions options;
    options.grid = TimeGrid::to_horizon(0.0, 20.0, 0.05);
    options.runs = 7;
    options.threads = threads;
    options.report_times = {10.0};
    return run_monte_carlo(*scheme, measurement(1.0), Eigen::VectorXd::Constant(1, 1.0), {kalman}, options);
  };
  const MonteCarloResult one = run(1), three = run(3);
  CHECK(format_summary_table(one, {"x"}) == format_summary_table(three, {"x"}));
  CHECK(one.filters[0].sampled->rmse_noisy == three.filters[0].sampled->rmse_noisy);
  CHECK(one.filters[0].horizon.rms == three.filters[0].horizon.rms);
}

TEST_CASE("sampled Monte Carlo: an update with S not positive definite stops the run, counted as diverged", "[runtime][sampled][unit]") {
  const auto scheme = make_scheme(SchemeKind::euler_maruyama, constant_system());
  Log log;
  FilterModel filter = logging_filter(log, 2);
  // The third update fails (as a generated update() does when S is not positive definite).
  filter.timing = std::make_unique<SampledSteps>(
      2, [](double*, double, double) {}, [count = 0](double*, double, const double*) mutable { return ++count < 3; });
  MonteCarloOptions options;
  options.grid = TimeGrid::to_horizon(0.0, 10.0, 0.5);
  options.runs = 1;
  const MonteCarloResult result =
      run_monte_carlo(*scheme, measurement(1.0), Eigen::VectorXd::Constant(1, 2.0), {filter}, options);
  const FilterStatistics& stats = result.filters.front();
  REQUIRE(stats.divergences.count() == 1);
  CHECK(stats.divergences.earliest() == 3.0);  // at t_3
  REQUIRE(stats.sampled);
  CHECK(stats.sampled->update_failures == 1);
  CHECK(stats.sampled->runs == 0);  // the run did not absorb every sample
  const std::string table = format_summary_table(result, {"x"});
  CHECK(table.find("Runs stopped by an update whose C P C^T + Uv Uv^T was not positive definite") != std::string::npos);
  CHECK(table.find("nan") == std::string::npos);
}

TEST_CASE("sampled Monte Carlo: paired differences against the first filter are per-run differences", "[runtime][sampled][unit]") {
  const auto scheme = make_scheme(SchemeKind::euler_maruyama, constant_system());
  Log log_a, log_b;
  // Filter a keeps m = 2 (Yhat = 7 = the noise-free value); filter b keeps m = 2.5 (Yhat = 8.5):
  // per run and sample the clean errors are 0 and -1.5, so the paired dRMSE clean is exactly 1.5
  // with no spread, and dAvRMSE noisy is the mean over runs of RMSE_b(s) - RMSE_a(s).
  FilterModel a = logging_filter(log_a, 1), b = logging_filter(log_b, 1);
  a.name = "a";
  b.name = "b";
  b.initial_state = [](double* state) {
    state[0] = 2.5;
    state[1] = 1.0;
  };
  MonteCarloOptions options;
  options.grid = TimeGrid::to_horizon(0.0, 10.0, 1.0);
  options.runs = 5;
  const MonteCarloResult result =
      run_monte_carlo(*scheme, measurement(1.0), Eigen::VectorXd::Constant(1, 2.0), {a, b}, options);
  const SampledMetrics& first = *result.filters[0].sampled;
  const SampledMetrics& second = *result.filters[1].sampled;
  CHECK(first.diff_rmse_clean.empty());
  REQUIRE(second.paired_runs == 5);
  CHECK(second.diff_rmse_clean[0] == Approx(1.5).epsilon(1e-12));
  CHECK(second.diff_rmse_clean_se[0] == Approx(0.0).margin(1e-12));
  CHECK(second.diff_rmse_noisy[0] == Approx(second.rmse_noisy[0] - first.rmse_noisy[0]).epsilon(1e-12));
  CHECK(format_summary_table(result, {"x"}).find("Paired against a") != std::string::npos);
}
