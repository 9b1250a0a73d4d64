// The continuous and delayed summary's standard errors and paired differences (runtime aggregate,
// summary_table's precision section): the delta-method standard error of an RMS and the paired
// standard error of a difference of mean squares match their spread over independent seeds; the
// paired difference is the difference of the mean squares where every run completes, 0 ± 0 for a
// filter against itself; the table shows both.
#include <catch2/catch.hpp>

#include <cmath>
#include <string>
#include <vector>

#include "pfgen_runtime/monte_carlo.hpp"
#include "pfgen_runtime/summary_table.hpp"
#include "support/scalar_linear_system.hpp"

using namespace pfgen_runtime;
using pfgen_test::ScalarLinear;
using pfgen_test::scalar_linear_system;
using pfgen_test::scalar_observation;

namespace {

// Kalman-Bucy for ScalarLinear with its gain scaled by `gain` (1: the optimal filter).
FilterModel scaled_gain_filter(const ScalarLinear& model, const std::string& name, double gain) {
  FilterModel filter;
  filter.name = name;
  filter.n = 1;
  filter.p = 1;
  filter.initial_state = [model](double* state) {
    state[0] = model.m0;
    state[1] = model.P0;
  };
  filter.timing = std::make_unique<GridSteps>([model, gain](double* state, double, double dt, const double* dy) {
    const double m = state[0], P = state[1];
    const double K = gain * P / (model.r * model.r);
    state[0] = m - model.a * m * dt + K * (dy[0] - m * dt);
    state[1] = P + (-2 * model.a * P + model.s * model.s - P * P / (model.r * model.r)) * dt;
  });
  return filter;
}

MonteCarloResult run(std::uint64_t seed, std::size_t runs, const std::vector<FilterModel>& filters) {
  const ScalarLinear model;
  const auto scheme = make_scheme(SchemeKind::euler_maruyama, scalar_linear_system(model));
  MonteCarloOptions options;
  options.grid = TimeGrid::to_horizon(0.0, 2.0, 0.01);
  options.runs = runs;
  options.seed = seed;
  options.record_points = 10;
  options.windows = {{0.0, 1.0}};
  options.report_times = {1.5};
  return run_monte_carlo(*scheme, scalar_observation(model.r), Eigen::VectorXd::Constant(1, 0.3), filters, options);
}

double spread(const std::vector<double>& values) {
  double mean = 0, squares = 0;
  for (double v : values) mean += v / static_cast<double>(values.size());
  for (double v : values) squares += (v - mean) * (v - mean);
  return std::sqrt(squares / static_cast<double>(values.size() - 1));
}

double average(const std::vector<double>& values) {
  double mean = 0;
  for (double v : values) mean += v / static_cast<double>(values.size());
  return mean;
}

}  // namespace

TEST_CASE("summary precision: a filter against itself differs by 0 ± 0; the difference is that of the mean squares",
          "[summary][runtime][unit]") {
  const ScalarLinear model;
  const MonteCarloResult result = run(3, 50,
                                      {scaled_gain_filter(model, "kb", 1.0), scaled_gain_filter(model, "kb-again", 1.0),
                                       scaled_gain_filter(model, "detuned", 0.5)});
  const FilterStatistics &first = result.filters[0], &again = result.filters[1], &detuned = result.filters[2];
  CHECK(first.horizon.paired_difference.empty());
  CHECK(first.reports.front().paired_abs_difference.empty());
  REQUIRE(again.horizon.paired_difference.size() == 1);
  CHECK(again.horizon.paired_runs == 50);
  CHECK(again.horizon.paired_difference[0] == 0.0);
  CHECK(again.horizon.paired_difference_se[0] == 0.0);
  CHECK(again.reports.front().paired_abs_difference[0] == 0.0);
  CHECK(again.horizon.rms_se[0] == first.horizon.rms_se[0]);
  // Every run completes: the mean of the differences is the difference of the means.
  const double squares = detuned.horizon.rms[0] * detuned.horizon.rms[0] - first.horizon.rms[0] * first.horizon.rms[0];
  CHECK(detuned.horizon.paired_difference[0] == Approx(squares).epsilon(1e-10));
  const double window = detuned.windows[0].rms[0] * detuned.windows[0].rms[0] - first.windows[0].rms[0] * first.windows[0].rms[0];
  CHECK(detuned.windows[0].paired_difference[0] == Approx(window).epsilon(1e-10));
  CHECK(detuned.reports[0].paired_abs_difference[0] ==
        Approx(detuned.reports[0].mean_abs[0] - first.reports[0].mean_abs[0]).epsilon(1e-10));
  CHECK(detuned.horizon.paired_difference_se[0] > 0);
  const std::string table = format_summary_table(result, {"x"});
  CHECK(table.find("With standard errors over the runs counted") != std::string::npos);
  CHECK(table.find("Paired against kb run by run") != std::string::npos);
  const std::size_t paired = table.find("Paired against kb run by run");
  REQUIRE(paired != std::string::npos);
  const std::size_t line = table.find("\nkb-again ", paired);
  REQUIRE(line != std::string::npos);
  // The horizon, the window and the report time: three cells of +0 ± 0.
  const std::string row = table.substr(line + 1, table.find('\n', line + 1) - line - 1);
  INFO(row);
  std::size_t zeros = 0;
  for (std::size_t at = row.find("+0 ± 0"); at != std::string::npos; at = row.find("+0 ± 0", at + 1)) ++zeros;
  CHECK(zeros == 3);
}

TEST_CASE("summary precision: the standard errors of an RMS and of a paired difference match their spread over seeds",
          "[summary][runtime][statistical]") {
  // 80 seeds of 100 runs: a standard deviation from 80 samples is known to about 8 %.
  const ScalarLinear model;
  const std::vector<FilterModel> filters{scaled_gain_filter(model, "kb", 1.0), scaled_gain_filter(model, "detuned", 0.6)};
  std::vector<double> rms, rms_se, difference, difference_se;
  for (std::uint64_t seed = 1; seed <= 80; ++seed) {
    const MonteCarloResult result = run(500 + seed, 100, filters);
    rms.push_back(result.filters[0].horizon.rms[0]);
    rms_se.push_back(result.filters[0].horizon.rms_se[0]);
    difference.push_back(result.filters[1].horizon.paired_difference[0]);
    difference_se.push_back(result.filters[1].horizon.paired_difference_se[0]);
  }
  const double rms_ratio = spread(rms) / average(rms_se), difference_ratio = spread(difference) / average(difference_se);
  INFO("spread / mean standard error: RMS " << rms_ratio << ", paired difference " << difference_ratio);
  CHECK(rms_ratio > 0.7);
  CHECK(rms_ratio < 1.4);
  CHECK(difference_ratio > 0.7);
  CHECK(difference_ratio < 1.4);
  // Pairing removes the spread the runs share: the paired error is well below the unpaired one,
  // sqrt(se_a^2 + se_b^2) of the mean squares.
  CHECK(average(difference_se) < 0.5 * 2 * average(rms) * average(rms_se) * std::sqrt(2.0));
}

TEST_CASE("summary: a filter whose equations are not finite at its state is reported as that, not as too stiff",
          "[summary][runtime][unit]") {
  const ScalarLinear model;
  FilterModel undefined;
  undefined.name = "undefined";
  undefined.n = 1;
  undefined.p = 1;
  undefined.initial_state = [](double* state) {
    state[0] = 0.5;
    state[1] = 1;
  };
  undefined.timing = std::make_unique<GridSteps>([](double* state, double, double dt, const double*) {
    const double r = 1 / (state[0] - 0.5);  // a definition that cannot be computed at m = 0.5
    state[0] += r * dt;
    state[1] += r * dt;
  });
  const MonteCarloResult result = run(3, 5, {scaled_gain_filter(model, "kb", 1.0), undefined});
  const FilterStatistics& stats = result.filters[1];
  CHECK(stats.undefined_runs == 5);
  CHECK(stats.too_stiff_runs == 0);
  CHECK(stats.divergences.count() == 5);
  const std::string table = format_summary_table(result, {"x"});
  CHECK(table.find("Runs stopped where the filter's equations were not finite at its own state") != std::string::npos);
  CHECK(table.find("too stiff") == std::string::npos);
}
