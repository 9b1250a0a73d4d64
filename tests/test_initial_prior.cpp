// The truth drawn from the filters' prior (MonteCarloOptions::initial_prior, `pfgen simulate --x0
// prior`): each run's x0 is N(mean, covariance), singular covariances included, from the run's own
// stream (the same for any thread count); the command line's --x0 and the model's `x0: prior`, and
// the note --reference gives when the truth's x0 is fixed away from m0.
#include <catch2/catch.hpp>

#include <cmath>
#include <vector>

#include "pfgen_runtime/monte_carlo.hpp"
#include "support/cli_helpers.hpp"

using namespace pfgen_runtime;

namespace {

// x stays where it starts (no drift, no noise): the truth at T is the run's x0.
SdeSystem still(std::size_t n) {
  SdeSystem system;
  system.n = n;
  system.q = 0;
  system.drift = [n](double, const double*, double* f) {
    for (std::size_t i = 0; i < n; ++i) f[i] = 0;
  };
  return system;
}

FilterModel idle_filter() {
  FilterModel filter;
  filter.name = "idle";
  filter.n = 2;
  filter.p = 1;
  filter.initial_state = [](double* state) {
    for (std::size_t i = 0; i < filter_state_size(2); ++i) state[i] = 0;
  };
  filter.timing = std::make_unique<GridSteps>([](double*, double, double, const double*) {});
  return filter;
}

MonteCarloResult run(const InitialPrior& prior, std::size_t runs, unsigned threads) {
  const auto scheme = make_scheme(SchemeKind::rk4, still(2));
  const Observation observation(Eigen::VectorXd::Zero(1), Eigen::MatrixXd::Ones(1, 2),
                                      Eigen::MatrixXd::Constant(1, 1, 1.0));
  MonteCarloOptions options;
  options.grid = TimeGrid::to_horizon(0.0, 0.1, 0.05);
  options.runs = runs;
  options.seed = 9;
  options.threads = threads;
  options.report_times = {0.1};
  options.initial_prior = prior;
  return run_monte_carlo(*scheme, observation, Eigen::VectorXd::Constant(2, 123.0), {idle_filter()}, options);
}

}  // namespace

TEST_CASE("initial prior: each run's x0 is a draw of N(mean, covariance), the same for any thread count",
          "[montecarlo][runtime][statistical]") {
  InitialPrior prior;
  prior.mean = Eigen::Vector2d(0.5, -2.0);
  prior.covariance = Eigen::Matrix2d::Zero();
  prior.covariance(0, 0) = 4.0;  // sd 2; the second component has variance 0: a singular prior
  const std::size_t runs = 4000;
  const MonteCarloResult one = run(prior, runs, 1);
  const TruthReportStatistics& truth = one.truth_reports.front();
  REQUIRE(truth.alive == runs);
  CHECK(one.x0_from_prior);
  // The fixed x0 (123) is not used; the mean within 4 standard errors, the 5-95 % range 2 x 1.645 sd.
  CHECK(std::abs(truth.mean[0] - 0.5) < 4 * 2.0 / std::sqrt(static_cast<double>(runs)));
  CHECK((truth.q95[0] - truth.q05[0]) == Approx(2 * 1.6449 * 2.0).epsilon(0.06));
  CHECK(truth.mean[1] == Approx(-2.0).epsilon(1e-15));
  CHECK(truth.q05[1] == truth.q95[1]);
  const MonteCarloResult two = run(prior, runs, 2);
  CHECK(two.truth_reports.front().mean == truth.mean);
  CHECK(two.truth_reports.front().q05 == truth.q05);
  CHECK(two.filters.front().horizon.rms == one.filters.front().horizon.rms);
  // A covariance that is no covariance is refused.
  prior.covariance(0, 0) = -1.0;
  CHECK_THROWS_WITH(run(prior, 2, 1), Catch::Contains("not positive semi-definite"));
}

TEST_CASE("simulate --x0 prior draws each run's truth from N(m0, P0); --reference notes a fixed x0 away from m0",
          "[simulate][compiler]") {
  using namespace pfgen_test;
  TempDir dir;
  const std::string model = example("reference/time_varying_cubic.yaml");
  auto simulate = [&](std::vector<std::string> more) {
    std::vector<std::string> args{"simulate", model, "--runs", "4", "--T", "0.2", "--cache-dir", dir.file("cache"), "-q"};
    args.insert(args.end(), more.begin(), more.end());
    return run_pfgen(args);
  };
  const auto fixed = simulate({"--reference", "particles:20"});
  REQUIRE(fixed.exit_code == 0);
  CHECK(fixed.err.find("pfgen: note: --reference: every run's truth starts at x0 = (0.5, -0.5), not from the "
                       "filters' prior N(m0, P0) with m0 = (0, 0)") != std::string::npos);
  CHECK(fixed.out.find("drawn from N(m0, P0)") == std::string::npos);
  const auto drawn = simulate({"--reference", "particles:20", "--x0", "prior"});
  REQUIRE(drawn.exit_code == 0);
  CHECK(drawn.err.find("note: --reference") == std::string::npos);
  CHECK(drawn.out.find("truth x0 drawn from N(m0, P0) per run") != std::string::npos);
  CHECK(drawn.out != fixed.out);
  // The model file's x0: prior says the same; --x0 model goes back to a fixed x0.
  std::string text = read_file(model);
  text.replace(text.find("x0: [0.5, -0.5]"), 15, "x0: prior");
  write_file(dir.file("prior.yaml"), text);
  const auto from_file = run_pfgen({"simulate", dir.file("prior.yaml"), "--runs", "4", "--T", "0.2", "--cache-dir",
                                    dir.file("cache"), "-q"});
  REQUIRE(from_file.exit_code == 0);
  CHECK(from_file.out.find("truth x0 drawn from N(m0, P0) per run") != std::string::npos);
  const auto back = run_pfgen({"simulate", dir.file("prior.yaml"), "--runs", "4", "--T", "0.2", "--x0", "model",
                               "--cache-dir", dir.file("cache"), "-q"});
  CHECK(back.exit_code == 1);
  CHECK(back.err.find("the model gives no x0") != std::string::npos);
  const auto bad = simulate({"--x0", "sometimes"});
  CHECK(bad.exit_code == 1);
  CHECK(count_lines(bad.err) == 1);
  CHECK(bad.err.find("--x0: 'sometimes' is neither prior") != std::string::npos);
}
