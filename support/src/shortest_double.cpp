#include "pfgen_support/shortest_double.hpp"

#include <charconv>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <stdexcept>

namespace pfgen_support {

std::string shortest_double(double value) {
  if (value == 0) return "0";
  char buffer[40];
  for (int precision = 1; precision <= 17; ++precision) {
    std::snprintf(buffer, sizeof buffer, "%.*g", precision, value);
    if (std::strtod(buffer, nullptr) == value) break;
  }
  return buffer;
}

std::string shortest_chars(double value) {
  char buffer[64];  // the longest shortest form ("-2.2250738585072014e-308") has 24 characters
  const auto [end, error] = std::to_chars(buffer, buffer + sizeof buffer, value);
  if (error != std::errc()) throw std::logic_error("shortest_chars: std::to_chars failed");
  return std::string(buffer, end);
}

std::string fixed_unless_huge(double value) {
  char buffer[48];
  std::snprintf(buffer, sizeof buffer, std::abs(value) < 1e15 ? "%f" : "%g", value);
  return buffer;
}

}  // namespace pfgen_support
