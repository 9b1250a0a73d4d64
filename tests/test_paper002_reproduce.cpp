// scripts/reproduce-paper002.sh with small settings (Tables 1, 2 and 4, their first eps, gamma = 1,
// 8 runs, dt = 0.01): its parsing and layout, the initial matrices it repairs and derives, and part 2's
// run of the invalid printed P(0) and Q(0). The figures of the full run are in docs/reproductions/alcorta-garcia-2011.md.
#include <catch2/catch.hpp>

#include <array>
#include <cstdio>
#include <regex>
#include <string>

#include "support/cli_helpers.hpp"

using namespace pfgen_test;

TEST_CASE("paper 002: the reproduction script prints Tables 1, 2 and 4 and part 2 with small settings",
          "[simulate][paper002][compiler]") {
  TempDir dir;
  const auto result = run_program({"env", "PFGEN=" + pfgen_executable(), "THREADS=1", "CASES=reactor1 reactor2 satellite1",
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
  CHECK(std::regex_search(result.out, std::regex("\n1 +505\\.8493 +" + J + " +" + J + " +705\\.1152@1\\.64 +" + J + " +" + J +
                                                 " +686\\.3813@0\\.28 +" + J + " +" + J + " +[0-9]+\n")));
  CHECK(std::regex_search(result.out,
                          std::regex("\n0\\.01 +0\\.3239 +" + J + " +" + J + " +2\\.0321 +" + J + " +" + J + " +[0-9]+\n")));
  // Every job of a row saw the same truths (the script compares them and stops otherwise).
  CHECK(result.out.find("Truths: the same in every job of each of the 3 rows") != std::string::npos);
  CHECK(std::regex_search(result.out, std::regex(R"(holds, on our runs, in [0-9]+ of 5 comparisons)")));
  // Part 2: each invalid printed matrix through its printed filter, beside the repaired start.
  CHECK(std::regex_search(result.out, std::regex("\nreactor1 +rs-printed +0\\.1 +" + J + " +" + J)));
  CHECK(std::regex_search(result.out, std::regex("\nreactor2 +ekf-printed +1 +" + J + " +" + J)));
  CHECK(std::regex_search(result.out, std::regex("\nsatellite1 +poly-printed +0\\.01 +" + J + " +" + J)));
}

namespace {

// (21)'s printed Q equations ("Q11^2 Q12^2" read as Q11^2 + Q12^2), which do not read C or dY.
std::array<double, 3> printed_dQ(const std::array<double, 3>& Q) {
  const double q11 = Q[0], q12 = Q[1], q22 = Q[2];
  return {4 * q11 + q11 * q11 + q12 * q12 - 1, 3 * q12 + q11 + q11 * q12 - q12 * q22,
          2 * q22 - 2 * q12 + q12 * q12 + q22 * q22 - 1};
}

// The first t where det Q = 0 on (21)'s own Q equations from Q(0), by classical Runge-Kutta in Q
// itself (not through pfgen, which integrates P = -eps Q^-1).
double printed_Q_singular_time(std::array<double, 3> Q) {
  const double h = 1e-5;
  auto plus = [](std::array<double, 3> a, const std::array<double, 3>& b, double c) {
    for (int k = 0; k < 3; ++k) a[k] += c * b[k];
    return a;
  };
  for (double t = 0; t < 2; t += h) {
    const auto k1 = printed_dQ(Q), k2 = printed_dQ(plus(Q, k1, h / 2)), k3 = printed_dQ(plus(Q, k2, h / 2)),
               k4 = printed_dQ(plus(Q, k3, h));
    for (int k = 0; k < 3; ++k) Q[k] += h / 6 * (k1[k] + 2 * k2[k] + 2 * k3[k] + k4[k]);
    if (Q[0] * Q[2] - Q[1] * Q[1] <= 0) return t + h;
  }
  return -1;
}

}  // namespace

// (21) as printed (the example's rs-printed) cannot run to T: its Q leaves the negative definite
// matrices, whatever the data, where its C equation divides by det Q = 0 and P = -eps Q^-1 is
// unbounded. pfgen's run of it stops every run there; the time is checked against a direct
// integration of the printed Q equations.
TEST_CASE("paper 002: (21) as printed stops every run where its own Q becomes singular",
          "[simulate][paper002][compiler]") {
  const double singular = printed_Q_singular_time({-6, 1e-4, -7});  // reactor case 3's Q(0)
  CHECK(singular == Approx(0.3824).margin(0.0005));
  // P(0) = -eps Q(0)^-1 at eps = 1.
  const double det = 42 - 1e-8;
  char initial[200];
  std::snprintf(initial, sizeof initial, "initial: {x0: [0.05, 50], m0: [1, 5], P0: [[%.17g, %.17g], [%.17g, %.17g]]}",
                7 / det, 1e-4 / det, 1e-4 / det, 6 / det);
  std::string model = read_file(source_dir() + "/examples/paper002/reactor.yaml");
  model = std::regex_replace(model, std::regex("\ninitial:[^\n]*"), std::string("\n") + initial);
  TempDir dir;
  write_file(dir.file("reactor.yaml"), model);
  const auto result = run_pfgen({"simulate", dir.file("reactor.yaml"), "--filters", "rs-printed", "--set", "eps=1",
                                 "--runs", "20", "--T", "1", "--dt", "0.001", "--threads", "1", "-q"});
  INFO(result.out << result.err);
  REQUIRE(result.exit_code == 0);
  std::smatch row;  // filter, state, ..., diverged, div first t, div median t
  REQUIRE(std::regex_search(result.out, row, std::regex(R"(\nrs-printed +x1 .* 20 +([0-9.]+) +([0-9.]+) +0 +-\n)")));
  CHECK(std::stod(row[1]) == Approx(singular).margin(0.005));
  CHECK(std::stod(row[2]) == Approx(singular).margin(0.005));
}
