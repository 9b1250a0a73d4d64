// scripts/reproduce-paper004.sh with small settings (2 runs, dt = 0.01: the delay is 80 steps): its
// parsing and layout, and the facts that do not depend on the number of runs (the as-printed truth
// blows up before t = 1; the variant's truth is the paper's printed x(1), x(2), x(4)). The figures
// of the full run are in docs/reproductions/basin-rodriguez-gonzalez-martinez-zuniga-2004.md.
#include <catch2/catch.hpp>

#include <regex>
#include <string>

#include "support/cli_helpers.hpp"

using namespace pfgen_test;

TEST_CASE("paper 004: the reproduction script prints both parts and the verdict with small settings",
          "[simulate][delay][paper004][compiler]") {
  TempDir dir;
  const auto result = run_program({"env", "PFGEN=" + pfgen_executable(), "THREADS=1",
                                   source_dir() + "/scripts/reproduce-paper004.sh", "2", "0.01", dir.file("out")});
  INFO(result.out << result.err);
  REQUIRE(result.exit_code == 0);
  CHECK(result.out.find("delay 0.8 = 80 steps") != std::string::npos);
  // As printed, every truth stops near t = 1/1.1.
  CHECK(std::regex_search(result.out, std::regex(R"(Truth diverged: 2 of 2 runs, first at t = 0\.9)")));
  // The variant's deterministic truth at t = 1, 2, 4 is the paper's to its three decimals.
  CHECK(std::regex_search(result.out, std::regex(R"(x, ours \(deterministic\)\s+1\.221\s+1\.372\s+1\.565\s+1\.821)")));
  // Every filter has an estimate with a standard error at t = 1.
  for (const char* label : {"m  delay-optimal (eqs 17-18)", "m1 delay-uncorrected (eqs 19-20)",
                            "m2 delay-ekf (textbook 4 m P)", "m2 ekf-printed (eq 22 scaled: 0.18 P)"}) {
    INFO(label);
    // The label as a literal, then a number, "±" and its standard error.
    const std::string literal = std::regex_replace(label, std::regex(R"([()*+.])"), R"(\$&)");
    CHECK(std::regex_search(result.out, std::regex(literal + R"(\s+-?[0-9.]+(e-?[0-9]+)? ± [0-9.e+-]+)")));
  }
  CHECK(result.out.find("m, paper") != std::string::npos);
  CHECK(std::regex_search(result.out, std::regex(R"(In all: delay-optimal better in [0-9]+, worse in [0-9]+ of 16)")));
}
