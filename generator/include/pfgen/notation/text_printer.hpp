#pragma once
// Plain text in the syntax of model files: 0.1*m1^2 + 0.1*P11. Text output
// parses back with GiNaC's parser (and pfgen's model reader).
#include "pfgen/notation/expression_printer.hpp"

namespace pfgen {

class TextPrinter : public ExpressionPrinter {
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

}  // namespace pfgen
