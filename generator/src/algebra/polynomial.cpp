#include "pfgen/algebra/polynomial.hpp"

#include <algorithm>
#include <cstdint>
#include <optional>
#include <stdexcept>

#include "pfgen/algebra/coefficient.hpp"
#include "pfgen/algebra/monomial_keys.hpp"

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

namespace {

// A coefficient as add_term takes it: normalised (a number is its own normal form, and the
// check saves a call per term).
GiNaC::ex normalized(GiNaC::ex&& coefficient) {
  return GiNaC::is_exactly_a<GiNaC::numeric>(coefficient) ? std::move(coefficient) : normalize_coefficient(coefficient);
}

// add_term's steps on one monomial's normalised coefficients, in order: zeros skipped, the first
// (or the first after a zero sum) taken as it is, the others added by coefficient_sum; a zero sum
// leaves no term. `coefficients(visit)` calls visit on each coefficient in turn.
template <class Coefficients>
std::optional<GiNaC::ex> summed_like_add_term(Coefficients&& coefficients) {
  bool present = false;
  GiNaC::ex sum;
  coefficients([&](GiNaC::ex&& c) {
    if (coefficient_is_zero(c)) return;
    sum = present ? coefficient_sum(sum, c) : std::move(c);
    present = !coefficient_is_zero(sum);
  });
  if (!present) return std::nullopt;
  return sum;
}

}  // namespace

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
  std::vector<const Terms::value_type*> ordered;
  ordered.reserve(terms_.size());
  for (const auto& entry : ordered_union_view({this})) ordered.push_back(entry.second);
  return ordered;
}

std::vector<std::pair<std::size_t, const Polynomial::Terms::value_type*>> Polynomial::ordered_union_view(
    const std::vector<const Polynomial*>& parts) {
  std::vector<std::pair<std::size_t, const Terms::value_type*>> ordered;
  std::size_t count = 0;
  for (const Polynomial* part : parts) count += part->terms_.size();
  ordered.reserve(count);
  for (std::size_t k = 0; k < parts.size(); ++k)
    for (const auto& term : parts[k]->terms_) ordered.emplace_back(k, &term);
  // Printing sorts every polynomial (3.3 million terms at dense cubic n = 20): by packed keys
  // when every monomial has one, else by displays_before on the factor lists. Both sorts keep
  // equal monomials in the order of the parts.
  std::vector<KeyedIndex> keyed;  // fewer than 2^32 terms here: memory would run out first
  keyed.reserve(count);
  for (const auto& [part, term] : ordered) {
    MonomialKey key;
    if (!display_order_key(term->first, key)) break;
    keyed.push_back(KeyedIndex{key, static_cast<std::uint32_t>(keyed.size())});
  }
  if (keyed.size() == count) {
    sort_by_key(keyed);
    std::vector<std::pair<std::size_t, const Terms::value_type*>> sorted;
    sorted.reserve(count);
    for (const KeyedIndex& entry : keyed) sorted.push_back(ordered[entry.index]);
    return sorted;
  }
  // Each monomial's degree is computed once, not at every comparison of the sort.
  std::vector<std::pair<std::uint32_t, std::size_t>> by_degree;
  by_degree.reserve(count);
  for (std::size_t k = 0; k < count; ++k) by_degree.emplace_back(ordered[k].second->first.degree(), k);
  std::stable_sort(by_degree.begin(), by_degree.end(), [&](const auto& a, const auto& b) {
    if (a.first != b.first) return a.first > b.first;
    return displays_before(ordered[a.second].second->first, ordered[b.second].second->first);
  });
  std::vector<std::pair<std::size_t, const Terms::value_type*>> sorted;
  sorted.reserve(count);
  for (const auto& entry : by_degree) sorted.push_back(ordered[entry.second]);
  return sorted;
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
  // Sorted by (packed key, position): stable, so a monomial's coefficients keep their order and
  // are summed as add_term sums them; sorting 24-byte keys moves far less than sorting the terms.
  // The coefficients are normalised here, in the order they were made in (and lie in memory),
  // so that a monomial with one term needs no second look at its coefficient after the sort.
  for (auto& term : terms) term.second = normalized(std::move(term.second));
  std::vector<KeyedIndex> keyed;
  bool all_keyed = terms.size() <= UINT32_MAX;
  if (all_keyed) keyed.reserve(terms.size());
  for (std::size_t k = 0; all_keyed && k < terms.size(); ++k) {
    MonomialKey key;
    all_keyed = map_order_key(terms[k].first, key);
    keyed.push_back(KeyedIndex{key, static_cast<std::uint32_t>(k), coefficient_is_zero(terms[k].second)});
  }
  Polynomial out;
  if (!all_keyed) {
    std::stable_sort(terms.begin(), terms.end(), [](const auto& a, const auto& b) { return a.first < b.first; });
    for (auto run = terms.begin(); run != terms.end();) {
      auto next = run + 1;
      while (next != terms.end() && next->first == run->first) ++next;
      auto coefficients = [&](auto&& visit) {
        for (auto it = run; it != next; ++it) visit(std::move(it->second));
      };
      out.append_greatest(std::move(run->first), summed_like_add_term(coefficients));
      run = next;
    }
    return out;
  }
  sort_by_key(keyed);
  std::size_t distinct = keyed.empty() ? 0 : 1;  // the result's size at most: reserved, not grown
  for (std::size_t k = 1; k < keyed.size(); ++k) distinct += !(keyed[k].key == keyed[k - 1].key);
  out.terms_.reserve(distinct);
  // After the sort the terms are read in no order of memory: each is asked for a few runs ahead.
  constexpr std::size_t kAhead = 8;
  for (std::size_t run = 0; run < keyed.size();) {
    if (run + 2 * kAhead < keyed.size()) __builtin_prefetch(&terms[keyed[run + 2 * kAhead].index]);
    if (run + kAhead < keyed.size()) prefetch_coefficient(terms[keyed[run + kAhead].index].second);
    std::size_t next = run + 1;
    while (next < keyed.size() && keyed[next].key == keyed[run].key) ++next;
    auto& [monomial, coefficient] = terms[keyed[run].index];
    if (next == run + 1) {
      if (!keyed[run].zero) out.append_greatest(std::move(monomial), std::move(coefficient));
    } else {
      auto coefficients = [&](auto&& visit) {
        for (std::size_t r = run; r < next; ++r) visit(std::move(terms[keyed[r].index].second));
      };
      out.append_greatest(std::move(monomial), summed_like_add_term(coefficients));
    }
    run = next;
  }
  return out;
}

void Polynomial::append_greatest(Monomial&& monomial, std::optional<GiNaC::ex>&& coefficient) {
  if (coefficient) terms_.emplace_back(std::move(monomial), std::move(*coefficient));
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
  std::vector<std::pair<Monomial, GiNaC::ex>> terms;
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
    terms.emplace_back(std::move(monomial), std::move(coefficient));
  };
  if (GiNaC::is_exactly_a<GiNaC::add>(expanded)) {
    for (std::size_t k = 0; k < expanded.nops(); ++k) add_one_term(expanded.op(k));
  } else {
    add_one_term(expanded);
  }
  return sum_of(std::move(terms));
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
  auto it = std::lower_bound(terms_.begin(), terms_.end(), monomial,
                             [](const Terms::value_type& term, const Monomial& m) { return term.first < m; });
  if (it == terms_.end() || !(it->first == monomial)) {
    terms_.emplace(it, std::forward<M>(monomial), std::move(c));
    return;
  }
  it->second = coefficient_sum(it->second, c);
  if (coefficient_is_zero(it->second)) terms_.erase(it);
}

void Polynomial::merge_in(const Terms& other, bool negated) {
  if (&other == &terms_) {  // p += p: merge a copy, the terms are moved from below
    const Terms copy = other;
    merge_in(copy, negated);
    return;
  }
  // add_term for each of other's terms (their monomials are distinct, so the order of the calls
  // does not matter), in one pass over both sorted lists.
  Terms merged;
  merged.reserve(terms_.size() + other.size());
  auto a = terms_.begin();
  for (const auto& [monomial, coefficient] : other) {
    for (; a != terms_.end() && a->first < monomial; ++a) merged.push_back(std::move(*a));
    GiNaC::ex c = normalize_coefficient(negated ? coefficient_product(coefficient, -1) : coefficient);
    const bool present = a != terms_.end() && a->first == monomial;
    if (coefficient_is_zero(c)) continue;  // add_term leaves the polynomial as it is
    if (!present) {
      merged.emplace_back(monomial, std::move(c));
      continue;
    }
    GiNaC::ex sum = coefficient_sum(a->second, c);
    if (!coefficient_is_zero(sum)) merged.emplace_back(std::move(a->first), std::move(sum));
    ++a;
  }
  for (; a != terms_.end(); ++a) merged.push_back(std::move(*a));
  terms_ = std::move(merged);
}

Polynomial& Polynomial::add_times_monomial(const Polynomial& p, const Monomial& monomial) {
  merge_in(p.times_monomial(monomial).terms_, false);
  return *this;
}

Polynomial& Polynomial::operator+=(const Polynomial& other) {
  merge_in(other.terms_, false);
  return *this;
}

Polynomial& Polynomial::operator-=(const Polynomial& other) {
  merge_in(other.terms_, true);
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
  std::vector<std::pair<Monomial, GiNaC::ex>> products;
  products.reserve(terms_.size() * other.terms_.size());
  for (const auto& [ma, ca] : terms_)
    for (const auto& [mb, cb] : other.terms_) products.emplace_back(ma * mb, coefficient_product(ca, cb));
  return sum_of(std::move(products));
}

Polynomial Polynomial::scaled(const GiNaC::ex& factor) const {
  Polynomial out;
  if (factor.is_zero()) return out;
  // The monomials stay as they are, and in order.
  out.terms_.reserve(terms_.size());
  for (const auto& [monomial, coefficient] : terms_) {
    GiNaC::ex c = normalize_coefficient(coefficient_product(coefficient, factor));
    if (!coefficient_is_zero(c)) out.terms_.emplace_back(monomial, std::move(c));
  }
  return out;
}

Polynomial Polynomial::times_monomial(const Monomial& monomial) const {
  // Distinct monomials stay distinct, but not in order: multiplying changes std::map-style
  // lexicographic comparisons ((x2) < (x3), but (x2^2) > (x2, x3) after multiplying by x2).
  Polynomial out;
  out.terms_.reserve(terms_.size());
  for (const auto& [m, coefficient] : terms_) out.terms_.emplace_back(m * monomial, coefficient);
  std::sort(out.terms_.begin(), out.terms_.end(), [](const auto& a, const auto& b) { return a.first < b.first; });
  return out;
}

Polynomial Polynomial::derivative(std::uint32_t index) const {
  std::vector<std::pair<Monomial, GiNaC::ex>> terms;
  for (const auto& [monomial, coefficient] : terms_) {
    std::uint32_t e = monomial.exponent_of(index);
    if (e == 0) continue;
    terms.emplace_back(monomial.without_one(index), coefficient_product(coefficient, GiNaC::numeric(e)));
  }
  return sum_of(std::move(terms));
}

Polynomial Polynomial::renumbered(const std::vector<std::uint32_t>& new_index) const {
  std::vector<std::pair<Monomial, GiNaC::ex>> terms;
  for (const auto& [monomial, coefficient] : terms_) {
    Monomial m;
    for (const auto& [var, exponent] : monomial.factors())
      m = m * Monomial::variable(new_index.at(var), exponent);
    terms.emplace_back(std::move(m), coefficient);
  }
  return sum_of(std::move(terms));
}

bool Polynomial::operator==(const Polynomial& other) const { return (*this - other).is_zero(); }

}  // namespace pfgen
