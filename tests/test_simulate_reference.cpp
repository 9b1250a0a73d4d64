// `pfgen simulate --reference particles:N` end to end (docs/theory.md §7.4): bad values are
// one-line errors naming --reference; the reference's table, CSV and plot are the same for any
// thread count, for continuous and sampled observations; a model without process noise gets one
// note and exactly the outputs of a run without --reference.
#include <catch2/catch.hpp>

#include <regex>
#include <string>
#include <vector>

#include "support/cli_helpers.hpp"

using namespace pfgen_test;

namespace {

std::vector<std::string> simulate_args(const std::string& model, const TempDir& dir,
                                       std::initializer_list<std::string> more) {
  std::vector<std::string> args{"simulate", example(model), "--cache-dir", dir.file("cache")};
  args.insert(args.end(), more.begin(), more.end());
  return args;
}

}  // namespace

TEST_CASE("simulate --reference: bad values are one-line errors naming --reference, before any build",
          "[simulate][particles][bad_input][integration]") {
  TempDir dir;
  const std::vector<std::pair<std::string, std::string>> cases{
      {"particles:0", "--reference: 'particles:0' asks for no particles"},
      {"particles:abc", "--reference: 'abc' in 'particles:abc' is not a whole number"},
      {"particles:", "--reference: '' in 'particles:' is not a whole number"},
      {"particles:-5", "--reference: '-5' in 'particles:-5' is not a whole number"},
      {"particles:1e3", "--reference: '1e3' in 'particles:1e3' is not a whole number"},
      {"foo:10", "--reference: 'foo:10' is not a known reference"},
      {"particles:99999999999", "--reference: 99999999999 particles are more than the 1000000 allowed"},
      {"particles:1000001", "--reference: 1000001 particles are more than the 1000000 allowed"},
      {"particles:0000000000000000000000099999999999999999999", "particles are more than the 1000000 allowed"},
  };
  for (const auto& [value, message] : cases) {
    const auto result = run_pfgen(simulate_args("reference/double_well.yaml", dir, {"--reference", value}));
    INFO(value << ": " << result.err);
    CHECK(result.exit_code != 0);
    CHECK(result.out.empty());
    CHECK(count_lines(result.err) == 1);
    CHECK(result.err.find(message) != std::string::npos);
    CHECK(result.err.find("write particles:N") != std::string::npos);
  }
  CHECK(dir.entries() == std::vector<std::string>{});  // refused before the build: no cache
}

TEST_CASE("simulate --reference: identical table and CSV for 1 and 2 threads, and the plot draws the reference",
          "[simulate][particles][compiler]") {
  TempDir dir;
  auto run = [&](const std::string& threads, const std::string& csv) {
    return run_pfgen(simulate_args("reference/double_well.yaml", dir,
                                   {"--runs", "4", "--T", "1", "--dt", "1e-2", "--threads", threads, "--reference",
                                    "particles:200", "-o", dir.file(csv)}));
  };
  const auto one = run("1", "one.csv");
  const auto two = run("2", "two.csv");
  REQUIRE(one.exit_code == 0);
  REQUIRE(two.exit_code == 0);
  INFO(one.out << one.err);
  CHECK(without_csv_line(one.out) == without_csv_line(two.out));
  CHECK(read_file(dir.file("one.csv")) == read_file(dir.file("two.csv")));
  CHECK(one.out.find("Distance to the particle reference (N = 200 particles") != std::string::npos);
  CHECK(std::regex_search(one.out, std::regex("\noptimal +x1 +4 +[0-9.e-]+ ")));
  // The reference's row: its own Monte Carlo error (from the second particle set), then its RMS error.
  CHECK(std::regex_search(one.out, std::regex("\nreference +x2 +4 +[0-9.e-]+ +[0-9.e-]+ ± [0-9.e-]+\n")));
  CHECK(std::regex_search(one.err, std::regex("particle reference \\(N = 200\\): [0-9.]+ thread-s")));
  const std::string header = read_file(dir.file("one.csv")).substr(0, read_file(dir.file("one.csv")).find('\n'));
  CHECK(header.find(",reference_m_x1,reference_err_x1,reference_err_x1_rms,") != std::string::npos);
  CHECK(header.find(",optimal_dref_x2,optimal_dref_x2_rms") != std::string::npos);

  const auto plotted = run_pfgen(simulate_args("reference/double_well.yaml", dir,
                                               {"--runs", "2", "--T", "1", "--dt", "1e-2", "--reference",
                                                "particles:50", "--plot", dir.file("e.svg"), "-q"}));
  REQUIRE(plotted.exit_code == 0);
  CHECK(read_file(dir.file("e.svg.gp")).find("title 'reference (N=50)'") != std::string::npos);
  CHECK(read_file(dir.file("e.svg")).find("reference (N=50)") != std::string::npos);
}

TEST_CASE("simulate --reference: skipped with one note for a truth without process noise or delayed observations, outputs unchanged",
          "[simulate][particles][compiler]") {
  TempDir dir;
  auto run = [&](std::initializer_list<std::string> more, const std::string& csv) {
    std::vector<std::string> args =
        simulate_args("basin_skliar_partial.yaml", dir, {"--runs", "2", "--T", "2", "--dt", "1e-2", "-q", "-o", dir.file(csv)});
    args.insert(args.end(), more.begin(), more.end());
    return run_pfgen(args);
  };
  const auto plain = run({}, "plain.csv");
  const auto referenced = run({"--reference", "particles:100"}, "referenced.csv");
  REQUIRE(plain.exit_code == 0);
  REQUIRE(referenced.exit_code == 0);
  INFO(referenced.err);
  CHECK(referenced.err == plain.err + "pfgen: --reference: skipped, the truth has no process noise (g = 0): the particles would "
                          "never spread, so their weights would collapse onto one\n");
  auto without_csv_line = [](std::string text) { return std::regex_replace(text, std::regex("csv: .*\n"), ""); };
  CHECK(without_csv_line(plain.out) == without_csv_line(referenced.out));
  CHECK(read_file(dir.file("plain.csv")) == read_file(dir.file("referenced.csv")));

  // Delayed observations likewise.
  auto delayed = [&](std::initializer_list<std::string> more) {
    std::vector<std::string> args = simulate_args("delay_linear.yaml", dir, {"--runs", "2", "--T", "1", "-q"});
    args.insert(args.end(), more.begin(), more.end());
    return run_pfgen(args);
  };
  const auto delayed_plain = delayed({});
  const auto delayed_referenced = delayed({"--reference", "particles:100"});
  REQUIRE(delayed_plain.exit_code == 0);
  REQUIRE(delayed_referenced.exit_code == 0);
  CHECK(delayed_referenced.err ==
        delayed_plain.err + "pfgen: --reference: skipped, the observations are delayed, and the reference weighs "
                            "undelayed ones only\n");
  CHECK(delayed_referenced.out == delayed_plain.out);
}

TEST_CASE("simulate --reference: sampled observations (paper 003) get the reference too, the same for 1 and 2 threads",
          "[simulate][particles][compiler]") {
  TempDir dir;
  auto run = [&](const std::string& threads) {
    return run_pfgen(simulate_args("paper003/example1_gamma0.yaml", dir,
                                   {"--runs", "3", "--T", "5", "--dt", "1e-2", "--threads", threads, "--reference",
                                    "particles:300", "-q"}));
  };
  const auto one = run("1");
  const auto two = run("2");
  REQUIRE(one.exit_code == 0);
  REQUIRE(two.exit_code == 0);
  INFO(one.out << one.err);
  CHECK(one.err.find("skipped") == std::string::npos);  // no skip note
  // x0 = 1 against m0 = 0: the note that the reference is the conditional mean for prior draws only.
  CHECK(one.err.find("note: --reference: every run's truth starts at x0 = (1)") != std::string::npos);
  CHECK(one.out == two.out);
  CHECK(one.out.find("Distance to the particle reference (N = 300 particles") != std::string::npos);
  CHECK(std::regex_search(one.out, std::regex("\ncd-optimal +x +3 +[0-9.e-]+ ")));
}
