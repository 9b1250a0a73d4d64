#pragma once
// How the symbolic tests compare a derived expression with an independently built one, and what
// they print when the two differ.
#include <sstream>
#include <string>

#include <ginac/ginac.h>

namespace pfgen_test {

// GiNaC's own text of an expression, for failure messages.
inline std::string text(const GiNaC::ex& e) {
  std::ostringstream out;
  out << e;
  return out.str();
}

// Empty when equal, else both sides and their difference. A difference that does not expand to
// zero gets one normal() pass too, for the rational functions that R^-1, 1/eps or the ukf's
// Cholesky entries bring.
inline std::string mismatch(const GiNaC::ex& expected, const GiNaC::ex& derived) {
  const GiNaC::ex diff = (expected - derived).expand();
  if (diff.is_zero() || diff.normal().is_zero()) return {};
  return "expected " + text(expected) + "\nderived  " + text(derived) + "\ndifference " + text(diff.normal());
}

}  // namespace pfgen_test
