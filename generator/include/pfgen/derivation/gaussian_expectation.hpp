#pragma once
// Exact Gaussian expectations of polynomials: E[p(x)] for x ~ N(m, P) as a
// polynomial in m and the entries of P.
//
// Algorithm (Stein's lemma, applied monomial by monomial):
//   E[x_i h(x)] = m_i E[h(x)] + sum_j P_ij E[d_j h(x)],  and  E[d_j h] = d/dm_j E[h],
// so E[x^a] = m_i E[x^b] + sum_j P_ij d/dm_j E[x^b] with x^a = x_i x^b. Each
// monomial's expectation is computed once and memoised, so the dense cubic
// drift of a 20-state model costs a few thousand small polynomial operations.
// The tests check it against an independent Isserlis-pairing expansion.
#include <map>

#include "pfgen/algebra/polynomial.hpp"
#include "pfgen/derivation/filter_variables.hpp"

namespace pfgen {

class GaussianExpectation {
 public:
  explicit GaussianExpectation(const FilterVariables& variables) : variables_(variables) {}

  // `p` is over the state variables 0..n-1; the result is over FilterVariables.
  Polynomial of(const Polynomial& p);
  const Polynomial& of_monomial(const Monomial& monomial);
  // The smaller monomial whose expectation E[monomial] is built from (monomial is not one):
  // the first variable's exponent lowered by one. derivation_budget follows the same chain.
  static Monomial peeled(const Monomial& monomial) {
    return monomial.without_one(monomial.factors().front().first);
  }

 private:
  const FilterVariables& variables_;
  std::map<Monomial, Polynomial> memo_;
};

}  // namespace pfgen
