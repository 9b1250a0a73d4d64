// `pfgen simulate` of models with sampled observations, end to end (plugin compiled): on a
// linear-Gaussian model cd-optimal's Monte Carlo errors match its own P at a sample time and
// between samples; output is the same for any thread count; a period that is not a whole number
// of steps is a one-line error; the paper-003 script's tables run with small settings.
#include <catch2/catch.hpp>

#include <algorithm>
#include <cmath>
#include <regex>
#include <sstream>

#include "support/cli_helpers.hpp"

using namespace pfgen_test;

namespace {

const char* const kLinearModel = R"(name: sampled_ou
states: [x]
drift: ["-0.5*x"]
diffusion: [["1"]]
observation:
  sampled: {period: 0.5, C: [["2"]], Uv: [["1"]], substeps: 20}
initial: {x0: [0], m0: [0], P0: [[1]]}
)";

// Column `name` of the CSV row whose t equals `t` (written as shortest round-trip numbers).
double csv_value(const std::string& csv, const std::string& name, const std::string& t) {
  std::istringstream in(csv);
  std::string line;
  std::getline(in, line);
  std::vector<std::string> header;
  std::stringstream h(line);
  for (std::string cell; std::getline(h, cell, ',');) header.push_back(cell);
  std::size_t column = header.size();
  for (std::size_t c = 0; c < header.size(); ++c)
    if (header[c] == name) column = c;
  REQUIRE(column < header.size());
  while (std::getline(in, line)) {
    std::vector<std::string> cells;
    std::stringstream row(line);
    for (std::string cell; std::getline(row, cell, ',');) cells.push_back(cell);
    if (!cells.empty() && cells[0] == t) return std::stod(cells.at(column));
  }
  FAIL("no CSV row at t = " << t);
  return 0;
}

// The table's mean |e| at report time t for filter f (the "|e|@t" columns, in order).
double mean_abs_error(const std::string& table, const std::string& filter, std::size_t report) {
  std::istringstream in(table);
  std::string line;
  while (std::getline(in, line)) {
    std::istringstream cells(line);
    std::vector<std::string> row;
    for (std::string cell; cells >> cell;) row.push_back(cell);
    if (row.size() > 4 + report && row[0] == filter && row[1] == "x") return std::stod(row[3 + report]);
  }
  FAIL("no row for " << filter);
  return 0;
}

}  // namespace

TEST_CASE("simulate sampled: cd-optimal's Monte Carlo |e| matches its own P at a sample and between samples", "[simulate][sampled][compiler]") {
  TempDir dir;
  write_file(dir.file("ou.yaml"), kLinearModel);
  const auto result =
      run_pfgen({"simulate", dir.file("ou.yaml"), "--cache-dir", dir.file("cache"), "--filters", "cd-optimal",
                 "--runs", "2000", "--T", "10.25", "--dt", "0.01", "--report-times", "10,10.25", "--record-points",
                 "2000", "-o", dir.file("r.csv"), "-q"});
  REQUIRE(result.exit_code == 0);
  INFO(result.out);
  const std::string csv = read_file(dir.file("r.csv"));
  // P does not depend on the data in a linear model: the shown run's P is every run's.
  const double P_sample = csv_value(csv, "cd-optimal_P_x", "10");      // m(t_k|t_k): after the update
  const double P_between = csv_value(csv, "cd-optimal_P_x", "10.25");  // predicted half a period on
  CHECK(P_between > 1.2 * P_sample);
  // Gaussian errors: E|e| = sqrt(2 P / pi); relative standard error of the mean |e| over 2000
  // runs is sqrt(pi/2 - 1) / sqrt(2000) = 1.7 %: 4 standard errors.
  const double tolerance = 4 * std::sqrt(M_PI / 2 - 1) / std::sqrt(2000.0);
  CHECK(mean_abs_error(result.out, "cd-optimal", 0) == Approx(std::sqrt(2 * P_sample / M_PI)).epsilon(tolerance));
  CHECK(mean_abs_error(result.out, "cd-optimal", 1) == Approx(std::sqrt(2 * P_between / M_PI)).epsilon(tolerance));
  CHECK(result.out.find("AvRMSE clean") != std::string::npos);
}

TEST_CASE("simulate sampled: the same output for any thread count, KIND@S sub-steps, and one-line errors", "[simulate][sampled][compiler]") {
  TempDir dir;
  auto run = [&](const std::string& threads, const std::string& csv) {
    return run_pfgen({"simulate", example("allahyani_date_example1_gamma05.yaml"), "--cache-dir", dir.file("cache"),
                      "--filters", "cd-optimal,cd-ekf,cd-euler@1,cd-euler@5", "--runs", "6", "--T", "20", "--dt",
                      "0.1", "--threads", threads, "-o", dir.file(csv), "-q"});
  };
  const auto one = run("1", "one.csv"), three = run("3", "three.csv");
  REQUIRE(one.exit_code == 0);
  REQUIRE(three.exit_code == 0);
  auto without_csv_line = [](std::string text) { return std::regex_replace(text, std::regex("csv: .*\n"), ""); };
  CHECK(without_csv_line(one.out) == without_csv_line(three.out));
  CHECK(read_file(dir.file("one.csv")) == read_file(dir.file("three.csv")));
  CHECK(one.out.find("cd-euler@5") != std::string::npos);

  const auto bad_dt = run_pfgen({"simulate", example("allahyani_date_example1_gamma05.yaml"), "--cache-dir",
                                 dir.file("cache"), "--runs", "2", "--T", "3", "--dt", "0.3"});
  CHECK(bad_dt.exit_code != 0);
  CHECK(bad_dt.err.find("not a whole number of steps") != std::string::npos);
  CHECK(std::count(bad_dt.err.begin(), bad_dt.err.end(), '\n') == 1);
  const auto bad_name = run_pfgen({"simulate", example("allahyani_date_example1_gamma05.yaml"), "--cache-dir",
                                   dir.file("cache"), "--filters", "cd-euler@0"});
  CHECK(bad_name.exit_code != 0);
  CHECK(std::count(bad_name.err.begin(), bad_name.err.end(), '\n') == 1);
}

TEST_CASE("simulate sampled: the paper 003 script prints Tables I-III in both readings with small settings", "[simulate][sampled][paper003][compiler]") {
  TempDir dir;
  // 2 runs on dt = 0.5 (the samples stay at T = 1): the script's parsing and layout, not the figures.
  const auto result = run_program({"env", "PFGEN=" + pfgen_executable(), "THREADS=1",
                                   source_dir() + "/scripts/reproduce-paper003.sh", "2", "0.5", dir.file("out")});
  INFO(result.out << result.err);
  REQUIRE(result.exit_code == 0);
  for (const char* title : {"Table I (Delta = 1/5), Y = C x(t_k), noise-free", "Table II (Delta = 1/10), Y = y_k",
                            "Table III (example 2, Delta = 1/10), Y = C x(t_k)"})
    CHECK(result.out.find(title) != std::string::npos);
  // Every filter's row has a figure for gamma = 0 (no '-' cell) in Table I.
  const std::regex row(R"(AvRMSE DDF \(cd-euler@1\)\s+[0-9.]+ ± [0-9.e-]+)");
  CHECK(std::regex_search(result.out, row));
  CHECK(result.out.find("AvMRAE cd-optimal") != std::string::npos);
  CHECK(result.out.find("State-error RMS") != std::string::npos);
  // Example 2 with gamma = 0.5: every truth stopped where G lost definiteness.
  CHECK(result.out.find("example 2, gamma index 1: 0 runs counted; truth diverged: 2 of 2 runs") != std::string::npos);
}
