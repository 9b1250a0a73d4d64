// Records of delayed observations (estimate and fit with dy = (A0 + A x(t - h)) dt + B dW2): at
// h = 0 the delayed filters give the undelayed ones' scores and estimates on the same record (an
// independent path: the continuous plugin's step against the delayed one's ring and grid), and a
// record that does not fit the delay's grid is refused with one line naming its place.
// tests/record_data/check_delayed.py checks h > 0 against the filters written in numpy.
#include <catch2/catch.hpp>

#include <cmath>
#include <random>
#include <string>
#include <vector>

#include "pfgen/pfgen.hpp"
#include "pfgen_runtime/record_run.hpp"
#include "support/cli_helpers.hpp"
#include "support/refusal.hpp"

namespace api = pfgen::api;
using Catch::Matchers::Contains;
using pfgen_test::TempDir;
using pfgen_test::write_file;

namespace {

// dx = a x dt + sigma dW1 observed as dy = x dt + 0.2 dW2, with or without a delay of 0.
api::Model linear_model(bool delayed) {
  api::ModelBuilder b(delayed ? "delayed_at_zero" : "undelayed");
  const GiNaC::symbol x = b.state("x");
  const GiNaC::symbol a = b.parameter("a", -0.5), sigma = b.parameter("sigma", 0.3);
  b.drift({a * x}).diffusion({{sigma}});
  if (delayed)
    b.delayed_observation(0, {0}, {{1}}, {{GiNaC::numeric(1, 5)}});
  else
    b.observation({0}, {{1}}, {{GiNaC::numeric(1, 5)}});
  return b.initial({0.5}, {{0.25}}, {1}).build();
}

// 400 increments every 0.01 of a seeded Euler path (any path does: both filters read the same).
api::RecordData linear_record() {
  std::mt19937_64 generator(7);
  std::normal_distribution<double> normal;
  api::RecordData data;
  data.columns = {"t", "y"};
  const double dt = 0.01;
  double x = 1;
  data.rows.push_back({0, std::nan("")});
  for (int k = 1; k <= 400; ++k) {
    const double dy = x * dt + 0.2 * std::sqrt(dt) * normal(generator);
    x += -0.5 * x * dt + 0.3 * std::sqrt(dt) * normal(generator);
    data.rows.push_back({k * dt, dy});
  }
  return data;
}

// A stand-in for a delayed filter: it notes the times it is stepped and asked at, and that its
// extra state is carried.
std::vector<double> step_times, rate_times;
std::size_t extra_seen = 0;

}  // namespace

TEST_CASE("RecordRun steps a fixed-grid filter on its own grid from the prior, with its extra state",
          "[record][delayed][unit]") {
  pfgen_runtime::RecordFilter filter;
  filter.name = "fake";
  filter.n = filter.p = filter.r = 1;
  filter.initial_state = [](double* state) { state[0] = 0, state[1] = 1, state[2] = 7, state[3] = 8; };
  filter.timing = std::make_shared<pfgen_runtime::RecordFixedIncrements>(
      [](double* state, const double*, double t, double dt, const double*) {
        step_times.push_back(t);
        extra_seen += state[2] == 7 && state[3] == 8 && dt == 0.1;
      },
      [](const double*, const double*, double t, double* h) {
        rate_times.push_back(t);
        h[0] = 0;
      },
      [](const double*, double, double* B) { B[0] = 1; }, 0.1, 2);
  step_times.clear(), rate_times.clear(), extra_seen = 0;
  pfgen_runtime::RecordRunOptions options;
  options.substeps = 2;
  pfgen_runtime::RecordRun run(filter, {}, 5, options);
  REQUIRE(run.state().size() == 4);
  const double y = 0.1;
  CHECK(run.advance(5.2, &y));
  CHECK(run.advance(5.4 + 1e-12, &y));  // within the relative 1e-9
  CHECK(step_times == std::vector<double>{0, 0.1, 0.2, 0.30000000000000004});
  // Per row: the predicted observation, then twice per state for its Jacobian in m (the
  // innovation's covariance), all at the row's grid time.
  CHECK(rate_times == std::vector<double>{0, 0, 0, 0.2, 0.2, 0.2});
  CHECK(extra_seen == 4);
  CHECK_THROWS_WITH(run.advance(5.7, &y), Contains("delayed observations need equally spaced rows: the interval from "
                                                   "t = 5.4 is 0.3, not the filters' step 0.2 (relative 1e-9)"));
  CHECK_THROWS_WITH(pfgen_runtime::RecordRun(filter, {}, 0, options, {0, 1}),
                    Contains("the filter 'fake' keeps a history and starts from the model's m0 and P0"));
}

TEST_CASE("delayed observations at h = 0 give the undelayed filters' scores and estimates on a record",
          "[record][delayed][compiler]") {
  TempDir dir;
  api::EstimateOptions options;
  options.record.data = linear_record();
  options.record.cache_dir = dir.file("cache");
  options.series = true;
  const std::vector<std::pair<std::string, std::string>> pairs{{"delay-optimal", "optimal"}, {"delay-ekf", "ekf"}};
  options.filters = {"delay-optimal", "delay-ekf"};
  const api::EstimateResult delayed = linear_model(true).estimate(options);
  options.filters = {"optimal", "ekf"};
  const api::EstimateResult undelayed = linear_model(false).estimate(options);
  REQUIRE(delayed.filters.size() == 2);
  REQUIRE(undelayed.filters.size() == 2);
  for (std::size_t f = 0; f < 2; ++f) {
    INFO(pairs[f].first << " against " << pairs[f].second);
    CHECK(delayed.filters[f].count == 400);
    CHECK(delayed.filters[f].log_likelihood == Approx(undelayed.filters[f].log_likelihood).epsilon(1e-12));
    CHECK(delayed.filters[f].increment_log_density ==
          Approx(undelayed.filters[f].increment_log_density).epsilon(1e-12));
    CHECK(delayed.filters[f].mean_square == Approx(undelayed.filters[f].mean_square).epsilon(1e-12));
  }
  // The CSV's columns past the time and the data, in the same order (names aside).
  REQUIRE(delayed.series.size() == undelayed.series.size());
  double largest = 0;
  for (std::size_t c = 2; c < delayed.series.size(); ++c)
    for (std::size_t r = 1; r < delayed.series[c].size(); ++r)
      largest = std::max(largest, std::abs(delayed.series[c][r] - undelayed.series[c][r]));
  CHECK(largest < 1e-12);
  CHECK_THAT(delayed.report, Contains("continuous (increments) observations delayed by h = 0, filter step 0.01"));
}

TEST_CASE("estimate and fit refuse a record that does not fit the delay's grid with one line", "[record][delayed][compiler]") {
  TempDir dir;
  const std::string model = std::string(PFGEN_SOURCE_DIR) + "/examples/delay_linear.yaml";
  const std::string cache = "--cache-dir=" + dir.file("cache");
  auto fails_with = [&](std::vector<std::string> arguments, const std::string& message) {
    arguments.push_back(cache);
    arguments.push_back("-q");
    pfgen_test::check_refused_in_one_line(arguments, message);
  };
  // A prior's time far before the record: the step from it is longer than the delay, said so with --t0
  // (before: an inconsistent plugin, 0 steps of history).
  const std::string record = std::string(PFGEN_SOURCE_DIR) + "/examples/records/delay_linear_increments.csv";
  fails_with({"estimate", model, "--data", record, "--t0", "-1e9"},
             "delay_linear_increments.csv:2: the record's step 1e+09 (the delayed filters' grid step), from the prior's "
             "time (--t0) to the first row: the delay h = 0.5 and the step dt = 1e+09: h must be at least one step "
             "(h / dt = 5e-10)");
  // A step that does not divide h = 0.5.
  write_file(dir.file("coarse.csv"), "t,y\n0,\n0.03,0.01\n0.06,0.02\n");
  fails_with({"estimate", model, "--data", dir.file("coarse.csv")},
             "coarse.csv:3: the record's step 0.03 (the delayed filters' grid step): the delay h = 0.5 and the step dt "
             "= 0.03: h must be a whole number of steps (h / dt = 16.666666666666668)");
  fails_with({"estimate", model, "--data", dir.file("coarse.csv"), "--substeps", "2"},
             "the record's step 0.03 over --substeps 2 (the delayed filters' grid step)");
  // Uneven rows: the line of the first interval that differs.
  write_file(dir.file("uneven.csv"), "t,y\n0,\n0.01,0.01\n0.02,0.02\n0.04,0.01\n");
  fails_with({"estimate", model, "--data", dir.file("uneven.csv")},
             "uneven.csv:5: delayed observations need equally spaced rows: the interval from t = 0.02 is 0.02, not the "
             "filters' step 0.01 (relative 1e-9)");
  fails_with({"fit", model, "--data", dir.file("uneven.csv"), "--estimate", "a"},
             "uneven.csv:5: delayed observations need equally spaced rows");
  // One row at the prior's time: no step to generate the filters for.
  write_file(dir.file("one.csv"), "t,y\n0,\n");
  fails_with({"estimate", model, "--data", dir.file("one.csv")},
             "one.csv:2: delayed observations need the record's step, and the record has one row, at the prior's time");
  // Coefficients that depend on t, with the prior away from t = 0: the filters count their grid from
  // the prior.
  std::string timed = pfgen_test::read_file(model);
  timed.replace(timed.find("drift: [a*x]"), 12, "drift: [a*x + 0.1*t]");
  write_file(dir.file("timed.yaml"), timed);
  write_file(dir.file("late.csv"), "t,y\n1,\n1.01,0.01\n1.02,0.02\n");
  fails_with({"estimate", dir.file("timed.yaml"), "--data", dir.file("late.csv")},
             "timed.yaml: the filter 'delay-optimal' depends on t, and a delayed filter counts its grid from the prior's "
             "time as t = 0: start the record at t = 0 (the prior's time is 1, the first row's)");
  // The same record with its prior at t = 0 runs (the first interval, from 0 to 1, is not the step).
  fails_with({"estimate", dir.file("timed.yaml"), "--data", dir.file("late.csv"), "--t0", "0"},
             "late.csv:2: the record's step 1 (the delayed filters' grid step)");
}

TEST_CASE("estimate's table keeps one line per filter when a model far off its data scores -5.7e53",
          "[record][delayed][compiler]") {
  // a = 5 makes the delayed filters' innovations huge; the fixed six decimals would print 54 digits and cut the
  // line (the verdicts ran into the next filter's row).
  TempDir dir;
  const auto result = pfgen_test::run_pfgen({"estimate", std::string(PFGEN_SOURCE_DIR) + "/examples/delay_linear.yaml",
                                             "--data",
                                             std::string(PFGEN_SOURCE_DIR) + "/examples/records/delay_linear_increments.csv",
                                             "--set", "a=5", "--cache-dir=" + dir.file("cache"), "-q"});
  INFO(result.out << result.err);
  REQUIRE(result.exit_code == 0);
  CHECK_THAT(result.out, Contains("\ndelay-optimal        -5.66571e+53              -5.66571e+53        1000"));
  CHECK_THAT(result.out, Contains("(Ljung-Box p = 0 at 10 lags)\ndelay-uncorrected "));
  CHECK_THAT(result.out, Contains("(Ljung-Box p = 0 at 10 lags)\ndelay-ekf "));
}
