#pragma once
// Whether an expression is a polynomial in a list of variables, and its degree in each, found in
// one walk of the expression. GiNaC's is_polynomial(list) and degree(v) walk the expression once
// per variable: for a dense model's drift (20 states, entries of 1771 terms) that was a third of
// reading the model file. The answers are GiNaC's, with degrees capped (see below).
#include <cstdint>
#include <vector>

#include <ginac/ginac.h>

namespace pfgen {

struct PolynomialShape {
  // As e.is_polynomial(variables) answers: only non-negative integer powers of the variables,
  // and no variable inside a function, a non-integer power or an exponent.
  bool polynomial = true;
  // When polynomial: e.degree(v) for each variable, in the list's order, except that a degree
  // above `cap` reads cap + 1 (GiNaC's own degree wraps around beyond int: x^(83^10) < 0).
  std::vector<std::int64_t> degrees;
};

PolynomialShape polynomial_shape(const GiNaC::ex& e, const std::vector<GiNaC::symbol>& variables, std::int64_t cap);

}  // namespace pfgen
