#include "support/isserlis_reference.hpp"

#include <stdexcept>
#include <string>

namespace pfgen_test {

IsserlisReference::IsserlisReference(std::vector<GiNaC::symbol> x, const pfgen::FilterVariables& vars)
    : x_(std::move(x)), vars_(vars) {
  if (x_.size() != vars_.n()) throw std::invalid_argument("IsserlisReference: state count differs from n");
  for (std::size_t i = 0; i < x_.size(); ++i) e_.push_back(GiNaC::symbol("isserlis_e" + std::to_string(i + 1)));
}

GiNaC::ex IsserlisReference::m(std::size_t i) const { return vars_.symbols().at(i); }

GiNaC::ex IsserlisReference::P(std::size_t i, std::size_t j) const { return vars_.symbols().at(vars_.P(i, j)); }

// Sum over the perfect pairings of `indices`: pair the first index with each
// of the others in turn and recurse on what is left. (2r-1)!! terms for 2r
// indices; the degrees in the tests keep that small.
GiNaC::ex IsserlisReference::pairings(std::vector<std::size_t> indices) const {
  if (indices.empty()) return 1;
  if (indices.size() % 2 == 1) return 0;
  const std::size_t first = indices.front();
  GiNaC::ex sum = 0;
  for (std::size_t k = 1; k < indices.size(); ++k) {
    std::vector<std::size_t> rest;
    for (std::size_t r = 1; r < indices.size(); ++r)
      if (r != k) rest.push_back(indices[r]);
    sum += P(first, indices[k]) * pairings(rest);
  }
  return sum;
}

GiNaC::ex IsserlisReference::central_moment(const std::vector<unsigned>& exponents) {
  auto it = moments_.find(exponents);
  if (it != moments_.end()) return it->second;
  // Spell the moment out as a list of indices, e.g. e_1^2 e_3 -> (0, 0, 2).
  std::vector<std::size_t> indices;
  for (std::size_t i = 0; i < exponents.size(); ++i)
    for (unsigned k = 0; k < exponents[i]; ++k) indices.push_back(i);
  GiNaC::ex value = pairings(indices).expand();
  moments_.emplace(exponents, value);
  return value;
}

GiNaC::ex IsserlisReference::expectation(const GiNaC::ex& p) {
  GiNaC::exmap shift;
  for (std::size_t i = 0; i < x_.size(); ++i) shift[x_[i]] = m(i) + e_[i];
  const GiNaC::ex expanded = p.subs(shift).expand();
  if (expanded.is_zero()) return 0;

  GiNaC::exmap e_to_one;
  for (const auto& e : e_) e_to_one[e] = 1;
  GiNaC::ex sum = 0;
  auto add_term = [&](const GiNaC::ex& term) {
    std::vector<unsigned> exponents(e_.size());
    for (std::size_t i = 0; i < e_.size(); ++i) {
      const int d = term.degree(e_[i]);
      if (d < 0 || term.ldegree(e_[i]) != d)
        throw std::logic_error("IsserlisReference: term is not a monomial in e after expansion");
      exponents[i] = static_cast<unsigned>(d);
    }
    // The term is coefficient * prod e_i^k_i, so setting every e_i to 1 leaves the coefficient.
    sum += term.subs(e_to_one) * central_moment(exponents);
  };
  if (GiNaC::is_exactly_a<GiNaC::add>(expanded)) {
    for (std::size_t k = 0; k < expanded.nops(); ++k) add_term(expanded.op(k));
  } else {
    add_term(expanded);
  }
  return sum.expand();
}

GiNaC::ex isserlis_expectation(const GiNaC::ex& p, const std::vector<GiNaC::symbol>& x,
                               const pfgen::FilterVariables& vars) {
  IsserlisReference reference(x, vars);
  return reference.expectation(p);
}

}  // namespace pfgen_test
