// rationalize_decimal_literals: every number of an expression becomes its exact rational before
// GiNaC's parser reads it (0.1 is 1/10, not a double). Plain literals of up to 18 digits take a
// path in 64-bit integers, longer ones and exponents the CLN path: both are checked against values
// worked out by hand.
#include <catch2/catch.hpp>

#include "pfgen/model/decimal_literals.hpp"

TEST_CASE("decimal literals: exact rationals, reduced, on both paths", "[model_loading][unit]") {
  const std::vector<std::pair<std::string, std::string>> cases = {
      {"0.3", "(3/10)"},
      {"12", "(12)"},
      {"1.25", "(5/4)"},
      {"007", "(7)"},
      {"5.", "(5)"},
      {".5", "(1/2)"},
      {"0.000", "(0)"},
      {"0.30", "(3/10)"},
      {"123456789012345678", "(123456789012345678)"},      // 18 digits: the integer path
      {"1234567890123456789", "(1234567890123456789)"},    // 19 digits: the CLN path
      {"100.0000000000000001", "(1000000000000000001/10000000000000000)"},
      {"0.1e-2", "(1/1000)"},
      {"2.50E+1", "(25)"},
      {"x1*0.25 + y_2 - 3*x10^2", "x1*(1/4) + y_2 - (3)*x10^(2)"},
  };
  for (const auto& [text, expected] : cases) {
    INFO(text);
    CHECK(pfgen::rationalize_decimal_literals(text) == expected);
  }
}
