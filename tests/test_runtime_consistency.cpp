// The consistency of a filter's P against its errors (the NEES test of Bar-Shalom, Li &
// Kirubarajan 2001; docs/guide/simulation.md, "Reading the output"): the chi-square quantiles its
// band comes from, e^T P^-1 e on the packed layout, and run_monte_carlo's NEES at T and per record
// time, where Kalman-Bucy is consistent and the same filter reporting 10 P or P / 10 is not; and
// the per-time RMS error of the series and the CSV's new columns.
#include <catch2/catch.hpp>

#include <cmath>
#include <regex>
#include <string>
#include <vector>

#include <Eigen/Dense>

#include "pfgen_runtime/monte_carlo.hpp"
#include "pfgen_runtime/results_csv.hpp"
#include "pfgen_runtime/schemes.hpp"
#include "pfgen_runtime/statistics.hpp"
#include "pfgen_runtime/summary_table.hpp"
#include "support/scalar_linear_system.hpp"

using namespace pfgen_runtime;
using pfgen_test::ScalarLinear;
using pfgen_test::scalar_linear_system;
using pfgen_test::scalar_observation;

namespace {

// Kalman-Bucy whose state holds `factor` P instead of P: its m is the exact filter's, its P wrong
// by the factor (1: the exact filter).
FilterModel scaled_kalman_bucy(const ScalarLinear& model, const std::string& name, double factor) {
  FilterModel filter;
  filter.name = name;
  filter.n = 1;
  filter.p = 1;
  filter.initial_state = [model, factor](double* state) {
    state[0] = model.m0;
    state[1] = factor * model.P0;
  };
  filter.timing = std::make_unique<GridSteps>([model, factor](double* state, double, double dt, const double* dy) {
    const double m = state[0], P = state[1] / factor, K = P / (model.r * model.r);
    state[0] = m - model.a * m * dt + K * (dy[0] - m * dt);
    state[1] = factor * (P + (-2 * model.a * P + model.s * model.s - P * P / (model.r * model.r)) * dt);
  });
  return filter;
}

// The CSV's column `name`, row `row`, as text.
std::string csv_cell(const std::string& csv, const std::string& name, std::size_t row) {
  std::vector<std::vector<std::string>> rows;
  std::size_t start = 0;
  while (start < csv.size()) {
    const std::size_t end = csv.find('\n', start);
    const std::string line = csv.substr(start, end - start);
    std::vector<std::string> cells;
    std::size_t from = 0;
    while (true) {
      const std::size_t comma = line.find(',', from);
      cells.push_back(line.substr(from, comma - from));
      if (comma == std::string::npos) break;
      from = comma + 1;
    }
    rows.push_back(cells);
    start = end + 1;
  }
  for (std::size_t c = 0; c < rows.front().size(); ++c)
    if (rows.front()[c] == name) return rows.at(row + 1).at(c);
  return "(no column " + name + ")";
}

}  // namespace

TEST_CASE("consistency: chi-square quantiles and the NEES band match tabulated values", "[montecarlo][runtime][unit]") {
  // Tabulated chi-square quantiles (e.g. Abramowitz & Stegun table 26.8).
  CHECK(chi_square_quantile(0.975, 1) == Approx(5.0239).epsilon(1e-4));
  CHECK(chi_square_quantile(0.025, 1) == Approx(0.000982069).epsilon(1e-4));
  CHECK(chi_square_quantile(0.025, 10) == Approx(3.24697).epsilon(1e-4));
  CHECK(chi_square_quantile(0.975, 10) == Approx(20.4832).epsilon(1e-4));
  CHECK(chi_square_quantile(0.025, 100) == Approx(74.2219).epsilon(1e-4));
  CHECK(chi_square_quantile(0.975, 100) == Approx(129.561).epsilon(1e-4));
  // Either side of 10^4 degrees of freedom (bisection below, Wilson-Hilferty above) they join:
  // the quantile grows by about one per degree of freedom there.
  CHECK(chi_square_quantile(0.975, 10000.5) - chi_square_quantile(0.975, 10000) == Approx(0.5).epsilon(0.02));
  CHECK(chi_square_quantile(0.025, 10000.5) - chi_square_quantile(0.025, 10000) == Approx(0.5).epsilon(0.02));
  CHECK(regularized_gamma_p(0.5, 1.92073 / 2) == Approx(0.834).epsilon(1e-3));
  const NeesBand band = nees_band(50, 2);  // chi-square(100) / 100
  CHECK(band.low == Approx(0.742219).epsilon(1e-4));
  CHECK(band.high == Approx(1.29561).epsilon(1e-4));
  CHECK(std::isnan(nees_band(0, 2).low));
  CHECK_THROWS_AS(chi_square_quantile(1.0, 3), std::invalid_argument);

  // e^T P^-1 e on the packed upper triangle against Eigen's.
  Eigen::Matrix3d P;
  P << 2.0, 0.3, -0.1, 0.3, 1.5, 0.2, -0.1, 0.2, 0.8;
  const Eigen::Vector3d e(0.4, -1.2, 0.7);
  const double packed[6] = {P(0, 0), P(0, 1), P(0, 2), P(1, 1), P(1, 2), P(2, 2)};
  double work[9];
  CHECK(normalized_error_squared(e.data(), packed, 3, work) == Approx(e.dot(P.ldlt().solve(e))).epsilon(1e-12));
  const double singular[3] = {1.0, 1.0, 1.0};  // [[1, 1], [1, 1]]
  CHECK(std::isnan(normalized_error_squared(e.data(), singular, 2, work)));
}

TEST_CASE("consistency: Kalman-Bucy's NEES lies in its band, 10 P and P / 10 are called out; the series has the RMS error",
          "[montecarlo][runtime][statistical]") {
  const ScalarLinear model;
  EulerMaruyama scheme(scalar_linear_system(model));
  const Observation observation = scalar_observation(model.r);
  MonteCarloOptions options;
  options.grid = TimeGrid::to_horizon(0.0, 4.0, 2e-3);
  options.runs = 400;
  options.seed = 48;
  options.threads = 2;
  options.record_points = 20;
  options.report_times = {2.0};
  options.initial_prior = InitialPrior{Eigen::VectorXd::Constant(1, model.m0), Eigen::MatrixXd::Constant(1, 1, model.P0)};
  const std::vector<FilterModel> filters{scaled_kalman_bucy(model, "kalman-bucy", 1.0),
                                         scaled_kalman_bucy(model, "pessimistic", 10.0),
                                         scaled_kalman_bucy(model, "overconfident", 0.1)};
  const MonteCarloResult result = run_monte_carlo(scheme, observation, Eigen::VectorXd::Zero(1), filters, options);

  const FilterStatistics& kb = result.filters[0];
  REQUIRE(kb.nees.size() == 2);  // at t = 2 and at T
  for (std::size_t q = 0; q < 2; ++q) {
    INFO("Kalman-Bucy's NEES/n " << kb.nees[q] << " in [" << kb.nees_low[q] << ", " << kb.nees_high[q] << "]");
    CHECK(kb.nees_runs[q] == 400);
    CHECK(kb.nees[q] >= kb.nees_low[q]);
    CHECK(kb.nees[q] <= kb.nees_high[q]);
    // 10 P: NEES about a tenth; P / 10: about ten times.
    CHECK(result.filters[1].nees[q] < result.filters[1].nees_low[q]);
    CHECK(result.filters[1].nees[q] == Approx(kb.nees[q] / 10).epsilon(1e-6));
    CHECK(result.filters[2].nees[q] > result.filters[2].nees_high[q]);
  }
  const std::string table = format_summary_table(result, {"x"});
  INFO(table);
  CHECK(table.find("\nConsistency of P (NEES/n:") != std::string::npos);
  CHECK(std::regex_search(table, std::regex("\nkalman-bucy +2 +400 +[0-9.]+ +[0-9.]+ - [0-9.]+ +consistent\n")));
  CHECK(table.find("consistent\n") != std::string::npos);
  CHECK(table.find("too large\n") != std::string::npos);
  CHECK(table.find("too small\n") != std::string::npos);

  // The series: the RMS error at T is the report statistics' RMS folded the same way, bit for bit,
  // and the NEES at the last record is the table's at T.
  const FilterSeries& series = result.series.filters[0];
  const Eigen::Index last = series.error_rms.rows() - 1;
  REQUIRE(result.series.t.back() == options.grid.end());
  CHECK(series.nees(last, 0) == kb.nees.back());
  CHECK(series.nees_runs.back() == 400);
  const std::string csv = format_results_csv(result, {"x"});
  const std::string header = csv.substr(0, csv.find('\n'));
  // Appended after every column there was, the reference's included.
  CHECK(header.find(",overconfident_alive,kalman-bucy_err_x_rms,kalman-bucy_nees,kalman-bucy_nees_low,"
                    "kalman-bucy_nees_high,pessimistic_err_x_rms,") != std::string::npos);
  const NeesBand band = nees_band(400, 1);
  CHECK(std::stod(csv_cell(csv, "kalman-bucy_nees_low", static_cast<std::size_t>(last))) == band.low);
  CHECK(std::stod(csv_cell(csv, "kalman-bucy_nees", static_cast<std::size_t>(last))) == kb.nees.back());
  // The per-time RMS error, against the RMS over the runs of the error's mean and spread: E e^2 =
  // mean^2 + variance, the latter from the quantiles' spread being about 2 x 1.645 sd; loosely.
  const double rms = std::stod(csv_cell(csv, "kalman-bucy_err_x_rms", static_cast<std::size_t>(last)));
  CHECK(rms == series.error_rms(last, 0));
  CHECK(rms == Approx(std::sqrt(model.P_inf())).epsilon(0.15));
}

TEST_CASE("consistency: the series' RMS error is the RMS over the runs alive, bit for bit", "[montecarlo][runtime][unit]") {
  const ScalarLinear model;
  EulerMaruyama scheme(scalar_linear_system(model));
  const Observation observation = scalar_observation(model.r);
  MonteCarloOptions options;
  options.grid = TimeGrid::to_horizon(0.0, 1.0, 1e-2);
  options.runs = 5;
  options.seed = 7;
  options.record_points = 10;
  const std::vector<FilterModel> filters{scaled_kalman_bucy(model, "kalman-bucy", 1.0)};
  // One run alone: its RMS error at a record is |e| of that run, the series' shown-run error.
  options.runs = 1;
  const MonteCarloResult one = run_monte_carlo(scheme, observation, Eigen::VectorXd::Zero(1), filters, options);
  const FilterSeries& series = one.series.filters[0];
  for (Eigen::Index r = 0; r < series.error_rms.rows(); ++r) {
    const double e = one.series.truth(r, 0) - series.m(r, 0);
    CHECK(series.error_rms(r, 0) == std::sqrt(e * e));
    const double nees = e * e / series.P_diagonal(r, 0);
    CHECK(series.nees(r, 0) == Approx(nees).epsilon(1e-12));
  }
}
