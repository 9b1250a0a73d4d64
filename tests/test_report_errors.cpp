// The signed errors at the report times (ReportStatistics::mean_error and the standard errors,
// format_report_errors): what scripts/reproduce-paper004.sh reads to compare mean m = x - mean e
// with paper 004's printed estimates. The summary table itself does not show them.
#include <catch2/catch.hpp>

#include <cmath>
#include <string>
#include <vector>

#include <Eigen/Core>

#include "pfgen_runtime/monte_carlo.hpp"
#include "pfgen_runtime/schemes.hpp"
#include "pfgen_runtime/summary_table.hpp"

using namespace pfgen_runtime;

namespace {

// dx = 0 (x stays 1), dy = x dt + dW2; the "filter" m = y(t) - y(0), so e = x - m = 1 - t - W2(t):
// mean 1 - t, standard deviation sqrt(t).
FilterModel integrating_filter() {
  FilterModel filter;
  filter.name = "integrator";
  filter.n = 1;
  filter.p = 1;
  filter.initial_state = [](double* state) {
    state[0] = 0.0;
    state[1] = 1.0;
  };
  filter.timing = std::make_unique<GridSteps>([](double* state, double, double, const double* dy) { state[0] += dy[0]; });
  return filter;
}

}  // namespace

TEST_CASE("report errors: the signed mean error and the standard errors match the known law", "[montecarlo][runtime][statistical]") {
  SdeSystem system;
  system.n = 1;
  system.q = 0;  // a deterministic truth (rk4): x stays 1
  system.drift = [](double, const double*, double* f) { f[0] = 0.0; };
  RungeKutta4 scheme(system);
  const Observation observation(Eigen::VectorXd::Zero(1), Eigen::MatrixXd::Ones(1, 1), Eigen::MatrixXd::Ones(1, 1));
  MonteCarloOptions options;
  options.grid = TimeGrid::to_horizon(0.0, 4.0, 0.01);
  options.runs = 4000;
  options.seed = 7;
  options.threads = 2;
  options.record_points = 10;
  options.report_times = {1.0, 4.0};
  const MonteCarloResult result =
      run_monte_carlo(scheme, observation, Eigen::VectorXd::Ones(1), {integrating_filter()}, options);
  REQUIRE(result.filters.size() == 1);
  for (const ReportStatistics& report : result.filters[0].reports) {
    const double t = report.t, sd = std::sqrt(t), n = 4000.0;
    INFO("t = " << t << ": mean e " << report.mean_error[0] << " ± " << report.mean_error_se[0] << ", mean |e| "
                << report.mean_abs[0] << " ± " << report.mean_abs_se[0]);
    REQUIRE(report.alive == 4000);
    // The signed mean is 1 - t within 5 standard errors; its standard error is sd / sqrt(n).
    CHECK(std::abs(report.mean_error[0] - (1.0 - t)) < 5 * sd / std::sqrt(n));
    CHECK(report.mean_error_se[0] == Approx(sd / std::sqrt(n)).epsilon(0.05));
    // |e| has variance E e^2 - (E|e|)^2; its standard error is below that of e's second moment.
    const double e2 = (1 - t) * (1 - t) + t;
    CHECK(report.mean_abs_se[0] == Approx(std::sqrt((e2 - report.mean_abs[0] * report.mean_abs[0]) / n)).epsilon(0.05));
    CHECK(report.mean_abs[0] >= std::abs(report.mean_error[0]));
  }
}

TEST_CASE("report errors: one row per filter, state and report time; '-' for what one run cannot give", "[montecarlo][runtime][unit]") {
  MonteCarloResult result;
  result.n = 1;
  FilterStatistics a;
  a.name = "delay-optimal";
  ReportStatistics r1;
  r1.t = 1;
  r1.alive = 200;
  r1.mean_abs = {0.5};
  r1.rms = {0.6};
  r1.mean_error = {-0.25};
  r1.mean_error_se = {0.0123};
  r1.mean_abs_se = {0.01};
  ReportStatistics r2 = r1;
  r2.t = 2;
  r2.alive = 1;
  r2.mean_error_se = {NAN};
  r2.mean_abs_se = {NAN};
  a.reports = {r1, r2};
  result.filters = {a};
  const std::string text = format_report_errors(result, {"x"});
  CHECK(text ==
        "\nErrors at the report times (e = x - m over the runs counted; se: standard error over runs):\n"
        "filter         state  t  runs  mean e     se  mean |e|    se\n"
        "delay-optimal      x  1   200   -0.25  0.012       0.5  0.01\n"
        "delay-optimal      x  2     1   -0.25      -       0.5     -\n");
  CHECK_THROWS_AS(format_report_errors(result, {}), std::invalid_argument);
  result.filters.clear();
  CHECK(format_report_errors(result, {"x"}).empty());
}
