// The public C++ API's estimate and fit (<pfgen/pfgen.hpp>): the report, CSV and JSON are the
// commands' bytes on the Nile record and on the Van der Pol sensor's increments, the same data
// given in memory gives the same numbers, and bad records and options are refused with one line.
#include <catch2/catch.hpp>

#include <cmath>
#include <sstream>

#include "pfgen/pfgen.hpp"
#include "support/cli_helpers.hpp"

namespace api = pfgen::api;
using Catch::Matchers::Contains;
using pfgen_test::TempDir;

namespace {

const std::string kSource = PFGEN_SOURCE_DIR;

// The command's stdout without its "Wrote FILE" lines (which the API has no file to write).
std::string without_wrote(const std::string& out) {
  std::istringstream lines(out);
  std::string line, kept;
  while (std::getline(lines, line))
    if (line.rfind("Wrote ", 0) != 0) kept += line + "\n";
  return kept;
}

// A record CSV read back as the API's in-memory data (every cell a number or empty).
api::RecordData csv_data(const std::string& path) {
  std::istringstream lines(pfgen_test::read_file(path));
  std::string line;
  api::RecordData data;
  std::getline(lines, line);
  std::istringstream header(line);
  for (std::string name; std::getline(header, name, ',');) data.columns.push_back(name);
  while (std::getline(lines, line)) {
    api::Vector row;
    std::istringstream cells(line + ",");
    for (std::string cell; std::getline(cells, cell, ',');) row.push_back(cell.empty() ? std::nan("") : std::stod(cell));
    data.rows.push_back(row);
  }
  return data;
}

struct Case {
  std::string model, data, time_column;
  std::vector<std::string> filters;
};

void same_as_the_command(const Case& c, const std::string& cache) {
  TempDir dir;
  std::vector<std::string> arguments{"estimate", c.model, "--data", c.data, "--time-column", c.time_column,
                                     "-o", dir.file("out.csv"), "--full-covariance", "--cache-dir=" + cache, "-q"};
  if (!c.filters.empty()) arguments.push_back("--filters=" + c.filters.front());
  const auto command = pfgen_test::run_pfgen(arguments);
  REQUIRE(command.exit_code == 0);

  const api::Model model = api::Model::load(c.model);
  api::EstimateOptions options;
  options.record.data_path = c.data;
  options.record.time_column = c.time_column;
  options.record.cache_dir = cache;
  options.filters = c.filters;
  options.full_covariance = true;
  options.series = true;
  const api::EstimateResult file = model.estimate(options);
  CHECK(file.report == without_wrote(command.out));
  CHECK(file.csv == pfgen_test::read_file(dir.file("out.csv")));
  REQUIRE(!file.filters.empty());
  CHECK(file.report.find(file.filters.front().verdict) != std::string::npos);

  // In memory, named as the file: the same bytes; and the numbers of the CSV's cells.
  options.record.data = csv_data(c.data);
  const api::EstimateResult memory = model.estimate(options);
  CHECK(memory.report == file.report);
  CHECK(memory.csv == file.csv);
  REQUIRE(memory.columns == file.columns);
  for (std::size_t k = 0; k < file.columns.size(); ++k) {
    INFO(file.columns[k]);
    REQUIRE(memory.series[k].size() == file.series[k].size());
    for (std::size_t r = 0; r < file.series[k].size(); ++r)
      if (!std::isnan(file.series[k][r])) CHECK(memory.series[k][r] == file.series[k][r]);
  }
  for (std::size_t f = 0; f < file.filters.size(); ++f) {
    CHECK(memory.filters[f].log_likelihood == file.filters[f].log_likelihood);
    CHECK(memory.filters[f].ljung_box_p == file.filters[f].ljung_box_p);
  }
}

}  // namespace

TEST_CASE("public API: estimate gives the command's report and CSV, from a file or from memory", "[api][compiler]") {
  TempDir cache;
  same_as_the_command({kSource + "/examples/records/nile.yaml", kSource + "/examples/records/nile.csv", "year", {}},
                      cache.file("plugins"));
  same_as_the_command({kSource + "/examples/van_der_pol.yaml", kSource + "/examples/records/van_der_pol_increments.csv",
                       "t", {"ekf"}},
                      cache.file("plugins"));

  // The scores are the table's: Nile's cd-optimal row, a sampled record (no increments' density).
  const api::Model nile = api::Model::load(kSource + "/examples/records/nile.yaml");
  api::EstimateOptions options;
  options.record.data_path = kSource + "/examples/records/nile.csv";
  options.record.time_column = "year";
  options.record.cache_dir = cache.file("plugins");
  const api::EstimateResult result = nile.estimate(options);
  REQUIRE(result.filters.size() >= 1);
  const api::RecordScores& s = result.filters.front();
  CHECK(s.count == 100);
  CHECK(std::isnan(s.increment_log_density));
  CHECK(s.ljung_box_lags == std::vector<std::size_t>{10});
  CHECK(s.consistent == (s.mean_square >= s.band_low && s.mean_square <= s.band_high));
  CHECK(result.csv.empty());  // series not asked for
  CHECK(result.time_column == "year");
  CHECK(result.observation_columns == std::vector<std::string>{"volume"});
}

TEST_CASE("public API: fit gives the command's report and JSON", "[api][compiler]") {
  TempDir dir;
  const std::string model_path = kSource + "/examples/records/nile.yaml", data = kSource + "/examples/records/nile.csv";
  const auto command = pfgen_test::run_pfgen({"fit", model_path, "--data", data, "--time-column", "year", "--estimate",
                                             "h", "--bounds", "h=0:", "--profile", "-o", dir.file("fit.json"),
                                             "--cache-dir=" + dir.file("cache"), "-q"});
  REQUIRE(command.exit_code == 0);
  api::FitOptions options;
  options.record.data_path = data;
  options.record.time_column = "year";
  options.record.cache_dir = dir.file("cache");
  options.estimate = {"h"};
  options.bounds = {{"h", 0, HUGE_VAL}};
  options.profile = true;
  const api::Model model = api::Model::load(model_path);
  const api::FitResult fit = model.fit(options);
  CHECK(fit.report == without_wrote(command.out));
  CHECK(fit.json == pfgen_test::read_file(dir.file("fit.json")));
  REQUIRE(fit.converged);
  REQUIRE(fit.parameters.size() == 1);
  const api::FittedParameter& h = fit.parameters.front();
  CHECK(h.name == "h");
  CHECK(h.profile_low < h.estimate);
  CHECK(h.estimate < h.profile_high);
  CHECK(fit.aic == Approx(2 - 2 * fit.log_likelihood).epsilon(1e-15));

  // The same record from arrays: the same estimate.
  const api::RecordData memory = csv_data(data);
  api::Vector times;
  api::Matrix values;
  for (const api::Vector& row : memory.rows) {
    times.push_back(row[0]);
    values.push_back({row[1]});
  }
  options.record.data = api::RecordData::from_arrays(times, values, {"volume"}, "year");
  options.record.data_path.clear();
  const api::FitResult arrays = model.fit(options);
  CHECK(arrays.parameters.front().estimate == h.estimate);
  CHECK(arrays.json == fit.json);
  CHECK_THAT(arrays.report, Contains("to <data> (100 rows)"));
}

TEST_CASE("public API: estimate and fit refuse a bad record or option with the command's line", "[api][compiler]") {
  TempDir dir;
  const api::Model model = api::Model::load(kSource + "/examples/records/nile.yaml");
  api::EstimateOptions options;
  options.record.cache_dir = dir.file("cache");
  auto refusal = [&](const api::EstimateOptions& o) {
    try {
      model.estimate(o);
    } catch (const api::Error& e) {
      return e.report();
    }
    return std::string("no error");
  };
  CHECK(refusal(options) == "error: --data: give the record: a CSV file's path, or the data in memory");
  options.record.data = api::RecordData::from_arrays({0, 1, 1}, {{1}, {2}, {3}});
  CHECK(refusal(options) ==
        "error: <data> row 3: column 't': the time 1 does not come after the previous row's (1): times must increase");
  options.record.data = api::RecordData::from_arrays({0, 1}, {{1}, {HUGE_VAL}});
  CHECK(refusal(options) == "error: <data> row 2: column 'y1': inf is not a finite number");
  options.record.data = api::RecordData::from_arrays({0, 1}, {{1}, {2}});
  options.record.time_column = "year";
  CHECK(refusal(options) == "error: <data>: the header has no time column 'year' (its columns: t, y1)");
  options.record.data = api::RecordData{{"t", "a,b"}, {{0, 1}}};
  options.record.time_column = "t";
  CHECK_THAT(refusal(options), Contains("holds a comma, quote or line break"));
  options.record.data = api::RecordData{{"t", "y"}, {{0, 1}, {1}}};
  CHECK(refusal(options) == "error: <data> row 2: the row has 1 values, the header 2");
  CHECK_THROWS_WITH(api::RecordData::from_arrays({0, 1}, {{1}}), "--data: 2 times but 1 rows of observations");

  api::FitOptions fit;
  fit.record.data_path = kSource + "/examples/records/nile.csv";
  fit.record.time_column = "year";
  fit.record.cache_dir = dir.file("cache");
  fit.estimate = {"q"};
  fit.bounds = {{"q", 0, 10}};
  CHECK_THROWS_WITH(model.fit(fit), "--bounds: q's bounds exclude its start 1469.1 (the model's value, or --set's)");
  fit.bounds = {{"q", std::nan(""), 10}};
  CHECK_THROWS_WITH(model.fit(fit), Contains("--bounds q: 'nan' is outside the range of a double"));
}
