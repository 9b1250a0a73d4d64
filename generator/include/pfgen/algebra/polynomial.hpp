#pragma once
// A sparse multivariate polynomial over numbered variables with GiNaC
// coefficients. The derivation works in this form rather than in GiNaC
// expressions: monomials are compared by exponent, never by GiNaC's
// address-seeded hash order, so every result has one canonical term order and
// the arithmetic avoids GiNaC's general-purpose simplifier.
#include <cstdint>
#include <map>
#include <vector>

#include <ginac/ginac.h>

namespace pfgen {

// A monomial: (variable index, exponent) pairs, sorted by index, exponents > 0.
class Monomial {
 public:
  Monomial() = default;
  static Monomial variable(std::uint32_t index, std::uint32_t exponent = 1);

  Monomial operator*(const Monomial& other) const;
  std::uint32_t exponent_of(std::uint32_t index) const;
  std::uint32_t degree() const;
  bool is_one() const { return factors_.empty(); }
  // The monomial with `index`'s exponent lowered by one (exponent_of(index) > 0).
  Monomial without_one(std::uint32_t index) const;
  const std::vector<std::pair<std::uint32_t, std::uint32_t>>& factors() const { return factors_; }

  bool operator<(const Monomial& other) const { return factors_ < other.factors_; }
  bool operator==(const Monomial& other) const { return factors_ == other.factors_; }

 private:
  std::vector<std::pair<std::uint32_t, std::uint32_t>> factors_;
};

// pfgen's canonical display order of monomials (Polynomial::ordered_terms): total degree
// descending, then the exponent of the lowest-numbered variable where they differ, larger first.
bool displays_before(const Monomial& a, const Monomial& b);

class Polynomial {
 public:
  using Terms = std::map<Monomial, GiNaC::ex>;

  Polynomial() = default;
  static Polynomial constant(const GiNaC::ex& c);
  static Polynomial variable(std::uint32_t index);

  // The sum of `terms` in their given order, like terms merged exactly as add_term() one after
  // another would merge them (the same coefficient sums in the same order, zero sums dropped),
  // by one stable sort instead of a map lookup per term: the derivation's big sums (dP's
  // E[(x-m)f^T] at n = 20: 17,000 products per entry) are built this way.
  static Polynomial sum_of(std::vector<std::pair<Monomial, GiNaC::ex>>&& terms);

  // Converts an expression polynomial in `variables` (checked by the caller);
  // everything else in it becomes part of the coefficients.
  static Polynomial from_ex(const GiNaC::ex& e, const std::vector<GiNaC::symbol>& variables);
  GiNaC::ex to_ex(const std::vector<GiNaC::ex>& variables) const;

  const Terms& terms() const { return terms_; }
  // The terms in pfgen's canonical display order: total degree descending,
  // then the exponent of the lowest-numbered variable where two monomials
  // differ, larger first. Printers and the code generator both use it.
  std::vector<std::pair<Monomial, GiNaC::ex>> ordered_terms() const;
  // The same order as pointers into terms(), copying no monomial or coefficient (printers).
  std::vector<const Terms::value_type*> ordered_view() const;
  bool is_zero() const { return terms_.empty(); }
  std::uint32_t degree() const;

  void add_term(const Monomial& monomial, const GiNaC::ex& coefficient);
  void add_term(Monomial&& monomial, const GiNaC::ex& coefficient);
  // *this += p.times_monomial(monomial), without the intermediate polynomial.
  Polynomial& add_times_monomial(const Polynomial& p, const Monomial& monomial);
  Polynomial& operator+=(const Polynomial& other);
  Polynomial& operator-=(const Polynomial& other);
  Polynomial operator+(const Polynomial& other) const;
  Polynomial operator-(const Polynomial& other) const;
  Polynomial operator*(const Polynomial& other) const;
  Polynomial scaled(const GiNaC::ex& factor) const;
  Polynomial times_monomial(const Monomial& monomial) const;
  Polynomial derivative(std::uint32_t index) const;
  // Renumbers variable i as new_index[i] (used to read x-polynomials in m).
  Polynomial renumbered(const std::vector<std::uint32_t>& new_index) const;

  bool operator==(const Polynomial& other) const;
  bool operator!=(const Polynomial& other) const { return !(*this == other); }

 private:
  template <class M>
  void accumulate(M&& monomial, const GiNaC::ex& coefficient);

  Terms terms_;
};

}  // namespace pfgen
