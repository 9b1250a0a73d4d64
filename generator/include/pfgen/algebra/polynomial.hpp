#pragma once
// A sparse multivariate polynomial over numbered variables with GiNaC
// coefficients. The derivation works in this form rather than in GiNaC
// expressions: monomials are compared by exponent, never by GiNaC's
// address-seeded hash order, so every result has one canonical term order and
// the arithmetic avoids GiNaC's general-purpose simplifier.
#include <algorithm>
#include <cstdint>
#include <optional>
#include <vector>

#include <ginac/ginac.h>

namespace pfgen {

// A monomial's (variable, exponent) pairs: up to three in place, more on the heap. A dense cubic
// n = 20 filter holds 3.3 million monomials, nearly all of at most three variables (m1*m2*P1_3);
// a std::vector would allocate each of them, and the allocations and the page faults they cause
// were a third of `pfgen derive`'s time. Ordered and compared as std::vector's pairs would be.
class FactorList {
 public:
  using value_type = std::pair<std::uint32_t, std::uint32_t>;
  using iterator = value_type*;
  using const_iterator = const value_type*;

  FactorList() = default;
  FactorList(const FactorList& other) { copy_from(other); }
  FactorList(FactorList&& other) noexcept { move_from(other); }
  FactorList& operator=(const FactorList& other) {
    if (this != &other) {
      size_ = 0;
      copy_from(other);
    }
    return *this;
  }
  FactorList& operator=(FactorList&& other) noexcept {
    if (this != &other) {
      release();
      move_from(other);
    }
    return *this;
  }
  ~FactorList() { release(); }

  std::size_t size() const { return size_; }
  bool empty() const { return size_ == 0; }
  value_type* begin() { return data(); }
  value_type* end() { return data() + size_; }
  const value_type* begin() const { return data(); }
  const value_type* end() const { return data() + size_; }
  const value_type& front() const { return data()[0]; }
  const value_type& back() const { return data()[size_ - 1]; }
  const value_type& operator[](std::size_t k) const { return data()[k]; }

  void reserve(std::size_t capacity);
  void push_back(const value_type& factor) {
    if (size_ == capacity_) reserve(2 * capacity_);
    data()[size_++] = factor;
  }
  void emplace_back(std::uint32_t variable, std::uint32_t exponent) { push_back(value_type(variable, exponent)); }
  iterator erase(iterator position);

  bool operator<(const FactorList& other) const {
    return std::lexicographical_compare(begin(), end(), other.begin(), other.end());
  }
  bool operator==(const FactorList& other) const {
    return size_ == other.size_ && std::equal(begin(), end(), other.begin());
  }

 private:
  static constexpr std::uint32_t kInline = 3;
  value_type* data() { return heap_ ? heap_ : inline_; }
  const value_type* data() const { return heap_ ? heap_ : inline_; }
  void copy_from(const FactorList& other);  // *this empty
  void move_from(FactorList& other) noexcept;  // *this holds no heap storage
  void release() noexcept {
    delete[] heap_;
    heap_ = nullptr;
    size_ = 0;
    capacity_ = kInline;
  }

  value_type* heap_ = nullptr;
  std::uint32_t size_ = 0;
  std::uint32_t capacity_ = kInline;
  value_type inline_[kInline];
};

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
  const FactorList& factors() const { return factors_; }

  bool operator<(const Monomial& other) const { return factors_ < other.factors_; }
  bool operator==(const Monomial& other) const { return factors_ == other.factors_; }

 private:
  FactorList factors_;
};

// pfgen's canonical display order of monomials (Polynomial::ordered_terms): total degree
// descending, then the exponent of the lowest-numbered variable where they differ, larger first.
bool displays_before(const Monomial& a, const Monomial& b);

class Polynomial {
 public:
  // Sorted by Monomial::operator<, monomials distinct, no zero coefficient. A sorted vector, not a
  // std::map: the dense cubic n = 20 filter holds 3.3 million terms, and a map's node per term
  // (its allocation, page faults, rebalancing and pointer-chasing walks) was a third of `pfgen
  // derive`'s time.
  using Terms = std::vector<std::pair<Monomial, GiNaC::ex>>;

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
  // The terms of several polynomials together in display order, each with the position of its
  // polynomial in `parts`; a monomial's terms are adjacent, in the order of the parts (printers
  // of a sum, without building it).
  static std::vector<std::pair<std::size_t, const Terms::value_type*>> ordered_union_view(
      const std::vector<const Polynomial*>& parts);
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
  // Adds a term whose monomial is greater than every present one (sum_of's sorted runs); none
  // when the coefficient is absent (the run summed to zero).
  void append_greatest(Monomial&& monomial, std::optional<GiNaC::ex>&& coefficient);
  // add_term(m, c) for each term of `other`, or add_term(m, -c) when `negated`, in one merge.
  void merge_in(const Terms& other, bool negated);

  Terms terms_;
};

}  // namespace pfgen
