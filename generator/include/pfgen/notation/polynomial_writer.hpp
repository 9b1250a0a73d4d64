#pragma once
// Writes polynomials in an ExpressionPrinter's notation and canonical order, appending to one
// string. A report prints millions of terms (the dense cubic n = 20 optimal filter: 3.3 million),
// so the per-term work matters: the writer keeps what repeats across the polynomials of one report
// (the printed variable powers m1^2, P1_10; the printed numbers 0.3, 1/3) and appends instead of
// building a string per factor and per term. The bytes are those of ExpressionPrinter::print.
#include <cstdint>
#include <string>
#include <unordered_map>
#include <vector>

#include <ginac/ginac.h>

#include "pfgen/algebra/polynomial.hpp"
#include "pfgen/notation/expression_printer.hpp"

namespace pfgen {

// A polynomial or its negative, unbuilt (dP's correction enters its sum negated).
struct SignedPolynomial {
  const Polynomial* polynomial;
  bool negated = false;
};

class PolynomialWriter {
 public:
  // `printer` and `name` must outlive the writer; `name(v)` must not change between calls.
  PolynomialWriter(const ExpressionPrinter& printer, ExpressionPrinter::VariableNamer name);

  // Appends p as ExpressionPrinter::print(p, name) writes it, or -p when `negated`
  // (as print(p.scaled(-1), name), without building the negated polynomial).
  // `continuing`: p follows other text in a sum, so its first sign is written " + " or " - ".
  void append(std::string& out, const Polynomial& p, bool negated = false, bool continuing = false);
  // Appends the sum of the parts with like terms merged, as print(p1 + p2 - p3) writes it,
  // without building the sum (its map of terms); the coefficients are summed in the same order.
  void append_sum(std::string& out, const std::vector<SignedPolynomial>& parts);
  std::string print(const Polynomial& p) {
    std::string out;
    append(out, p);
    return out;
  }

 private:
  struct NumericHash {
    std::size_t operator()(const GiNaC::numeric& x) const { return x.gethash(); }
  };
  struct NumericEqual {
    bool operator()(const GiNaC::numeric& a, const GiNaC::numeric& b) const { return a.is_equal(b); }
  };
  // A numeric coefficient as printed: its sign, whether its magnitude is 1, and the magnitude's text.
  struct PrintedNumber {
    bool negative;
    bool unit;
    std::string magnitude;
  };
  // Powers up to this exponent of variables below this index are looked up by index (a table
  // that grows to the largest index seen), the others by hash.
  static constexpr std::uint32_t kTabulatedExponents = 16;
  static constexpr std::uint32_t kTabulatedVariables = 1u << 16;

  void append_term(std::string& out, const Monomial& monomial, const GiNaC::ex& coefficient, bool negated,
                   bool first);
  // Keyed by the signed coefficient as the polynomial holds it, whose hash GiNaC keeps once computed.
  const PrintedNumber& number(const GiNaC::numeric& value);
  const std::string& variable_power(std::uint32_t variable, std::uint32_t exponent);

  const ExpressionPrinter& printer_;
  ExpressionPrinter::VariableNamer name_;
  std::unordered_map<GiNaC::numeric, PrintedNumber, NumericHash, NumericEqual> numbers_;
  std::vector<std::vector<std::string>> tabulated_powers_;  // [variable][exponent], "" until printed
  std::unordered_map<std::uint64_t, std::string> other_powers_;  // key: variable << 32 | exponent
  std::vector<const std::string*> factors_;                       // scratch, reused term after term
};

}  // namespace pfgen
