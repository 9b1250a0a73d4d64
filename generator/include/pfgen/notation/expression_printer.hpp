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

}  // namespace pfgen
