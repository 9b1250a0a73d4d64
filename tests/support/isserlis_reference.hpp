#pragma once
// A brute-force reference for Gaussian expectations of polynomials, written
// independently of pfgen::GaussianExpectation (which uses a Stein-lemma
// recursion) so that the tests can check the derivation against a second,
// unrelated code path (docs/theory.md §3.3 and §3.5, "Isserlis / Wick").
//
// For x ~ N(m, P) and a GiNaC polynomial p in the state symbols x:
//   1. substitute x = m + e with fresh symbols e and expand in e;
//   2. replace each central moment E[e_i1 ... e_ik] by the sum over all
//      perfect pairings of {i1..ik} of the products of P entries (Isserlis /
//      Wick); odd moments vanish.
// The result is a GiNaC expression in the symbols of pfgen::FilterVariables:
// m_i = vars.symbols()[i], P_ij = vars.symbols()[vars.P(i, j)]. Symbols of
// `p` other than x (parameters, time, or even the filter's own m_i) are left
// alone, so E[(x_i - m_i) f_j(x)] is computed by passing that product as it is.
#include <map>
#include <vector>

#include <ginac/ginac.h>

#include "pfgen/derivation/filter_variables.hpp"

namespace pfgen_test {

class IsserlisReference {
 public:
  IsserlisReference(std::vector<GiNaC::symbol> x, const pfgen::FilterVariables& vars);

  // E[p(x)], expanded.
  GiNaC::ex expectation(const GiNaC::ex& p);

  // E[e_0^k0 e_1^k1 ...] for e ~ N(0, P): the sum over all pairings.
  GiNaC::ex central_moment(const std::vector<unsigned>& exponents);

  // The symbol standing for m_i and for P_ij (either order).
  GiNaC::ex m(std::size_t i) const;
  GiNaC::ex P(std::size_t i, std::size_t j) const;

 private:
  GiNaC::ex pairings(std::vector<std::size_t> indices) const;

  std::vector<GiNaC::symbol> x_;
  std::vector<GiNaC::symbol> e_;
  const pfgen::FilterVariables& vars_;
  std::map<std::vector<unsigned>, GiNaC::ex> moments_;
};

// Shorthand for a one-off expectation.
GiNaC::ex isserlis_expectation(const GiNaC::ex& p, const std::vector<GiNaC::symbol>& x,
                               const pfgen::FilterVariables& vars);

}  // namespace pfgen_test
