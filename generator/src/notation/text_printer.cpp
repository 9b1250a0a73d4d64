#include "pfgen/notation/text_printer.hpp"

#include <sstream>

#include "pfgen/notation/number_format.hpp"

namespace pfgen {

std::string TextPrinter::number(const GiNaC::numeric& value) const {
  if (!value.is_rational()) return shortest_double(value.to_double());
  std::string decimal = exact_decimal(value);
  if (!decimal.empty()) return decimal;
  std::ostringstream out;
  out << value.numer() << "/" << value.denom();
  return out.str();
}

std::string TextPrinter::symbol_name(const std::string& name) const { return name; }

std::string TextPrinter::power(const std::string& base, const std::string& exponent) const {
  bool plain = exponent.find_first_not_of("0123456789") == std::string::npos;
  return base + "^" + (plain ? exponent : "(" + exponent + ")");
}

void TextPrinter::append_factors(std::string& out, const std::string* const* factors, std::size_t count) const {
  for (std::size_t k = 0; k < count; ++k) {
    const std::string& factor = *factors[k];
    if (k) out += '*';
    // A fraction coefficient needs parentheses to stay one factor: (1/3)*m1.
    bool fraction = factor.find('/') != std::string::npos && factor.front() != '(';
    if (fraction && count > 1) {
      out += '(';
      out += factor;
      out += ')';
    } else {
      out += factor;
    }
  }
}

std::string TextPrinter::quotient(const std::string& numerator, const std::string& denominator) const {
  bool single = denominator.find_first_of("*/") == std::string::npos;
  return numerator + "/" + (single ? denominator : "(" + denominator + ")");
}

std::string TextPrinter::function_call(const std::string& name, const std::vector<std::string>& args) const {
  std::string out = name + "(";
  for (std::size_t k = 0; k < args.size(); ++k) out += (k ? ", " : "") + args[k];
  return out + ")";
}

std::string TextPrinter::parenthesized(const std::string& inner) const { return "(" + inner + ")"; }

std::string TextPrinter::constant(const GiNaC::ex& c) const {
  std::ostringstream out;
  out << c;
  return out.str();
}

}  // namespace pfgen
