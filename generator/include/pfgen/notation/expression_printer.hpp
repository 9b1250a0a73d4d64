#pragma once
// Canonical printing of expressions and polynomials. GiNaC's own printers
// follow its hash order, which changes from run to run (docs/theory.md §9.1); this
// printer puts every sum and product in an order of pfgen's own:
//   - polynomial terms by total degree (highest first), then by exponents in
//     variable order (m1, ..., mn, P11, P12, ...), higher exponents first;
//   - the terms and factors of coefficient expressions by their printed text.
// Subclasses (text, LaTeX; later C++) supply only the notation, in the manner
// of GiNaC's hierarchy of print contexts.
#include <functional>
#include <optional>
#include <string>
#include <vector>

#include <ginac/ginac.h>

#include "pfgen/algebra/polynomial.hpp"

namespace pfgen {

class ExpressionPrinter {
 public:
  using VariableNamer = std::function<std::string(std::uint32_t)>;
  virtual ~ExpressionPrinter() = default;

  // Any GiNaC expression (model entries, coefficients).
  std::string print(const GiNaC::ex& e) const;
  // A polynomial whose variable k is printed as `name(k)`.
  std::string print(const Polynomial& p, const VariableNamer& name) const;

 protected:
  friend class PolynomialWriter;  // prints polynomials with the same pieces, keeping what repeats

  // A term: sign, non-negative number (1 when absent) and already printed factors.
  struct Term {
    bool negative = false;
    GiNaC::numeric magnitude = 1;
    std::vector<std::string> numerator_factors;
    std::vector<std::string> denominator_factors;
  };

  // ---- notation, supplied by each printer ----
  virtual std::string number(const GiNaC::numeric& non_negative) const = 0;
  virtual std::string symbol_name(const std::string& name) const = 0;
  virtual std::string power(const std::string& base, const std::string& exponent) const = 0;
  // Appends the product of already printed factors to `out` (the writer's hot path: no string
  // is built per term); join_factors returns the same as a string.
  virtual void append_factors(std::string& out, const std::string* const* factors, std::size_t count) const = 0;
  std::string join_factors(const std::vector<std::string>& factors) const;
  virtual std::string quotient(const std::string& numerator, const std::string& denominator) const = 0;
  virtual std::string function_call(const std::string& name, const std::vector<std::string>& args) const = 0;
  virtual std::string parenthesized(const std::string& inner) const = 0;
  virtual std::string constant(const GiNaC::ex& c) const = 0;  // Pi, Euler, ...

  // ---- canonical structure, shared ----
  std::string print_sum(std::vector<Term> terms) const;
  std::string print_term_body(const Term& term) const;  // without its sign
  Term to_term(const GiNaC::ex& e) const;
  std::string print_factor(const GiNaC::ex& e) const;   // an operand of a product, parenthesised if needed
  std::string print_integer_power(const std::string& base, long exponent) const;
};

// A factor of a product that is a sum, or a sum to a non-zero integer power, with its sign chosen
// by pfgen rather than by GiNaC. GiNaC keeps such a sum either as written or negated with -1 in the
// product's number, by a term order that varies from run to run (docs/theory.md §9.1):
// (P23 - L21*L31)/L22 is -(L21*L31 - P23)/L22 in one run and (-L21*L31 + P23)/L22 in the next. Of
// the sum and its negative, `sum` is the one whose printed terms (by `printer`) begin with a +, and
// `text` its printed form. The printers and the code generator both make products canonical so.
struct CanonicalSumFactor {
  GiNaC::ex sum;
  std::string text;
  long exponent;
  bool negated;  // `sum` is the factor's sum negated
  // The product's sign changes with the choice: a negated sum to an odd power.
  bool flips_sign() const { return negated && exponent % 2 != 0; }
};

// Empty unless `factor` is a sum, or a sum to an integer power of at most 2^30 in magnitude.
std::optional<CanonicalSumFactor> canonical_sum_factor(const GiNaC::ex& factor, const ExpressionPrinter& printer);

}  // namespace pfgen
