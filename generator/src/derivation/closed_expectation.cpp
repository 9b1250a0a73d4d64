#include "pfgen/derivation/closed_expectation.hpp"

#include <stdexcept>

#include "pfgen/algebra/coefficient.hpp"

namespace pfgen {
namespace {

std::uint32_t total(const std::vector<std::uint32_t>& g) {
  std::uint32_t sum = 0;
  for (std::uint32_t a : g) sum += a;
  return sum;
}

// The indices of e^g, ascending, each repeated by its exponent.
std::vector<std::size_t> index_list(const std::vector<std::uint32_t>& g) {
  std::vector<std::size_t> out;
  for (std::size_t i = 0; i < g.size(); ++i)
    for (std::uint32_t k = 0; k < g[i]; ++k) out.push_back(i);
  return out;
}

GiNaC::numeric binomial(std::uint32_t n, std::uint32_t k) {
  return GiNaC::binomial(GiNaC::numeric(n), GiNaC::numeric(k));
}

// Calls visit(b, multiplicity binom(g, b)) for every b <= g with 1 <= |b| <= most.
template <typename Visit>
void sub_indices(const std::vector<std::uint32_t>& g, std::uint32_t most, std::vector<std::uint32_t>& b, std::size_t at,
                 std::uint32_t size, const GiNaC::numeric& multiplicity, Visit& visit) {
  if (at == g.size()) {
    if (size >= 1) visit(b, multiplicity);
    return;
  }
  for (std::uint32_t k = 0; k <= g[at] && size + k <= most; ++k) {
    b[at] = k;
    sub_indices(g, most, b, at + 1, size + k, multiplicity * binomial(g[at], k), visit);
  }
  b[at] = 0;
}

}  // namespace

ClosedExpectation::ClosedExpectation(const FilterVariables& variables)
    : variables_(variables), base_(static_cast<std::uint32_t>(variables.all_count())) {}

Monomial ClosedExpectation::deviations(const std::vector<std::uint32_t>& g) const {
  Monomial out;
  for (std::size_t i = 0; i < g.size(); ++i)
    if (g[i]) out = out * Monomial::variable(deviation(i), g[i]);
  return out;
}

Polynomial ClosedExpectation::cumulant(const std::vector<std::uint32_t>& a) const {
  const std::vector<std::size_t> i = index_list(a);
  auto P = [&](std::size_t x, std::size_t y) { return Polynomial::variable(variables_.P(i[x], i[y])); };
  switch (i.size()) {
    case 2:
      return P(0, 1);
    case 3:
      return Polynomial::variable(variables_.higher_moment(i));
    case 4:
      return Polynomial::variable(variables_.higher_moment(i)) - P(0, 1) * P(2, 3) - P(0, 2) * P(1, 3) -
             P(0, 3) * P(1, 2);
    default:
      throw std::logic_error("ClosedExpectation: no cumulant of order " + std::to_string(i.size()) + " is carried");
  }
}

const Polynomial& ClosedExpectation::central(const std::vector<std::uint32_t>& g) {
  if (auto it = central_.find(g); it != central_.end()) return it->second;
  Polynomial value;
  const std::uint32_t size = total(g);
  if (size == 0) {
    value = Polynomial::constant(1);
  } else if (size <= variables_.order() && size >= 2) {
    // A carried moment is the filter's own variable: the recursion would give it back only at k = 2.
    const std::vector<std::size_t> i = index_list(g);
    value = Polynomial::variable(size == 2 ? variables_.P(i[0], i[1]) : variables_.higher_moment(i));
  } else if (size > 1) {
    std::size_t first = 0;
    while (g[first] == 0) ++first;
    std::vector<std::uint32_t> rest = g;
    --rest[first];
    std::vector<std::uint32_t> b(g.size(), 0);
    std::vector<std::pair<Polynomial, GiNaC::numeric>> terms;
    auto visit = [&](const std::vector<std::uint32_t>& beta, const GiNaC::numeric& multiplicity) {
      std::vector<std::uint32_t> a = beta, remaining = rest;
      ++a[first];
      for (std::size_t k = 0; k < g.size(); ++k) remaining[k] -= beta[k];
      terms.emplace_back(cumulant(a) * central(remaining), multiplicity);
    };
    sub_indices(rest, static_cast<std::uint32_t>(variables_.order() - 1), b, 0, 0, 1, visit);
    for (const auto& [term, multiplicity] : terms) value += term.scaled(multiplicity);
  }
  return central_.emplace(g, std::move(value)).first->second;
}

const Polynomial& ClosedExpectation::power_of_sum(std::size_t i, std::uint32_t exponent) {
  const auto key = std::make_pair(i, exponent);
  if (auto it = powers_.find(key); it != powers_.end()) return it->second;
  Polynomial value;
  for (std::uint32_t k = 0; k <= exponent; ++k) {
    Monomial term;
    if (exponent - k) term = term * Monomial::variable(variables_.m(i), exponent - k);
    if (k) term = term * Monomial::variable(deviation(i), k);
    value.add_term(std::move(term), binomial(exponent, k));
  }
  return powers_.emplace(key, std::move(value)).first->second;
}

Polynomial ClosedExpectation::shifted(const Polynomial& q) {
  Polynomial out;
  for (const auto& [monomial, coefficient] : q.terms()) {
    Polynomial term = Polynomial::constant(coefficient);
    for (const auto& [variable, exponent] : monomial.factors()) term = term * power_of_sum(variable, exponent);
    out += term;
  }
  return out;
}

Polynomial ClosedExpectation::of(const Polynomial& p) {
  std::vector<std::pair<Monomial, GiNaC::ex>> products;
  std::vector<std::uint32_t> g(variables_.n());
  for (const auto& [monomial, coefficient] : p.terms()) {
    Monomial rest;
    std::fill(g.begin(), g.end(), 0);
    for (const auto& [variable, exponent] : monomial.factors()) {
      if (variable >= base_)
        g[variable - base_] = exponent;
      else
        rest = rest * Monomial::variable(variable, exponent);
    }
    for (const auto& [m, c] : central(g).terms()) products.emplace_back(m * rest, coefficient_product(c, coefficient));
  }
  return Polynomial::sum_of(std::move(products));
}

GiNaC::numeric gaussian_central_moment(const std::vector<std::size_t>& indices,
                                       const std::vector<std::vector<GiNaC::numeric>>& P) {
  if (indices.size() == 3) return 0;  // odd orders vanish
  if (indices.size() != 4) throw std::logic_error("gaussian_central_moment: moments of orders 3 and 4 only");
  auto pair = [&](std::size_t a, std::size_t b) { return P[indices[a]][indices[b]]; };
  return pair(0, 1) * pair(2, 3) + pair(0, 2) * pair(1, 3) + pair(0, 3) * pair(1, 2);
}

}  // namespace pfgen
