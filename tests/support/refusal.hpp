#pragma once
// The check of a refused command line: `pfgen ARGUMENTS` exits 1 with exactly one line on stderr,
// which contains `message` (how every error of pfgen's is reported, docs/guide/commands.md).
#include <catch2/catch.hpp>

#include <string>
#include <vector>

#include "support/cli_helpers.hpp"

namespace pfgen_test {

inline void check_refused_in_one_line(const std::vector<std::string>& arguments, const std::string& message) {
  const auto result = run_pfgen(arguments);
  CHECK(result.exit_code == 1);
  CHECK_THAT(result.err, Catch::Matchers::Contains(message));
  CHECK(count_lines(result.err) == 1);
}

}  // namespace pfgen_test
