#pragma once
#include <ginac/ginac.h>
#include <string>

#include "pfgen_support/shortest_double.hpp"

namespace pfgen {

// A rational whose denominator has only the prime factors 2 and 5 (3/100,
// 1/8) is written as the exact decimal ("0.03", "0.125"); other rationals
// return an empty string and are printed as fractions by the caller.
std::string exact_decimal(const GiNaC::numeric& value);

// A double as the shortest text that reads back as the same double ("%.17g" at most): the
// support library's (pfgen_support/shortest_double.hpp), shared with the runtime.
using pfgen_support::shortest_double;

// A measured or estimated double in three significant digits ("2.5", "0.0123", "1.7e+05"), for
// messages and report lines that state a rate or a size, not a value to read back.
std::string three_digits(double value);

}  // namespace pfgen
