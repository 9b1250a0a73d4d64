#pragma once
// LaTeX math: 0.1\,m_{1}^{2} + 0.1\,P_{11}; rationals as \frac, Greek names as
// Greek letters, multi-letter names upright, x_1 style names subscripted.
#include "pfgen/notation/expression_printer.hpp"

namespace pfgen {

class LatexPrinter : public ExpressionPrinter {
 public:
  std::string name(const std::string& identifier) const { return symbol_name(identifier); }

 protected:
  std::string number(const GiNaC::numeric& non_negative) const override;
  std::string symbol_name(const std::string& name) const override;
  std::string power(const std::string& base, const std::string& exponent) const override;
  void append_factors(std::string& out, const std::string* const* factors, std::size_t count) const override;
  std::string quotient(const std::string& numerator, const std::string& denominator) const override;
  std::string function_call(const std::string& name, const std::vector<std::string>& args) const override;
  std::string parenthesized(const std::string& inner) const override;
  std::string constant(const GiNaC::ex& c) const override;
};

// Escapes text-mode special characters (& % $ # _ { } ~ ^ \) for prose around the math, and
// writes < > | " ` and -- so that they print as written in the document's OT1 fonts.
std::string latex_escape_text(const std::string& text);

}  // namespace pfgen
