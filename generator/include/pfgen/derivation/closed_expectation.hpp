#pragma once
// Expectations under a moment filter's closed law (docs/theory.md §2.10): x = m + e, the deviation e
// with the central moments the filter carries (P, then M3, M4 ... up to its order k) and every
// cumulant of order > k zero. E[q(x)] is then a polynomial in m and those moments.
//
// Algorithm (the moment-cumulant recursion, which at k = 2 is Isserlis' theorem):
//   E[e_i e^g] = sum over b <= g, 1 <= |b| <= k-1, of kappa(e_i + b) binom(g, b) E[e^(g-b)],
// kappa of order 2 = P, of order 3 = M3, of order 4 = M4_ijlq - (P_ij P_lq + P_il P_jq + P_iq P_jl),
// memoised by exponent vector. Polynomials in x are first written in m and e (`shifted`): the
// deviations are variables numbered after every filter variable, so no result holds them.
#include <cstdint>
#include <map>
#include <vector>

#include "pfgen/algebra/polynomial.hpp"
#include "pfgen/derivation/filter_variables.hpp"

namespace pfgen {

class ClosedExpectation {
 public:
  explicit ClosedExpectation(const FilterVariables& variables);

  // The variable standing for e_i in the polynomials `of` takes.
  std::uint32_t deviation(std::size_t i) const { return static_cast<std::uint32_t>(base_ + i); }
  // q(m + e) for q over the states (variable i is x_i), over m and the deviations.
  Polynomial shifted(const Polynomial& q);
  // E over e of a polynomial in the filter variables and the deviations: a polynomial in the filter variables.
  Polynomial of(const Polynomial& p);
  // E[q(x)] for q over the states.
  Polynomial of_state_polynomial(const Polynomial& q) { return of(shifted(q)); }
  // The central moment E[e^g], g the deviations' exponents (n entries): 1 for g = 0, 0 for |g| = 1, the
  // filter's variable for 2 <= |g| <= k, the closed value above.
  const Polynomial& central(const std::vector<std::uint32_t>& g);
  // e^g as a monomial of deviations.
  Monomial deviations(const std::vector<std::uint32_t>& g) const;

 private:
  Polynomial cumulant(const std::vector<std::uint32_t>& a) const;  // 2 <= |a| <= k
  const Polynomial& power_of_sum(std::size_t i, std::uint32_t exponent);  // (m_i + e_i)^exponent

  const FilterVariables& variables_;
  std::uint32_t base_;
  std::map<std::vector<std::uint32_t>, Polynomial> central_;
  std::map<std::pair<std::size_t, std::uint32_t>, Polynomial> powers_;
};

// The central moment of x ~ N(m, P) with these indices (a moment filter's of order 3 or 4): 0 at order 3,
// P_ij P_lq + P_il P_jq + P_iq P_jl at order 4. A moment filter's value under its Gaussian prior (its initial
// state) and `eval`'s for a moment not given. P is full and symmetric.
GiNaC::numeric gaussian_central_moment(const std::vector<std::size_t>& indices,
                                       const std::vector<std::vector<GiNaC::numeric>>& P);

}  // namespace pfgen
