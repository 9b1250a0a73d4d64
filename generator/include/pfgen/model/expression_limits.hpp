#pragma once
// Limits on one expression's text, checked before GiNaC parses or evaluates it (docs/guide/model-file.md,
// limits). GiNaC's parser recurses once per parenthesis, sign and exponent, so 10000
// nested parentheses or 100000 unary minuses overflowed the stack (signal 11); and GiNaC evaluates
// numeric powers at once, so -2^(2^40)*x or ((1e9999)^1000)^1000 ran for minutes or aborted in
// GMP. Each limit gives one reason, which the parser reports with the file, field, row and column.
#include <cstddef>
#include <optional>
#include <string>

namespace pfgen {

inline constexpr std::size_t kMaxExpressionLength = 100000;  // characters
inline constexpr int kMaxParenthesisDepth = 256;             // nested ( ), function calls included
inline constexpr int kMaxOperatorNesting = 256;              // nested signs and exponents: - - x, 2^-2^-x
inline constexpr double kMaxConstantDigits = 10000;          // decimal digits of any number it gives

// Why `text` is beyond a limit, or nullopt. The number of digits is estimated from the text
// (log10 of numerators and denominators, times the exponent for a power, plus the growth of
// multinomial coefficients for a power of a sum), an upper estimate for the numbers that GiNaC's
// evaluation and the derivation's expansion make from it. Text that is not a valid expression
// passes, for GiNaC's parser to explain.
std::optional<std::string> expression_limit_problem(const std::string& text);

}  // namespace pfgen
