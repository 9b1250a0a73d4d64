#pragma once
// A double as the exact rational it is (mantissa times a power of two), so that GiNaC evaluates at
// the very point a compiled program gets and the tests compare exact values rounded once.
#include <cmath>

#include <ginac/ginac.h>

namespace pfgen_test {

inline GiNaC::numeric exact(double value) {
  int exponent = 0;
  const double mantissa = std::frexp(value, &exponent);
  const auto integer = static_cast<long long>(std::ldexp(mantissa, 53));
  return GiNaC::numeric(std::to_string(integer).c_str()) * GiNaC::numeric(2).power(exponent - 53);
}

}  // namespace pfgen_test
