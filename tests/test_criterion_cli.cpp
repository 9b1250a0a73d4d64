// `pfgen simulate` with the exponential criterion J: --risk-epsilon adds the section (the same
// bytes for any --threads) and --criterion-csv its CSV; bad values are one-line errors before
// anything is built.
#include <catch2/catch.hpp>

#include <regex>
#include <string>
#include <vector>

#include "support/cli_helpers.hpp"
#include "support/same_for_threads.hpp"

using namespace pfgen_test;

namespace {

std::vector<std::string> simulate_args(const std::string& model, const TempDir& dir,
                                       std::initializer_list<std::string> more) {
  std::vector<std::string> args{"simulate", model, "--cache-dir", dir.file("cache")};
  args.insert(args.end(), more.begin(), more.end());
  return args;
}

}  // namespace

TEST_CASE("simulate --risk-epsilon: J per filter, identical for 1 and 2 threads, and its CSV",
          "[criterion][simulate][compiler]") {
  TempDir dir;
  const ProcessResult one = same_for_1_and_2_threads(
      dir,
      simulate_args(example("basin2006_quadratic.yaml"), dir,
                    {"--runs", "6", "--T", "1", "--dt", "1e-3", "--filters", "optimal,ekf", "--risk-epsilon", "0.5", "-q"}),
      "--criterion-csv");
  CHECK(one.out.find("Exponential criterion J = eps log E[exp(int_0^T L dt / eps)], eps = 0.5, L = (x - m)^T M (x - "
                     "m), M = identity") != std::string::npos);
  // One row per filter: name, runs, J (a number), ...
  CHECK(std::regex_search(one.out, std::regex(R"(\noptimal\s+6\s+[0-9.e+-]+\s)")));
  CHECK(std::regex_search(one.out, std::regex(R"(\nekf\s+6\s+[0-9.e+-]+\s)")));
  const std::string csv = read_file(dir.file("one.csv"));
  CHECK(csv.rfind("filter,epsilon,runs,completed,J,", 0) == 0);
  CHECK(csv.find("\noptimal,0.5,6,6,") != std::string::npos);
  CHECK(one.out.find("criterion csv: " + dir.file("one.csv")) != std::string::npos);

  // Without it, no section (the other outputs are checked byte for byte by the golden tests).
  const auto plain = run_pfgen(simulate_args(example("basin2006_quadratic.yaml"), dir,
                                             {"--runs", "6", "--T", "1", "--dt", "1e-3", "--filters", "optimal,ekf",
                                              "--threads", "1", "-q"}));
  REQUIRE(plain.exit_code == 0);
  CHECK(plain.out.find("Exponential criterion") == std::string::npos);
  const std::size_t start = one.out.find("\nExponential criterion J"), end = one.out.find("\nTruth diverged");
  REQUIRE(start != std::string::npos);
  CHECK(std::regex_replace(one.out.substr(0, start) + one.out.substr(end), std::regex("criterion csv: .*\n"), "") ==
        plain.out);
}

TEST_CASE("simulate: bad criterion options are one-line errors naming the option, before the build",
          "[criterion][simulate][bad_input][integration]") {
  TempDir dir;
  struct Case {
    std::vector<std::string> args;
    std::string message;
  };
  const std::vector<Case> cases{
      {{"--risk-epsilon", "0"}, "--risk-epsilon: '0' is not a finite number > 0"},
      {{"--risk-epsilon", "-2"}, "--risk-epsilon: '-2' is not a finite number > 0"},
      {{"--criterion-csv", dir.file("j.csv")}, "--criterion-csv: no criterion J to write; give --risk-epsilon"},
      {{"--risk-epsilon", "1", "--criterion-csv", dir.file("missing/j.csv")}, "does not exist"},
      {{"--risk-epsilon", "1", "-o", dir.file("j.csv"), "--criterion-csv", dir.file("j.csv")}, "--criterion-csv"},
  };
  for (const Case& c : cases) {
    std::vector<std::string> args{"simulate", example("basin2006_quadratic.yaml"), "--cache-dir", dir.file("cache")};
    args.insert(args.end(), c.args.begin(), c.args.end());
    const auto result = run_pfgen(args);
    INFO(result.err);
    CHECK(result.exit_code != 0);
    CHECK(result.out.empty());
    CHECK(count_lines(result.err) == 1);
    CHECK(result.err.find(c.message) != std::string::npos);
  }
  CHECK(dir.entries() == std::vector<std::string>{});
}

TEST_CASE("simulate: the model's risk: section asks for J; --set changes its eps, --risk-epsilon overrides it, "
          "its weight is used and named",
          "[criterion][simulate][compiler]") {
  TempDir dir;
  const std::string model = dir.file("risky.yaml");
  write_file(model, read_file(example("basin2006_quadratic.yaml")) +
                        "\nparameters: {k_eps: 1}\nrisk:\n  epsilon: 4*k_eps\n  weight: [[2]]\n");
  auto run = [&](std::initializer_list<std::string> more) {
    std::vector<std::string> args{"simulate", model, "--cache-dir", dir.file("cache"), "--runs", "4", "--T", "0.5",
                                  "--dt", "1e-3", "--filters", "optimal", "--threads", "1", "-q"};
    args.insert(args.end(), more.begin(), more.end());
    return run_pfgen(args);
  };
  const auto file = run({});
  INFO(file.err);
  REQUIRE(file.exit_code == 0);
  CHECK(file.out.find("eps = 4, L = (x - m)^T M (x - m), M = [2]") != std::string::npos);
  const auto set = run({"--set", "k_eps=0.25"});
  REQUIRE(set.exit_code == 0);
  CHECK(set.out.find("eps = 1, L = (x - m)^T M (x - m), M = [2]") != std::string::npos);
  const auto cli = run({"--risk-epsilon", "7"});
  REQUIRE(cli.exit_code == 0);
  CHECK(cli.out.find("eps = 7, L = (x - m)^T M (x - m), M = [2]") != std::string::npos);
  const auto bad = run({"--set", "k_eps=-1"});
  CHECK(bad.exit_code != 0);
  CHECK(count_lines(bad.err) == 1);
  CHECK(bad.err.find("risk.epsilon") != std::string::npos);
}
