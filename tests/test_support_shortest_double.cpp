// Shortest round-trip text of a double (pfgen_support/shortest_double.hpp), in both spellings:
// each must read back exactly, and no shorter text of the same kind may.
#include <catch2/catch.hpp>

#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <limits>
#include <random>
#include <string>

#include "pfgen_support/shortest_double.hpp"

using namespace pfgen_support;

namespace {

std::string g_format(double value, int precision) {
  char buffer[400];  // room for any precision, to keep -Wformat-truncation quiet
  std::snprintf(buffer, sizeof buffer, "%.*g", precision, value);
  return buffer;
}

// Doubles with every exponent: random bit patterns, skipping NaN and infinities.
double random_double(std::mt19937_64& rng) {
  for (;;) {
    const std::uint64_t bits = rng();
    double value;
    std::memcpy(&value, &bits, sizeof value);
    if (std::isfinite(value)) return value;
  }
}

}  // namespace

TEST_CASE("support: shortest_double is printf %g at the least precision that round-trips", "[unit][support]") {
  CHECK(shortest_double(0.0) == "0");
  CHECK(shortest_double(-0.0) == "0");
  CHECK(shortest_double(0.1) == "0.1");
  CHECK(shortest_double(-2.5) == "-2.5");
  CHECK(shortest_double(1e-5) == "1e-05");
  CHECK(shortest_double(20) == "2e+01");  // %g's choice at precision 1: the generator's notation
  CHECK(shortest_double(1.0 / 3) == "0.3333333333333333");
  CHECK(shortest_double(0.1 + 0.2) == "0.30000000000000004");
  CHECK(shortest_double(std::numeric_limits<double>::max()) == "1.7976931348623157e+308");
  CHECK(shortest_double(std::numeric_limits<double>::denorm_min()) == "5e-324");
  std::mt19937_64 rng(9);
  for (int k = 0; k < 20000; ++k) {
    const double value = random_double(rng);
    const std::string text = shortest_double(value);
    INFO(g_format(value, 17) << " -> " << text);
    REQUIRE(std::strtod(text.c_str(), nullptr) == value);
    if (value == 0) continue;
    int precision = 1;  // the precision that made `text`
    while (g_format(value, precision) != text) ++precision;
    REQUIRE(precision <= 17);
    if (precision > 1) REQUIRE(std::strtod(g_format(value, precision - 1).c_str(), nullptr) != value);
  }
}

TEST_CASE("support: shortest_chars is std::to_chars, fixed or scientific whichever is shorter", "[unit][support]") {
  CHECK(shortest_chars(0.0) == "0");
  CHECK(shortest_chars(-0.0) == "-0");
  CHECK(shortest_chars(20) == "20");
  CHECK(shortest_chars(9.2) == "9.2");
  CHECK(shortest_chars(1e-3) == "0.001");  // a tie in length goes to fixed
  CHECK(shortest_chars(1e-4) == "1e-04");
  CHECK(shortest_chars(1e-5) == "1e-05");
  CHECK(shortest_chars(1e8) == "1e+08");
  CHECK(shortest_chars(123456789) == "123456789");
  CHECK(shortest_chars(std::numeric_limits<double>::lowest()) == "-1.7976931348623157e+308");
  std::mt19937_64 rng(10);
  for (int k = 0; k < 20000; ++k) {
    const double value = random_double(rng);
    const std::string text = shortest_chars(value);
    INFO(g_format(value, 17) << " -> " << text);
    REQUIRE(std::strtod(text.c_str(), nullptr) == value);
    // Never longer than the %g spelling: to_chars chooses the shorter layout of the fewest digits.
    if (value != 0) REQUIRE(text.size() <= shortest_double(value).size());
  }
}
