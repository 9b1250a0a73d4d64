#pragma once
// A double as the shortest text that reads back (strtod) as the same double. Two spellings
// exist, both round-trip, and each output keeps the one it has always had (outputs are
// byte-stable):
//   shortest_double: printf's %g at the least precision that round-trips (%.17g at most), so
//     exponents look like "1e-05" and 20 is "2e+01"; 0 and -0 are "0". The generator's notation:
//     text, LaTeX, JSON and the literals of generated C++.
//   shortest_chars: std::to_chars, fixed or scientific whichever is shorter, so 20 is "20" and
//     -0 is "-0". The runtime's CSV and the command line's messages about settings.
// NaN and infinities are written as the C library writes them ("nan", "inf"); callers that must
// not print them check first.
#include <string>

namespace pfgen_support {

std::string shortest_double(double value);
std::string shortest_chars(double value);

// printf's %f (six decimals), the form tables and messages have always shown, up to 1e15 in
// magnitude; beyond, %g, since the fixed form would print dozens or hundreds of digits (a
// log-likelihood of -5.7e53, an eigenvalue of 1e200).
std::string fixed_unless_huge(double value);

}  // namespace pfgen_support
