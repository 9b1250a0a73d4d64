#include "pfgen/notation/number_format.hpp"

#include <cmath>
#include <cstdio>
#include <sstream>

namespace pfgen {

std::string exact_decimal(const GiNaC::numeric& value) {
  if (!value.is_rational()) return {};
  GiNaC::numeric denominator = value.denom();
  int twos = 0, fives = 0;
  while (GiNaC::mod(denominator, 2).is_zero()) { denominator /= 2; ++twos; }
  while (GiNaC::mod(denominator, 5).is_zero()) { denominator /= 5; ++fives; }
  if (denominator != 1) return {};
  const int places = std::max(twos, fives);
  if (places > 30) return {};
  GiNaC::numeric scaled = GiNaC::abs(value) * GiNaC::numeric(10).power(GiNaC::numeric(places));
  std::ostringstream digits_stream;
  digits_stream << scaled;  // an integer by construction
  std::string digits = digits_stream.str();
  if (places > 0) {
    if (static_cast<int>(digits.size()) <= places) digits.insert(0, places + 1 - digits.size(), '0');
    digits.insert(digits.size() - places, ".");
  }
  return (value.is_negative() ? "-" : "") + digits;
}

std::string three_digits(double value) {
  char buffer[32];
  std::snprintf(buffer, sizeof buffer, "%.3g", value);
  return buffer;
}

}  // namespace pfgen
