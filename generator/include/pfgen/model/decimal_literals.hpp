#pragma once
// Decimal literals such as 0.1 or 2.5e-3 are exact rationals in pfgen: the
// derived coefficients (0.03 = 3/100 in paper 000 eq 22) must compare exactly
// with published equations, which floating-point GiNaC numerics would not.
#include <ginac/ginac.h>
#include <optional>
#include <string>

namespace pfgen {

// Rewrites every numeric literal in `expression` as a parenthesised exact
// rational "(N/D)", leaving identifiers such as x1 or a2b untouched.
std::string rationalize_decimal_literals(const std::string& expression);

// Parses one real number ("-1.5", "2", "1e-3") exactly; nullopt if `text` is not one.
std::optional<GiNaC::numeric> parse_exact_number(const std::string& text);

// Why parse_exact_number refused `text`, beginning with "is": a well-formed number whose exponent
// is too long to read exactly (1e5000000000000) is out of double's range; anything else is not a
// number.
std::string unread_number_problem(const std::string& text);

// Why an exact number cannot become a double, or nothing: a nonzero value below the smallest
// normal double (about 2.2e-308; 1e-400 would be 0 in generated code and simulation) or beyond the
// largest (about 1.8e308). The text begins with "is", for "'1e-400' is ...".
std::optional<std::string> double_range_problem(const GiNaC::numeric& value);

// A number's order of magnitude for a message: 1/10^400 as 1.0E-400, not as its 401 digits
// (GiNaC's float, which has no range limit, not a double, which would print it as 0).
std::string approximate_text(const GiNaC::numeric& value);

}  // namespace pfgen
