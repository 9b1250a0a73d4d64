#pragma once
// The check that `pfgen simulate`'s results do not depend on the thread count, for tests that run
// the real program.
#include <catch2/catch.hpp>

#include <string>
#include <vector>

#include "support/cli_helpers.hpp"

namespace pfgen_test {

// `pfgen ARGS --threads 1`, then `--threads 2`, each writing `option` FILE into `dir` (one.csv,
// two.csv): both must succeed and give the same stdout, but for the line naming the file, and the
// same file, byte for byte. Returns the one-thread run.
inline ProcessResult same_for_1_and_2_threads(const TempDir& dir, const std::vector<std::string>& args,
                                              const std::string& option = "-o") {
  auto run = [&](const char* threads, const std::string& file) {
    std::vector<std::string> argv = args;
    argv.insert(argv.end(), {"--threads", threads, option, dir.file(file)});
    return run_pfgen(argv);
  };
  const ProcessResult one = run("1", "one.csv"), two = run("2", "two.csv");
  INFO(one.err);
  REQUIRE(one.exit_code == 0);
  REQUIRE(two.exit_code == 0);
  CHECK(without_csv_line(one.out) == without_csv_line(two.out));
  CHECK(read_file(dir.file("one.csv")) == read_file(dir.file("two.csv")));
  return one;
}

}  // namespace pfgen_test
