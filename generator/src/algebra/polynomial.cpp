#include "pfgen/algebra/polynomial.hpp"

#include <algorithm>
#include <stdexcept>

#include "pfgen/algebra/coefficient.hpp"

namespace pfgen {

// ---- FactorList ----

void FactorList::reserve(std::size_t capacity) {
  if (capacity <= capacity_) return;
  auto* grown = new value_type[capacity];
  std::copy(begin(), end(), grown);
  delete[] heap_;
  heap_ = grown;
  capacity_ = static_cast<std::uint32_t>(capacity);
}

FactorList::iterator FactorList::erase(iterator position) {
  std::copy(position + 1, end(), position);
  --size_;
  return position;
}

void FactorList::copy_from(const FactorList& other) {
  reserve(other.size_);
  std::copy(other.begin(), other.end(), data());
  size_ = other.size_;
}

void FactorList::move_from(FactorList& other) noexcept {
  if (other.heap_) {
    heap_ = other.heap_;
    capacity_ = other.capacity_;
    other.heap_ = nullptr;
    other.capacity_ = kInline;
  } else {
    std::copy(other.inline_, other.inline_ + other.size_, inline_);
  }
  size_ = other.size_;
  other.size_ = 0;
}

// ---- Monomial ----

Monomial Monomial::variable(std::uint32_t index, std::uint32_t exponent) {
  Monomial m;
  if (exponent > 0) m.factors_.emplace_back(index, exponent);
  return m;
}

Monomial Monomial::operator*(const Monomial& other) const {
  Monomial out;
  out.factors_.reserve(factors_.size() + other.factors_.size());
  auto a = factors_.begin();
  auto b = other.factors_.begin();
  while (a != factors_.end() || b != other.factors_.end()) {
    if (b == other.factors_.end() || (a != factors_.end() && a->first < b->first)) {
      out.factors_.push_back(*a++);
    } else if (a == factors_.end() || b->first < a->first) {
      out.factors_.push_back(*b++);
    } else {
      out.factors_.emplace_back(a->first, a->second + b->second);
      ++a;
      ++b;
    }
  }
  return out;
}

std::uint32_t Monomial::exponent_of(std::uint32_t index) const {
  for (const auto& [var, exponent] : factors_)
    if (var == index) return exponent;
  return 0;
}

std::uint32_t Monomial::degree() const {
  std::uint32_t d = 0;
  for (const auto& factor : factors_) d += factor.second;
  return d;
}

Monomial Monomial::without_one(std::uint32_t index) const {
  Monomial out = *this;
  for (auto it = out.factors_.begin(); it != out.factors_.end(); ++it) {
    if (it->first == index) {
      if (--it->second == 0) out.factors_.erase(it);
      return out;
    }
  }
  throw std::logic_error("Monomial::without_one: variable not present");
}

// ---- Polynomial ----

bool displays_before(const Monomial& a, const Monomial& b) {
  if (a.degree() != b.degree()) return a.degree() > b.degree();
  const auto& fa = a.factors();
  const auto& fb = b.factors();
  std::size_t i = 0, j = 0;
  while (i < fa.size() || j < fb.size()) {
    std::uint32_t va = i < fa.size() ? fa[i].first : UINT32_MAX;
    std::uint32_t vb = j < fb.size() ? fb[j].first : UINT32_MAX;
    std::uint32_t ea = va <= vb ? fa[i].second : 0;
    std::uint32_t eb = vb <= va ? fb[j].second : 0;
    if (ea != eb) return ea > eb;
    if (va <= vb) ++i;
    if (vb <= va) ++j;
  }
  return false;
}

std::vector<const Polynomial::Terms::value_type*> Polynomial::ordered_view() const {
  // Each monomial's degree is computed once, not at every comparison of the sort.
  std::vector<std::pair<std::uint32_t, const Terms::value_type*>> keyed;
  keyed.reserve(terms_.size());
  for (const auto& term : terms_) keyed.emplace_back(term.first.degree(), &term);
  std::stable_sort(keyed.begin(), keyed.end(), [](const auto& a, const auto& b) {
    if (a.first != b.first) return a.first > b.first;
    return displays_before(a.second->first, b.second->first);
  });
  std::vector<const Terms::value_type*> ordered;
  ordered.reserve(keyed.size());
  for (const auto& entry : keyed) ordered.push_back(entry.second);
  return ordered;
}

std::vector<std::pair<Monomial, GiNaC::ex>> Polynomial::ordered_terms() const {
  std::vector<std::pair<Monomial, GiNaC::ex>> ordered;
  ordered.reserve(terms_.size());
  for (const auto* term : ordered_view()) ordered.push_back(*term);
  return ordered;
}

Polynomial Polynomial::constant(const GiNaC::ex& c) {
  Polynomial p;
  p.add_term(Monomial(), c);
  return p;
}

Polynomial Polynomial::variable(std::uint32_t index) {
  Polynomial p;
  p.add_term(Monomial::variable(index), 1);
  return p;
}

Polynomial Polynomial::sum_of(std::vector<std::pair<Monomial, GiNaC::ex>>&& terms) {
  // Stable: a monomial's coefficients keep their order, so they are summed as add_term sums them.
  std::stable_sort(terms.begin(), terms.end(), [](const auto& a, const auto& b) { return a.first < b.first; });
  Polynomial out;
  auto run = terms.begin();
  while (run != terms.end()) {
    auto next = run + 1;
    while (next != terms.end() && next->first == run->first) ++next;
    // add_term's steps: each coefficient normalised; the first (or the first after a zero sum)
    // taken as it is, the others added by coefficient_sum; a zero sum leaves no term.
    bool present = false;
    GiNaC::ex sum;
    for (auto it = run; it != next; ++it) {
      // A number is its own normal form: the check here saves a call per term.
      GiNaC::ex c = GiNaC::is_exactly_a<GiNaC::numeric>(it->second) ? it->second : normalize_coefficient(it->second);
      if (coefficient_is_zero(c)) continue;
      sum = present ? coefficient_sum(sum, c) : std::move(c);
      present = !coefficient_is_zero(sum);
    }
    // Sorted runs arrive in increasing order: inserting at the end costs no search.
    if (present) out.terms_.emplace_hint(out.terms_.end(), std::move(run->first), std::move(sum));
    run = next;
  }
  return out;
}

Polynomial Polynomial::from_ex(const GiNaC::ex& e, const std::vector<GiNaC::symbol>& variables) {
  std::map<GiNaC::ex, std::uint32_t, GiNaC::ex_is_less> index;
  for (std::uint32_t i = 0; i < variables.size(); ++i) index[variables[i]] = i;
  auto as_factor = [&](const GiNaC::ex& f, Monomial& monomial) {
    auto it = index.find(f);
    if (it != index.end()) {
      monomial = monomial * Monomial::variable(it->second);
      return true;
    }
    if (GiNaC::is_exactly_a<GiNaC::power>(f)) {
      auto base = index.find(f.op(0));
      const GiNaC::ex& exponent = f.op(1);
      if (base != index.end() && exponent.info(GiNaC::info_flags::posint)) {
        monomial = monomial * Monomial::variable(
                                  base->second,
                                  static_cast<std::uint32_t>(GiNaC::ex_to<GiNaC::numeric>(exponent).to_int()));
        return true;
      }
    }
    return false;
  };
  Polynomial out;
  GiNaC::ex expanded = e.expand();
  auto add_one_term = [&](const GiNaC::ex& term) {
    Monomial monomial;
    GiNaC::ex coefficient = 1;
    if (GiNaC::is_exactly_a<GiNaC::mul>(term)) {
      for (std::size_t k = 0; k < term.nops(); ++k)
        if (!as_factor(term.op(k), monomial)) coefficient *= term.op(k);
    } else if (!as_factor(term, monomial)) {
      coefficient = term;
    }
    out.add_term(monomial, coefficient);
  };
  if (GiNaC::is_exactly_a<GiNaC::add>(expanded)) {
    for (std::size_t k = 0; k < expanded.nops(); ++k) add_one_term(expanded.op(k));
  } else {
    add_one_term(expanded);
  }
  return out;
}

GiNaC::ex Polynomial::to_ex(const std::vector<GiNaC::ex>& variables) const {
  GiNaC::ex sum = 0;
  for (const auto& [monomial, coefficient] : terms_) {
    GiNaC::ex term = coefficient;
    for (const auto& [var, exponent] : monomial.factors()) term *= GiNaC::pow(variables.at(var), exponent);
    sum += term;
  }
  return sum;
}

std::uint32_t Polynomial::degree() const {
  std::uint32_t d = 0;
  for (const auto& term : terms_) d = std::max(d, term.first.degree());
  return d;
}

void Polynomial::add_term(const Monomial& monomial, const GiNaC::ex& coefficient) { accumulate(monomial, coefficient); }

void Polynomial::add_term(Monomial&& monomial, const GiNaC::ex& coefficient) {
  accumulate(std::move(monomial), coefficient);
}

template <class M>
void Polynomial::accumulate(M&& monomial, const GiNaC::ex& coefficient) {
  GiNaC::ex c = normalize_coefficient(coefficient);
  if (coefficient_is_zero(c)) return;
  // Look up before inserting: map::emplace would build (allocate) a node only to drop it
  // when the monomial is already there, the common case when sums collect like terms.
  auto it = terms_.lower_bound(monomial);
  if (it == terms_.end() || !(it->first == monomial)) {
    terms_.emplace_hint(it, std::forward<M>(monomial), std::move(c));
    return;
  }
  it->second = coefficient_sum(it->second, c);
  if (coefficient_is_zero(it->second)) terms_.erase(it);
}

Polynomial& Polynomial::add_times_monomial(const Polynomial& p, const Monomial& monomial) {
  for (const auto& [m, coefficient] : p.terms_) add_term(m * monomial, coefficient);
  return *this;
}

Polynomial& Polynomial::operator+=(const Polynomial& other) {
  for (const auto& [monomial, coefficient] : other.terms_) add_term(monomial, coefficient);
  return *this;
}

Polynomial& Polynomial::operator-=(const Polynomial& other) {
  for (const auto& [monomial, coefficient] : other.terms_)
    add_term(monomial, coefficient_product(coefficient, -1));
  return *this;
}

Polynomial Polynomial::operator+(const Polynomial& other) const {
  Polynomial out = *this;
  out += other;
  return out;
}

Polynomial Polynomial::operator-(const Polynomial& other) const {
  Polynomial out = *this;
  out -= other;
  return out;
}

Polynomial Polynomial::operator*(const Polynomial& other) const {
  Polynomial out;
  for (const auto& [ma, ca] : terms_)
    for (const auto& [mb, cb] : other.terms_) out.add_term(ma * mb, coefficient_product(ca, cb));
  return out;
}

Polynomial Polynomial::scaled(const GiNaC::ex& factor) const {
  Polynomial out;
  if (factor.is_zero()) return out;
  for (const auto& [monomial, coefficient] : terms_)
    out.add_term(monomial, coefficient_product(coefficient, factor));
  return out;
}

Polynomial Polynomial::times_monomial(const Monomial& monomial) const {
  Polynomial out;
  for (const auto& [m, coefficient] : terms_) out.terms_.emplace(m * monomial, coefficient);
  return out;
}

Polynomial Polynomial::derivative(std::uint32_t index) const {
  Polynomial out;
  for (const auto& [monomial, coefficient] : terms_) {
    std::uint32_t e = monomial.exponent_of(index);
    if (e == 0) continue;
    out.add_term(monomial.without_one(index), coefficient_product(coefficient, GiNaC::numeric(e)));
  }
  return out;
}

Polynomial Polynomial::renumbered(const std::vector<std::uint32_t>& new_index) const {
  Polynomial out;
  for (const auto& [monomial, coefficient] : terms_) {
    Monomial m;
    for (const auto& [var, exponent] : monomial.factors())
      m = m * Monomial::variable(new_index.at(var), exponent);
    out.add_term(m, coefficient);
  }
  return out;
}

bool Polynomial::operator==(const Polynomial& other) const { return (*this - other).is_zero(); }

}  // namespace pfgen
