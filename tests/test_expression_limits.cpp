// The limits on one expression (pfgen/model/expression_limits.hpp) at their edges: what is just
// inside passes, what is just beyond is refused with its reason, and text that is no expression
// is left to GiNaC's parser.
#include <catch2/catch.hpp>

#include <string>

#include "pfgen/model/expression_limits.hpp"

using pfgen::expression_limit_problem;

namespace {
std::string repeat(const std::string& text, int times) {
  std::string out;
  for (int k = 0; k < times; ++k) out += text;
  return out;
}
std::string problem(const std::string& text) { return expression_limit_problem(text).value_or("none"); }
}  // namespace

TEST_CASE("expression limits: nesting of parentheses, signs and exponents", "[expression_limits][unit]") {
  CHECK(problem(repeat("(", 256) + "x" + repeat(")", 256)) == "none");
  CHECK(problem(repeat("(", 257) + "x" + repeat(")", 257)) == "expression nests deeper than 256 parentheses");
  CHECK(problem(repeat("sin(", 257) + "t" + repeat(")", 257)) == "expression nests deeper than 256 parentheses");
  CHECK(problem(repeat("-", 256) + "x") == "none");
  CHECK(problem(repeat("- ", 257) + "x") == "expression nests signs and exponents deeper than 256 levels");
  CHECK(problem(repeat("x^-", 257) + "x") == "expression nests signs and exponents deeper than 256 levels");
  // A long flat sum nests nothing.
  CHECK(problem(repeat("x + ", 20000) + "x") == "none");
}

TEST_CASE("expression limits: length", "[expression_limits][unit]") {
  const std::string longest = repeat("x+", 49999) + "xx";
  REQUIRE(longest.size() == pfgen::kMaxExpressionLength);
  CHECK(problem(longest) == "none");
  CHECK(problem(longest + "x") == "expression is longer than 100000 characters");
}

TEST_CASE("expression limits: digits of numbers, estimated before GiNaC computes them", "[expression_limits][unit]") {
  CHECK(problem("x*10^9999") == "none");
  CHECK(problem("x*1e9999") == "none");
  CHECK(problem("x*2^33000") == "none");  // 9934 digits
  CHECK(problem("-x*2^34000") == "'2^34000' gives a number of about 1.02e+04 digits; numbers are limited to 10000 digits");
  CHECK(problem("x*1e9999*1e9999").find("gives a number of about 2e+04 digits") != std::string::npos);
  CHECK(problem("x*(1e9999)^(1/2)") == "none");
  CHECK(problem("2^(-2^40)*x").find("'2^(-2^40)' gives a number of about 3.31e+11 digits") == 0);
  // Long literals count their digits; a NaN exponent in doubles (inf - inf) counts as infinite.
  CHECK(problem("x*" + repeat("7", 9000)) == "none");
  CHECK(problem("x*" + repeat("7", 10001)).find("gives a number of about 1e+04 digits") != std::string::npos);
  CHECK(problem("x*0." + repeat("0", 4000) + "1") == "none");
  CHECK(problem("2^(1e400 - 1e399)*x").find("'2^(1e400 - 1e399)' gives a number of more than 1e+308 digits") == 0);
  // Rationals count numerator and denominator: 1.0000001^100000 = 10000001^100000 / 10^700000.
  CHECK(problem("1.0000001^500*x") == "none");  // about 7000 digits
  CHECK(problem("1.0000001^100000*x").find("gives a number of about 1.4e+06 digits") != std::string::npos);
  // Powers of sums: the binomial coefficients of (x+1)^n have up to n log10 2 digits.
  CHECK(problem("(x+1)^1000") == "none");
  CHECK(problem("(x+1)^40000").find("'(x+1)^40000' gives a number of about 1.2e+04 digits") == 0);
  // Symbolic powers are not evaluated: the degree limit refuses x^(2^40) later.
  CHECK(problem("x^(2^40)") == "none");
  CHECK(problem("2^x") == "none");
  CHECK(problem("exp(1)^(10^10)*x") == "none");
  // Functions GiNaC evaluates exactly at whole numbers.
  CHECK(problem("factorial(1000)*x") == "none");
  CHECK(problem("factorial(100000)*x").find("'factorial(100000)' gives a number of about 5e+05 digits") == 0);
  CHECK(problem("zeta(100000)").find("'zeta(100000)'") == 0);
  CHECK(problem("zeta(60)*x") == "none");
  CHECK(problem("zeta(66*040)*x").find("'zeta(66*040)' gives a number of about 1.19e+07 digits") == 0);
  CHECK(problem("sin(100000)") == "none");
  // A call without arguments crashed GiNaC's evaluation.
  CHECK(problem("x + exp()") == "'exp()': a function needs an argument");
  CHECK(problem("sin( )*x") == "'sin()': a function needs an argument");
  // Not an expression: GiNaC's parser names the syntax error.
  CHECK(problem("x +* 2") == "none");
  CHECK(problem("-(x + 1") == "none");
}
