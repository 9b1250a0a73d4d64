// scripts/reproduce-paper002.sh with small settings (Table 2 and Table 4, their first eps, gamma = 1,
// 8 runs, dt = 0.01): its parsing and layout, the initial matrices it repairs and derives, and part 2's
// run of the indefinite printed P(0). The figures of the full run are in the README ("Paper 002").
#include <catch2/catch.hpp>

#include <regex>
#include <string>

#include "support/cli_helpers.hpp"

using namespace pfgen_test;

TEST_CASE("paper 002: the reproduction script prints Tables 2 and 4 and part 2 with small settings",
          "[simulate][paper002][compiler]") {
  TempDir dir;
  const auto result = run_program({"env", "PFGEN=" + pfgen_executable(), "THREADS=1", "CASES=reactor2 satellite1",
                                   "READINGS=gamma1", "EPS_COUNT=1", source_dir() + "/scripts/reproduce-paper002.sh",
                                   "8", "0.01", dir.file("out")});
  INFO(result.out << result.err);
  REQUIRE(result.exit_code == 0);
  // The repairs of the indefinite printed matrices (nearest positive semi-definite) and the
  // risk-sensitive filter's Q(0), with the printed ones beside them.
  CHECK(result.out.find("K-B m(0) = (1, 5), P(0) = (2.327476988 4.842606428 10.07564727) [printed (2 5 10)]") !=
        std::string::npos);
  CHECK(result.out.find("Pol m(0) = (0.92, 0.5), P(0) = (15.54295247 13.72104204 12.11269196) [printed (10 20 5)]") !=
        std::string::npos);
  CHECK(result.out.find("R-S C(0) = (1, 5), Q(0) = (-7 0.0001 -7.5)") != std::string::npos);
  // One row per table: eps, the paper's J, then ours with a standard error (or the stop marker).
  const std::string J = R"(((-?[0-9.]+(e[-+]?[0-9]+)? ± [0-9.e+-]+!?|-)( \[[0-9]+ stop @[0-9.e-]+\])?))";
  CHECK(std::regex_search(result.out, std::regex("\n1 +505\\.8493 +" + J + " +705\\.1152@1\\.64 +" + J + " +" + J +
                                                 " +686\\.3813@0\\.28 +" + J + " +" + J + " +[0-9]+\n")));
  CHECK(std::regex_search(result.out,
                          std::regex("\n0\\.01 +0\\.3239 +" + J + " +2\\.0321 +" + J + " +" + J + " +[0-9]+\n")));
  // Every job of a row saw the same truths (the script compares them and stops otherwise).
  CHECK(result.out.find("Truths: the same in every job of each of the 2 rows") != std::string::npos);
  CHECK(std::regex_search(result.out, std::regex(R"(holds, on our runs, in [0-9]+ of 3 comparisons)")));
  // Part 2: each indefinite printed P(0) through its printed filter, beside the repaired start.
  CHECK(std::regex_search(result.out, std::regex("\nreactor2 +ekf-printed +1 +" + J + " +" + J)));
  CHECK(std::regex_search(result.out, std::regex("\nsatellite1 +poly-printed +0\\.01 +" + J + " +" + J)));
}
