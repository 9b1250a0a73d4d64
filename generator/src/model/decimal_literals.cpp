#include "pfgen/model/decimal_literals.hpp"

#include <cctype>
#include <cstdint>
#include <cstdio>
#include <cstdlib>
#include <limits>
#include <numeric>
#include <sstream>
#include <stdexcept>

namespace pfgen {
namespace {

bool is_identifier_char(char c) {
  return std::isalnum(static_cast<unsigned char>(c)) || c == '_';
}

// Scans a numeric literal starting at `pos`; returns its length (0 if none).
std::size_t scan_number(const std::string& s, std::size_t pos) {
  std::size_t i = pos;
  bool digits = false;
  while (i < s.size() && std::isdigit(static_cast<unsigned char>(s[i]))) { ++i; digits = true; }
  if (i < s.size() && s[i] == '.') {
    ++i;
    while (i < s.size() && std::isdigit(static_cast<unsigned char>(s[i]))) { ++i; digits = true; }
  }
  if (!digits) return 0;
  if (i < s.size() && (s[i] == 'e' || s[i] == 'E')) {
    std::size_t j = i + 1;
    if (j < s.size() && (s[j] == '+' || s[j] == '-')) ++j;
    std::size_t exponent_start = j;
    while (j < s.size() && std::isdigit(static_cast<unsigned char>(s[j]))) ++j;
    if (j > exponent_start) i = j;
  }
  return i - pos;
}

// Exact value of an unsigned literal already known to be well formed.
GiNaC::numeric literal_value(const std::string& literal) {
  std::string mantissa = literal;
  long exponent = 0;
  std::size_t e = literal.find_first_of("eE");
  if (e != std::string::npos) {
    mantissa = literal.substr(0, e);
    // Bounded so that 1e99999999999 is refused instead of exhausting memory.
    std::string digits = literal.substr(e + 1);
    std::size_t first = digits.find_first_not_of("+-0");
    if (first != std::string::npos && digits.size() - first > 4)
      throw std::out_of_range("the exponent of '" + literal + "' is too large");
    exponent = std::stol(digits);
  }
  std::string digits;
  for (char c : mantissa) {
    if (c == '.') {
      continue;
    }
    digits += c;
  }
  std::size_t dot = mantissa.find('.');
  if (dot != std::string::npos) exponent -= static_cast<long>(mantissa.size() - dot - 1);
  // Strip leading zeros so CLN does not read the digits as octal.
  std::size_t first = digits.find_first_not_of('0');
  digits = first == std::string::npos ? "0" : digits.substr(first);
  GiNaC::numeric value(digits.c_str());
  GiNaC::numeric ten(10);
  if (exponent > 0) value *= ten.power(GiNaC::numeric(exponent));
  if (exponent < 0) value /= ten.power(GiNaC::numeric(-exponent));
  return value;
}

// Appends "(n)" or "(n/d)", the reduced value of a literal of digits with at most one '.' and at
// most 18 digits (the common case: 0.3, 12, 1.25), as the general path below writes it, in 64-bit
// integers instead of CLN numbers and a stream; false, appending nothing, for any other literal.
bool append_small_decimal(const std::string& s, std::size_t pos, std::size_t length, std::string& out) {
  std::uint64_t numerator = 0, denominator = 1;
  std::size_t digits = 0;
  bool after_dot = false;
  for (std::size_t i = pos; i < pos + length; ++i) {
    const char c = s[i];
    if (c == '.') {
      after_dot = true;
      continue;
    }
    if (!std::isdigit(static_cast<unsigned char>(c)) || ++digits > 18) return false;
    numerator = numerator * 10 + static_cast<std::uint64_t>(c - '0');
    if (after_dot) denominator *= 10;
  }
  const std::uint64_t common = std::gcd(numerator, denominator);  // gcd(0, d) = d: 0/1
  out += '(';
  out += std::to_string(numerator / common);
  if (denominator / common != 1) {
    out += '/';
    out += std::to_string(denominator / common);
  }
  out += ')';
  return true;
}

}  // namespace

std::string rationalize_decimal_literals(const std::string& expression) {
  std::string out;
  out.reserve(expression.size() * 2);
  std::size_t i = 0;
  while (i < expression.size()) {
    char c = expression[i];
    if (std::isalpha(static_cast<unsigned char>(c)) || c == '_') {
      std::size_t j = i;
      while (j < expression.size() && is_identifier_char(expression[j])) ++j;
      out.append(expression, i, j - i);
      i = j;
      continue;
    }
    std::size_t length = scan_number(expression, i);
    if (length > 0 && append_small_decimal(expression, i, length, out)) {
      i += length;
      continue;
    }
    if (length > 0) {
      GiNaC::numeric value = literal_value(expression.substr(i, length));
      std::ostringstream rational;
      rational << "(" << value.numer();
      if (!value.is_integer()) rational << "/" << value.denom();
      rational << ")";
      out += rational.str();
      i += length;
      continue;
    }
    out += c;
    ++i;
  }
  return out;
}

std::optional<GiNaC::numeric> parse_exact_number(const std::string& text) {
  std::size_t start = text.find_first_not_of(" \t");
  if (start == std::string::npos) return std::nullopt;
  std::size_t end = text.find_last_not_of(" \t");
  std::string s = text.substr(start, end - start + 1);
  bool negative = false;
  if (!s.empty() && (s[0] == '-' || s[0] == '+')) {
    negative = s[0] == '-';
    s = s.substr(1);
  }
  if (s.empty() || scan_number(s, 0) != s.size()) return std::nullopt;
  GiNaC::numeric value;
  try {
    value = literal_value(s);
  } catch (const std::out_of_range&) {
    return std::nullopt;
  }
  return negative ? -value : value;
}

std::string unread_number_problem(const std::string& text) {
  std::size_t start = text.find_first_not_of(" \t");
  if (start == std::string::npos) return "is not a number";
  std::string s = text.substr(start, text.find_last_not_of(" \t") - start + 1);
  if (s[0] == '-' || s[0] == '+') s = s.substr(1);
  const std::size_t e = s.find_first_of("eE");
  // Well formed, refused only by literal_value's bound on the exponent, and not zero.
  if (s.empty() || scan_number(s, 0) != s.size() || e == std::string::npos ||
      s.find_first_of("123456789") >= e)
    return "is not a number";
  return s[e + 1] == '-' ? "is below the smallest normal double (about 2.2e-308 in magnitude)"
                         : "is beyond the largest double (about 1.8e308)";
}

std::optional<std::string> double_range_problem(const GiNaC::numeric& value) {
  if (value.is_zero() || !value.is_real()) return std::nullopt;
  const GiNaC::numeric magnitude = GiNaC::abs(value);
  if (magnitude < GiNaC::numeric(std::numeric_limits<double>::min()))
    return "is below the smallest normal double (about 2.2e-308 in magnitude): it would be lost in generated code and simulation";
  if (magnitude > GiNaC::numeric(std::numeric_limits<double>::max()))
    return "is beyond the largest double (about 1.8e308)";
  return std::nullopt;
}

std::string approximate_text(const GiNaC::numeric& value) {
  std::ostringstream out;
  out << GiNaC::ex(value).evalf();
  const std::string text = out.str();
  const auto exponent = text.find('E');
  if (exponent == std::string::npos) return text;
  // The mantissa, a double however far the exponent is out of double's range, rounded to three
  // digits (9.9999999999999999999E-321 is 1.0E-320); its rounding may carry into the exponent.
  char mantissa[32];
  std::snprintf(mantissa, sizeof mantissa, "%.2e", std::strtod(text.substr(0, exponent).c_str(), nullptr));
  std::string rounded = mantissa;
  auto e = rounded.find('e');
  while (rounded[e - 1] == '0' && rounded[e - 2] != '.') rounded.erase(--e, 1);  // 1.00 as GiNaC's 1.0
  const long power = std::strtol(text.c_str() + exponent + 1, nullptr, 10) + std::strtol(rounded.c_str() + e + 1, nullptr, 10);
  return rounded.substr(0, e) + "E" + std::to_string(power);
}

}  // namespace pfgen
