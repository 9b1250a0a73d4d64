// Recorded data: the record reader's errors (file, line, column), the innovation scores against a
// direct computation, and estimate/fit's refusals of bad input.
#include <catch2/catch.hpp>

#include <filesystem>
#include <map>
#include <sstream>

#include <cmath>
#include <random>
#include <vector>

#include "pfgen_runtime/innovation_scores.hpp"
#include "pfgen_runtime/record_reader.hpp"
#include "pfgen_runtime/statistics.hpp"
#include "support/cli_helpers.hpp"
#include "support/refusal.hpp"

using Catch::Matchers::Contains;
using pfgen_test::TempDir;
using pfgen_test::write_file;

namespace {

std::string reader_error(const std::string& contents, const std::string& time = "t", std::size_t expected = 1) {
  TempDir dir;
  const std::string path = dir.file("r.csv");
  write_file(path, contents);
  try {
    pfgen_runtime::RecordReader reader(path, time, {}, expected);
    double t = 0;
    std::vector<double> y(expected);
    while (reader.next(t, y.data())) {
    }
  } catch (const pfgen_runtime::RecordError& e) {
    return std::string(e.what()).substr(path.size());  // the place after the path
  }
  return "";
}

}  // namespace

TEST_CASE("the record reader names the line and column of every bad cell", "[record][unit]") {
  CHECK(reader_error("") == ": the file is empty: a record needs a header line naming its columns");
  CHECK_THAT(reader_error("time,y\n1,2\n"), Contains("the header has no time column 't' (its columns: time, y)"));
  CHECK_THAT(reader_error("t,y,z\n1,2,3\n"), Contains("2 columns besides the time 't', the model observes 1"));
  CHECK(reader_error("t,y\n0,1\n1,abc\n") == ":3: column 2 (y): 'abc' is not a number");
  CHECK(reader_error("t,y\n0,1\n1,1e999\n") == ":3: column 2 (y): '1e999' is beyond the range of a double");
  CHECK(reader_error("t,y\n0,1\n0,2\n") ==
        ":3: column 1 (t): the time 0 does not come after the previous row's (line 2): times must increase");
  CHECK(reader_error("t,y\n0,1\n1\n") == ":3: the row has 1 fields, the header 2");
  CHECK(reader_error("t,y\n,1\n") == ":2: column 1 (t): the time is missing");
  CHECK(reader_error("t,y\n0,\"1\"\n") == ":2: quoted fields are not read: write the cell without quotes");
  CHECK(reader_error("t,t\n") == ":1: column 2: the header names 't' twice");
  CHECK(reader_error(std::string("t,y\n0,") + std::string(pfgen_runtime::RecordReader::kMaxLineLength + 5, '1') + "\n") ==
        ":2: the line is longer than 1048576 bytes");
}

TEST_CASE("the record reader reads missing cells as NaN, skips comments and blank lines, takes CRLF", "[record][unit]") {
  TempDir dir;
  const std::string path = dir.file("r.csv");
  write_file(path, "# a comment\r\nt , y\r\n\r\n0, 1.5\r\n1,\r\n2,NaN\r\n3,+2");
  pfgen_runtime::RecordReader reader(path, "t", {}, 1);
  std::vector<double> times, values;
  double t = 0, y = 0;
  while (reader.next(t, &y)) times.push_back(t), values.push_back(y);
  REQUIRE(times == std::vector<double>{0, 1, 2, 3});
  CHECK(values[0] == 1.5);
  CHECK(std::isnan(values[1]));
  CHECK(std::isnan(values[2]));
  CHECK(values[3] == 2);
  CHECK(reader.line() == 7);
  // A UTF-8 byte-order mark before the header (or before a comment) is skipped, not read into the first name.
  for (const std::string& start : {std::string("t,y\n"), std::string("# exported\nt,y\n")}) {
    write_file(path, "\xEF\xBB\xBF" + start + "0,1\n");
    pfgen_runtime::RecordReader marked(path, "t", {}, 1);
    REQUIRE(marked.next(t, &y));
    CHECK(y == 1);
  }
}

TEST_CASE("innovation scores: the mean square, its band and Ljung-Box as computed directly", "[record][unit]") {
  std::mt19937_64 generator(3);
  std::normal_distribution<double> normal;
  std::vector<double> e(400);
  double previous = 0;
  for (double& v : e) v = previous = 0.3 * previous + normal(generator);  // mildly correlated
  pfgen_runtime::InnovationScores scores(1, 10);
  for (double v : e) scores.add(&v, -0.5 * v * v);
  const auto s = scores.summary();
  const double N = static_cast<double>(e.size());
  double mean = 0, square = 0, ll = 0;
  for (double v : e) mean += v / N, square += v * v / N, ll += -0.5 * v * v;
  CHECK(s.mean_square == Approx(square).epsilon(1e-12));
  CHECK(s.log_likelihood == Approx(ll).epsilon(1e-12));
  CHECK(s.band_low == Approx(pfgen_runtime::chi_square_quantile(0.025, N) / N));
  double centred = 0;
  for (double v : e) centred += (v - mean) * (v - mean);
  double Q = 0;
  for (std::size_t l = 1; l <= 10; ++l) {
    double c = 0;
    for (std::size_t k = l; k < e.size(); ++k) c += (e[k] - mean) * (e[k - l] - mean);
    Q += (c / centred) * (c / centred) / (N - static_cast<double>(l));
  }
  Q *= N * (N + 2);
  REQUIRE(s.whiteness.size() == 1);
  CHECK(s.whiteness[0].lags == 10);
  CHECK(s.whiteness[0].statistic == Approx(Q).epsilon(1e-10));
  CHECK(s.whiteness[0].p_value < 0.05);  // an AR(1) with 0.3 over 400 values is not white
  CHECK_THAT(s.verdict(), Contains("fails whiteness"));
}

TEST_CASE("estimate and fit refuse bad options and data with one clear line", "[record][compiler]") {
  TempDir dir;
  const std::string model = std::string(PFGEN_SOURCE_DIR) + "/examples/records/nile.yaml";
  const std::string data = std::string(PFGEN_SOURCE_DIR) + "/examples/records/nile.csv";
  const std::string cache = "--cache-dir=" + dir.file("cache");
  auto fails_with = [&](std::vector<std::string> arguments, const std::string& message) {
    arguments.push_back(cache);
    arguments.push_back("-q");
    pfgen_test::check_refused_in_one_line(arguments, message);
  };
  fails_with({"fit", model, "--data", data, "--time-column", "year", "--estimate", "sigma"},
             "--estimate: 'sigma' is not a parameter of");
  fails_with({"fit", model, "--data", data, "--time-column", "year", "--estimate", "q,q"}, "'q' is named twice");
  fails_with({"fit", model, "--data", data, "--time-column", "year", "--estimate", "q", "--bounds", "q=0:10"},
             "--bounds: q's bounds exclude its start 1469.1");
  fails_with({"fit", model, "--data", data, "--time-column", "year", "--estimate", "q", "--bounds", "h=0:10"},
             "'h' is not among the estimated parameters");
  fails_with({"fit", model, "--data", data, "--time-column", "year", "--estimate", "q", "--starts", "3"},
             "give q both ends in --bounds");
  fails_with({"fit", model, "--data", data, "--time-column", "year", "--estimate", "q", "--bounds", "q=0:,q=1:"},
             "--bounds: 'q' is given bounds twice");
  // The Nile's record is sampled: the continuous data's options would do nothing, so they are refused.
  fails_with({"estimate", model, "--data", data, "--time-column", "year", "--substeps", "5"},
             "--substeps: sampled observations are predicted in the model's sub-steps "
             "(observation.sampled.substeps per period); --substeps is for continuous data");
  fails_with({"fit", model, "--data", data, "--time-column", "year", "--estimate", "q", "--data-form", "rates"},
             "--data-form: sampled observations are read as samples y_k; --data-form rates is for continuous data");
  write_file(dir.file("none.csv"), "year,volume\n1871,NA\n1872,\n");
  fails_with({"fit", model, "--data", dir.file("none.csv"), "--time-column", "year", "--estimate", "q"},
             "none.csv: every observation is missing: the record has no sample to fit");
  fails_with({"estimate", model, "--data", data, "--time-column", "year", "--t0", "-1e9"},
             "check the time column and the prior's time (--t0)");
  fails_with({"estimate", model, "--data", data}, "the header has no time column 't' (its columns: year, volume)");
  write_file(dir.file("bad.csv"), "year,volume\n1871,1120\n1872,abc\n");
  fails_with({"estimate", model, "--data", dir.file("bad.csv"), "--time-column", "year"},
             "bad.csv:3: column 2 (volume): 'abc' is not a number");
  fails_with({"estimate", model, "--data", data, "--time-column", "year", "-o", model}, "-o");
  fails_with({"estimate", model, "--data", data, "--time-column", "year", "--plot", dir.file("p.png")},
             "--plot: the plot reads the CSV; give -o FILE.csv too");
  // A last sample too far off to score would print a log-likelihood of -inf; fit names the file and line too.
  write_file(dir.file("far.csv"), "year,volume\n1871,1120\n1872,1160\n1873,1e308\n");
  fails_with({"estimate", model, "--data", dir.file("far.csv"), "--time-column", "year"},
             "far.csv:4: the filter 'cd-optimal' failed: the observation is too far from its prediction to score in "
             "double precision at t = 1873");
  fails_with({"fit", model, "--data", dir.file("far.csv"), "--time-column", "year", "--estimate", "q"},
             "the log-likelihood is not finite at the start: ");
  fails_with({"fit", model, "--data", dir.file("far.csv"), "--time-column", "year", "--estimate", "q"},
             "far.csv:4: the filter 'cd-optimal' failed");
}

TEST_CASE("estimate writes no CSV when the record fails part way", "[record][compiler]") {
  TempDir dir;
  const std::string model = std::string(PFGEN_SOURCE_DIR) + "/examples/records/nile.yaml";
  write_file(dir.file("bad.csv"), "year,volume\n1871,1120\n1872,1160\n1873,x\n");
  const auto result = pfgen_test::run_pfgen({"estimate", model, "--data", dir.file("bad.csv"), "--time-column", "year",
                                             "-o", dir.file("out.csv"), "--cache-dir=" + dir.file("cache"), "-q"});
  CHECK(result.exit_code == 1);
  CHECK(dir.entries() == std::vector<std::string>{"bad.csv", "cache"});
}

TEST_CASE("estimate and simulate asked for a plot without gnuplot on PATH refuse before writing anything",
          "[record][integration]") {
  // Before, the CSV replaced the existing one and the .gp script was written, and only then did the plot fail.
  TempDir dir;
  std::filesystem::create_directory(dir.file("empty-path"));
  const std::string model = std::string(PFGEN_SOURCE_DIR) + "/examples/records/nile.yaml";
  const std::string data = std::string(PFGEN_SOURCE_DIR) + "/examples/records/nile.csv";
  write_file(dir.file("out.csv"), "keep\n");
  const std::vector<std::vector<std::string>> commands = {
      {"estimate", model, "--data", data, "--time-column", "year", "-o", dir.file("out.csv"), "--plot",
       dir.file("out.png"), "--cache-dir=" + dir.file("cache"), "-q"},
      {"simulate", model, "--runs", "2", "-o", dir.file("out.csv"), "--plot", dir.file("out.png"),
       "--cache-dir=" + dir.file("cache"), "-q"}};
  for (const auto& command : commands) {
    std::vector<std::string> argv{"/usr/bin/env", "PATH=" + dir.file("empty-path"), pfgen_test::pfgen_executable()};
    argv.insert(argv.end(), command.begin(), command.end());
    const auto result = pfgen_test::run_program(argv);
    INFO(command[0] << ": " << result.err);
    CHECK(result.exit_code == 1);
    CHECK(result.err == "pfgen: error: --plot: gnuplot is not on PATH: install gnuplot (scripts/install-deps.sh "
                        "installs gnuplot-nox), or leave --plot out\n");
    CHECK(dir.entries() == std::vector<std::string>{"empty-path", "out.csv"});
    CHECK(pfgen_test::read_file(dir.file("out.csv")) == "keep\n");
  }
}

TEST_CASE("a gnuplot that fails is named by its first error line, not a warning before it", "[record][compiler]") {
  TempDir dir;
  std::filesystem::create_directory(dir.file("bin"));
  const std::string fake = dir.file("bin/gnuplot");
  write_file(fake, "#!/bin/sh\necho 'line 0: warning: Cannot find or open file' >&2\n"
                   "echo '\"script\" line 9: No data in plot' >&2\nexit 1\n");
  std::filesystem::permissions(fake, std::filesystem::perms::owner_all);
  const std::string model = std::string(PFGEN_SOURCE_DIR) + "/examples/records/nile.yaml";
  const std::string data = std::string(PFGEN_SOURCE_DIR) + "/examples/records/nile.csv";
  const auto result = pfgen_test::run_program({"/usr/bin/env", "PATH=" + dir.file("bin") + ":/usr/bin:/bin",
                                               pfgen_test::pfgen_executable(), "estimate", model, "--data", data,
                                               "--time-column", "year", "-o", dir.file("out.csv"), "--plot",
                                               dir.file("out.png"), "--cache-dir=" + dir.file("cache"), "-q"});
  CHECK(result.exit_code == 1);
  CHECK(result.err == "pfgen: error: gnuplot failed on '" + dir.file("out.png.gp") +
                          "' (exit status 1): \"script\" line 9: No data in plot\n");
}

TEST_CASE("the model file's bounds: reach fit, and bad ones are refused with their field", "[record][compiler]") {
  TempDir dir;
  const std::string data = std::string(PFGEN_SOURCE_DIR) + "/examples/records/nile.csv";
  const std::string base = "name: nile\nstates: [x]\nparameters: {q: 1469.1, h: 15099}\ndrift: [\"0\"]\n"
                           "diffusion: [[\"sqrt(q)\"]]\nobservation:\n  sampled: {period: 1, C: [[\"1\"]], "
                           "Uv: [[\"sqrt(h)\"]], substeps: 1}\ninitial: {x0: prior, m0: [0], P0: [[1e7]]}\n";
  auto model_with = [&](const std::string& bounds) {
    write_file(dir.file("m.yaml"), base + bounds);
    return dir.file("m.yaml");
  };
  auto arguments_for = [&](const std::string& model, std::vector<std::string> more) {
    std::vector<std::string> arguments{"fit", model, "--data", data, "--time-column", "year", "-q",
                                       "--cache-dir=" + dir.file("cache")};
    arguments.insert(arguments.end(), more.begin(), more.end());
    return arguments;
  };
  auto run = [&](const std::string& model, std::vector<std::string> more) {
    return pfgen_test::run_pfgen(arguments_for(model, std::move(more)));
  };
  // Three starts need finite bounds: the model file's give them, and the fit lands where
  // --bounds would put it.
  const auto from_file = run(model_with("bounds: {q: [1, 1e5], h: [1, 1e6]}\n"), {"--estimate", "q,h", "--starts", "3"});
  REQUIRE(from_file.exit_code == 0);
  CHECK_THAT(from_file.out, Contains("q                    1468.5"));
  const auto without = run(model_with(""), {"--estimate", "q,h", "--starts", "3"});
  CHECK(without.exit_code == 1);
  CHECK_THAT(without.err, Contains("give q both ends in --bounds"));
  // --bounds replaces the file's for its parameter: this one excludes the start.
  CHECK_THAT(run(model_with("bounds: {q: [1, 1e5]}\n"), {"--estimate", "q", "--bounds", "q=0:10"}).err,
             Contains("q's bounds exclude its start 1469.1"));
  for (const auto& [bounds, message] : std::vector<std::pair<std::string, std::string>>{
           {"bounds: {sigma: [0, 1]}\n", "field 'bounds.sigma': 'sigma' is not a parameter"},
           {"bounds: {q: [5, 1]}\n", "field 'bounds.q': the low end is not below the high end"},
           {"bounds: {q: [0, 100]}\n", "field 'bounds.q': the bounds exclude the parameter's value 1469.1"},
           {"bounds: {q: [0]}\n", "field 'bounds.q': expected [low, high] (an end may be ~ for none)"},
           {"bounds: {q: [0, abc]}\n", "'abc' is not a number"},
           {"bounds: [q]\n", "field 'bounds': expected a mapping of parameters to [low, high]"}}) {
    INFO(bounds);
    pfgen_test::check_refused_in_one_line(arguments_for(model_with(bounds), {"--estimate", "q"}), message);
  }
  // An end given as ~ is open.
  CHECK(run(model_with("bounds: {q: [0, ~]}\n"), {"--estimate", "q"}).exit_code == 0);
}

TEST_CASE("fit refuses a parameter the filter's likelihood does not read", "[record][compiler]") {
  TempDir dir;
  std::string model = pfgen_test::read_file(std::string(PFGEN_SOURCE_DIR) + "/examples/van_der_pol.yaml");
  // k: the additive kinds' noise, which the optimal filter never reads.
  model.replace(model.find("parameters: {mu: 1, s: 0.5, r: 0.1}"), 35, "parameters: {mu: 1, s: 0.5, r: 0.1, k: 2}");
  model.replace(model.find("additive_diffusion: [[\"0\"], [\"s\"]]"), 35, "additive_diffusion: [[\"0\"], [\"k\"]]");
  write_file(dir.file("m.yaml"), model);
  const std::string data = std::string(PFGEN_SOURCE_DIR) + "/examples/records/van_der_pol_increments.csv";
  auto fit = [&](const std::string& filter) {
    return pfgen_test::run_pfgen({"fit", dir.file("m.yaml"), "--data", data, "--estimate", "k", "--filter", filter, "-q",
                                  "--cache-dir=" + dir.file("cache")});
  };
  const auto refused = fit("optimal");
  CHECK(refused.exit_code == 1);
  CHECK_THAT(refused.err, Contains("--estimate: 'k' does not change the log-likelihood of the filter 'optimal' on this "
                                   "record (it does not enter that filter's equations)"));
  // The additive filter reads it: fitted.
  const auto fitted = fit("additive");
  CHECK(fitted.exit_code == 0);
  CHECK_THAT(fitted.out, Contains("converged"));
}

TEST_CASE("estimate refuses a gap between samples that would take more than 10^7 sub-steps", "[record][compiler]") {
  // Found by fuzzing: a time of 118E6 after 7 asked for 7 x 10^8 prediction sub-steps, minutes of work.
  TempDir dir;
  const std::string model = std::string(PFGEN_SOURCE_DIR) + "/examples/records/nile.yaml";
  write_file(dir.file("gap.csv"), "year,volume\n1871,1120\n1872,1160\n118E6,963\n");
  pfgen_test::check_refused_in_one_line(
      {"estimate", model, "--data", dir.file("gap.csv"), "--time-column", "year", "-q", "--cache-dir=" + dir.file("cache")},
      "gap.csv:4: the interval from t = 1872 to 118000000 needs 1.18e+08 prediction sub-steps (1 per period 1), more "
      "than 1e+07: check the time column");
}

TEST_CASE("a moment filter over a record fails where its moments leave the realisable set, and runs where not",
          "[record][compiler]") {
  // Van der Pol's record at one closure4 step per 0.01: the first row already drives x1's Pearson bound below 0,
  // which fails the run with the margin's name (never a silent run past it); four steps per row keep it realisable.
  TempDir dir;
  const std::string model = std::string(PFGEN_SOURCE_DIR) + "/examples/van_der_pol.yaml";
  const std::string data = std::string(PFGEN_SOURCE_DIR) + "/examples/records/van_der_pol_increments.csv";
  const auto failed = pfgen_test::run_pfgen({"estimate", model, "--data", data, "--filters", "closure4",
                                             "--cache-dir=" + dir.file("cache"), "-q"});
  CHECK(failed.exit_code == 1);
  CHECK_THAT(failed.err, Contains("van_der_pol_increments.csv:3: the filter 'closure4' failed: its moments left the "
                                  "realisable set at t = 0.01 (Pearson's bound of x1 is -"));
  const auto ran = pfgen_test::run_pfgen({"estimate", model, "--data", data, "--filters", "closure3,closure4",
                                          "--substeps", "4", "--cache-dir=" + dir.file("cache"), "-q"});
  INFO(ran.err);
  CHECK(ran.exit_code == 0);
  CHECK_THAT(ran.out, Contains("closure4 ") && Contains("passes: consistent and white"));
}

TEST_CASE("estimate reports a filter that stops part way and goes on with the others; only a lone one fails it",
          "[record][compiler]") {
  // closure3 leaves its realisable set at row 462 of the double well's record; optimal and closure4 run through.
  TempDir dir;
  const std::string model = std::string(PFGEN_SOURCE_DIR) + "/examples/reference/double_well.yaml";
  const std::string record = std::string(PFGEN_SOURCE_DIR) + "/tests/data/double_well_increments.csv";
  const std::string cache = "--cache-dir=" + dir.file("cache");
  const auto all = pfgen_test::run_pfgen({"estimate", model, "--data", record, "--filters", "optimal,closure3,closure4",
                                          "-o", dir.file("out.csv"), cache, "-q"});
  INFO(all.out << all.err);
  REQUIRE(all.exit_code == 0);
  CHECK_THAT(all.out, Contains("\nclosure3         stopped at " + record + ":462: its moments left the realisable set "
                               "at t = 4.6 (Pearson's bound of x1 is -"));
  CHECK_THAT(all.out, Contains("\noptimal   ") && Contains("\nclosure4  ") && Contains("passes: consistent and white"));
  // Every row is written; closure3's 2 n + 3 p = 7 cells are empty from its row on, and only there.
  std::istringstream csv(pfgen_test::read_file(dir.file("out.csv")));
  std::string line;
  std::size_t rows = 0, emptied = 0;
  while (std::getline(csv, line)) {
    ++rows;
    if (line.find(",,,,,,,,") != std::string::npos) ++emptied;
  }
  CHECK(rows == 1002);
  CHECK(emptied == 1002 - 462 + 1);
  // Alone, its failure is the command's: exit 1, the row named, no CSV.
  const auto alone = pfgen_test::run_pfgen({"estimate", model, "--data", record, "--filters", "closure3", "-o",
                                            dir.file("alone.csv"), cache, "-q"});
  CHECK(alone.exit_code == 1);
  CHECK_THAT(alone.err, Contains(record + ":462: the filter 'closure3' failed: its moments left the realisable set"));
  CHECK(!std::filesystem::exists(dir.file("alone.csv")));
}

TEST_CASE("fit of a moment filter says where its likelihood ends: a profile interval's end at the filter's edge, "
          "an estimate at that edge", "[record][compiler]") {
  // The double well's record (tests/record_data/make_double_well_record.py): closure4 leaves its realisable set
  // for a small enough noise s, so the log-likelihood stops existing there. Beyond that edge nothing is inside
  // a likelihood interval, and an estimate against it is no maximum.
  TempDir dir;
  const std::string model = std::string(PFGEN_SOURCE_DIR) + "/examples/reference/double_well.yaml";
  const std::string record = std::string(PFGEN_SOURCE_DIR) + "/tests/data/double_well_increments.csv";
  std::istringstream lines(pfgen_test::read_file(record));
  std::string first_rows, line;
  for (int k = 0; k < 302 && std::getline(lines, line); ++k) first_rows += line + "\n";
  write_file(dir.file("dw.csv"), first_rows);
  const std::string cache = "--cache-dir=" + dir.file("cache");
  const auto profiled = pfgen_test::run_pfgen({"fit", model, "--data", dir.file("dw.csv"), "--filter", "closure4",
                                               "--estimate", "s", "--bounds", "s=0.1:2", "--profile", "-o",
                                               dir.file("fit.json"), cache, "-q"});
  INFO(profiled.out << profiled.err);
  REQUIRE(profiled.exit_code == 0);
  CHECK_THAT(profiled.out, Contains(" (the filter fails beyond), 2 (bound)]"));
  const std::string json = pfgen_test::read_file(dir.file("fit.json"));
  CHECK_THAT(json, Contains("\"profile_filter_fails_beyond\": [true, false]"));
  // The end is the edge, found independently by estimate: 1 % below it the filter fails, 1 % above it runs.
  const std::size_t at = json.find("\"profile\": [") + 12;
  const double low = std::stod(json.substr(at));
  REQUIRE(low > 0.1);
  auto run_at = [&](double s) {
    return pfgen_test::run_pfgen({"estimate", model, "--data", dir.file("dw.csv"), "--filters", "closure4", "--set",
                                  "s=" + std::to_string(s), cache, "-q"});
  };
  const auto below = run_at(0.99 * low);
  CHECK(below.exit_code == 1);
  CHECK_THAT(below.err, Contains("moments left the realisable set"));
  CHECK(run_at(1.01 * low).exit_code == 0);
  // Without bounds the first step out (the Wald half-width, 1.95) lands past the hole, at s < 0, where the
  // filter runs again (s enters as s^2): the search probes between its steps, so the same edge is found.
  const auto unbounded = pfgen_test::run_pfgen({"fit", model, "--data", dir.file("dw.csv"), "--filter", "closure4",
                                                "--estimate", "s", "--profile", cache, "-q"});
  INFO(unbounded.out);
  CHECK_THAT(unbounded.out, Contains("[0.211268 (the filter fails beyond), "));
  // An estimate held at a bound whose neighbour beyond it fails is at its bound, not at the filter's edge.
  const auto at_bound = pfgen_test::run_pfgen({"fit", model, "--data", record, "--filter", "closure4", "--estimate",
                                               "s", "--set", "c=0.443535", "--set", "r=0.488226", "--bounds",
                                               "s=0.4865:2", cache, "-q"});
  INFO(at_bound.out);
  CHECK_THAT(at_bound.out, Contains("(at its bound)"));
  CHECK(at_bound.out.find("edge") == std::string::npos);

  // Three parameters on the whole record: the optimiser stops against the edge; the report says so, names the
  // failing neighbour and gives no standard errors rather than calling the information not positive definite.
  const auto edge = pfgen_test::run_pfgen({"fit", model, "--data", record, "--filter", "closure4", "--estimate",
                                           "s,c,r", "-o", dir.file("edge.json"), cache, "-q"});
  INFO(edge.out << edge.err);
  REQUIRE(edge.exit_code == 0);
  CHECK_THAT(edge.out, Contains("the estimate is at the edge of where the filter runs, not at a maximum: the "
                                "log-likelihood cannot be evaluated next to it, at s = ") &&
                           Contains("the filter 'closure4' failed: its moments left the realisable set") &&
                           Contains("; no standard errors"));
  CHECK_THAT(pfgen_test::read_file(dir.file("edge.json")), Contains("\"at_edge_of_filter\": true"));

  // Profiling c from that estimate: the others' values there fail at once, so the search starts them elsewhere
  // too, and c's interval reaches below 0.2 (before, it ended at 0.27, marked as the filter's edge). Checked
  // apart: at c = 0.2, s refitted (from 0.6: at 0.5 the filter fails), the log-likelihood is within chi2_0.95(1)/2 = 1.92 of the maximum.
  const auto profiled_c = pfgen_test::run_pfgen({"fit", model, "--data", record, "--filter", "closure4", "--estimate",
                                                 "s,c", "--profile", "-o", dir.file("c.json"), cache, "-q"});
  INFO(profiled_c.out);
  REQUIRE(profiled_c.exit_code == 0);
  const std::string c_json = pfgen_test::read_file(dir.file("c.json"));
  const std::size_t c_at = c_json.find("\"name\": \"c\"");
  REQUIRE(c_at != std::string::npos);
  const double c_low = std::stod(c_json.substr(c_json.find("\"profile\": [", c_at) + 12));
  CHECK(c_low < 0.2);
  const double best = std::stod(c_json.substr(c_json.find("\"log_likelihood\": ") + 18));
  const auto at_c = pfgen_test::run_pfgen({"fit", model, "--data", record, "--filter", "closure4", "--estimate", "s",
                                           "--set", "c=0.2", "--set", "s=0.6", "-o", dir.file("c02.json"), cache,
                                           "-q"});
  INFO(at_c.out);
  REQUIRE(at_c.exit_code == 0);
  const std::string c02 = pfgen_test::read_file(dir.file("c02.json"));
  CHECK(std::stod(c02.substr(c02.find("\"log_likelihood\": ") + 18)) > best - 1.920729410347062);
}

TEST_CASE("the sampled moment filters over the Nile record are the Kalman filter's, log-likelihood and all",
          "[record][compiler]") {
  // A random walk sampled with Gaussian noise from a Gaussian prior: the law stays Gaussian, so cd-closure3 and
  // cd-closure4 carry M3 = 0 and M4 = 3 P^2 through every prediction and update and score as cd-optimal does.
  TempDir dir;
  const std::string model = std::string(PFGEN_SOURCE_DIR) + "/examples/records/nile.yaml";
  const std::string data = std::string(PFGEN_SOURCE_DIR) + "/examples/records/nile.csv";
  const auto ran = pfgen_test::run_pfgen({"estimate", model, "--data", data, "--time-column", "year", "--filters",
                                          "cd-optimal,cd-closure3,cd-closure4", "--cache-dir=" + dir.file("cache"), "-q"});
  INFO(ran.err);
  REQUIRE(ran.exit_code == 0);
  std::istringstream lines(ran.out);
  std::map<std::string, std::string> log_likelihood;
  for (std::string line; std::getline(lines, line);) {
    std::istringstream words(line);
    std::string filter, value;
    words >> filter >> value;
    if (filter.rfind("cd-", 0) == 0) log_likelihood[filter] = value;
  }
  REQUIRE(log_likelihood.size() == 3);
  CHECK(log_likelihood["cd-optimal"] == "-641.585578");
  CHECK(log_likelihood["cd-closure3"] == log_likelihood["cd-optimal"]);
  CHECK(log_likelihood["cd-closure4"] == log_likelihood["cd-optimal"]);
}

TEST_CASE("fit estimates a moment filter's prior mean: on the Nile, cd-closure4's fit is cd-optimal's",
          "[record][compiler]") {
  // The higher central moments of the prior N(m0, P0) do not depend on m0, so m0.X is estimated for a moment
  // filter as for the others (a delayed filter's history is what refuses it). On this linear Gaussian model
  // cd-closure4 carries M3 = 0 and M4 = 3 P^2, so its fit is cd-optimal's to the printed digit.
  TempDir dir;
  const std::string model = std::string(PFGEN_SOURCE_DIR) + "/examples/records/nile.yaml";
  const std::string data = std::string(PFGEN_SOURCE_DIR) + "/examples/records/nile.csv";
  auto fit = [&](const std::string& filter) {
    const auto r = pfgen_test::run_pfgen({"fit", model, "--data", data, "--time-column", "year", "--estimate",
                                          "q,h,m0.x", "--filter", filter, "-q", "--cache-dir=" + dir.file("cache")});
    INFO(r.err);
    REQUIRE(r.exit_code == 0);
    return r.out.substr(r.out.find('\n'));  // after the line naming the filter
  };
  const std::string optimal = fit("cd-optimal");
  CHECK_THAT(optimal, Contains("m0.x "));
  CHECK(fit("cd-closure4") == optimal);
}

TEST_CASE("simulate runs the sampled moment filters with their moments: closer to the particle reference than "
          "cd-optimal on a bistable state",
          "[record][compiler]") {
  // Their higher moments ride along as extra state through the sub-steps and the updates; on the bistable
  // example (20 seeded runs, 500 particles) the order-4 filter is the closest to the reference's conditional mean.
  TempDir dir;
  const std::string model = std::string(PFGEN_SOURCE_DIR) + "/examples/sampled/bistable_sampled.yaml";
  const auto result = pfgen_test::run_pfgen({"simulate", model, "--filters", "cd-optimal,cd-closure3,cd-closure4",
                                             "--runs", "20", "--x0", "prior", "--reference", "particles:500",
                                             "--threads", "2", "--cache-dir=" + dir.file("cache"), "-q"});
  INFO(result.err);
  REQUIRE(result.exit_code == 0);
  CHECK_THAT(result.out, Contains("Closest in x: cd-closure4 "));
  CHECK_THAT(result.out, !Contains("left the realisable set"));  // no run stopped
  CHECK_THAT(result.out, Contains("Truth diverged: no run"));
}

TEST_CASE("simulate stops a moment filter's run where its moments leave the realisable set, in its own section",
          "[record][compiler]") {
  // The double well's closure4 leaves the realisable set (a state's Pearson bound) in most runs; the plugin hands
  // simulate its margins, and each such run is stopped, counted as diverged and listed in the section; the stops
  // CSV names each such run's event `unrealisable`.
  TempDir dir;
  const std::string model = std::string(PFGEN_SOURCE_DIR) + "/examples/reference/double_well.yaml";
  const auto result = pfgen_test::run_pfgen({"simulate", model, "--filters", "optimal,closure3,closure4", "--runs", "20",
                                             "--threads", "2", "--stops-csv", dir.file("stops.csv"),
                                             "--cache-dir=" + dir.file("cache"), "-q"});
  INFO(result.err);
  REQUIRE(result.exit_code == 0);
  CHECK_THAT(result.out, Contains("Runs stopped where a moment filter's moments left the realisable set"));
  CHECK_THAT(result.out, Contains("  closure4: 14 runs"));
  CHECK_THAT(result.out, Contains("  closure3: 15 runs"));
  const std::size_t section = result.out.find("left the realisable set");
  CHECK(result.out.find("  optimal: ", section) == std::string::npos);  // the Gaussian closure has no margins
  std::map<std::string, int> events;  // "source,event" -> rows
  std::istringstream stops(pfgen_test::read_file(dir.file("stops.csv")));
  std::string line;
  std::getline(stops, line);
  CHECK(line == "source,event,run,t");
  while (std::getline(stops, line)) ++events[line.substr(0, line.find(',', line.find(',') + 1))];
  CHECK(events["closure4,unrealisable"] == 14);
  CHECK(events["closure3,unrealisable"] == 15);
  CHECK(events.size() == 2);  // no other stop, and no `diverged` row for a realisability stop
}
