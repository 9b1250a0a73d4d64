// The risk-sensitive kind does what it is for, through the whole chain (derive, generate, compile,
// simulate, J): on examples/leqg_tracking.yaml (linear, so the kind is the LEQG filter) it trades
// mean-square error for the exponential criterion. With eps = 3 (theta = 2/3) and 3000 seeded runs,
// Kalman-Bucy (pfgen's optimal) has the smaller mean int |x - m|^2 dt, and the risk-sensitive filter
// the smaller J, each by several standard errors (measured: J 18.6 +- 0.3 against 20.6 +- 0.7, mean
// int L 14.15 +- 0.07 against 13.13 +- 0.09). With eps large the two agree.
#include <catch2/catch.hpp>

#include <map>
#include <sstream>
#include <string>
#include <vector>

#include "support/cli_helpers.hpp"

using namespace pfgen_test;

namespace {

// filter -> column -> value, from simulate's --criterion-csv.
std::map<std::string, std::map<std::string, double>> criterion_rows(const std::string& csv) {
  std::istringstream in(csv);
  std::string line;
  std::getline(in, line);
  std::vector<std::string> header;
  std::stringstream h(line);
  for (std::string cell; std::getline(h, cell, ',');) header.push_back(cell);
  std::map<std::string, std::map<std::string, double>> out;
  while (std::getline(in, line)) {
    std::stringstream row(line);
    std::string filter, cell;
    std::getline(row, filter, ',');
    for (std::size_t k = 1; std::getline(row, cell, ',') && k < header.size(); ++k)
      if (!cell.empty()) out[filter][header[k]] = std::stod(cell);
  }
  return out;
}

}  // namespace

TEST_CASE("risk-sensitive (LEQG) filter has the smaller J and Kalman-Bucy the smaller mean-square error",
          "[risk][simulate][compiler]") {
  TempDir dir;
  auto run = [&](const std::string& eps) {
    const std::string csv = dir.file("j" + eps + ".csv");
    const ProcessResult r = run_pfgen({"simulate", example("leqg_tracking.yaml"), "--cache-dir", dir.file("cache"),
                                       "--runs", "3000", "--set", "eps=" + eps, "--criterion-csv", csv, "-q"});
    INFO(r.err);
    REQUIRE(r.exit_code == 0);
    return criterion_rows(read_file(csv));
  };
  auto rows = run("3");
  const auto& kb = rows.at("optimal");
  const auto& rs = rows.at("risk-sensitive");
  CHECK(rs.at("stopped") == 0);
  CHECK(kb.at("J") - rs.at("J") > 2 * (kb.at("J_se") + rs.at("J_se")) / 2);
  CHECK(rs.at("mean_integral") - kb.at("mean_integral") > 5 * (kb.at("mean_integral_se") + rs.at("mean_integral_se")));
  // eps = 1000: theta = 0.002, the filters (and so J) agree to well within a standard error.
  rows = run("1000");
  CHECK(std::abs(rows.at("optimal").at("J") - rows.at("risk-sensitive").at("J")) < 0.1 * rows.at("optimal").at("J_se"));
}
