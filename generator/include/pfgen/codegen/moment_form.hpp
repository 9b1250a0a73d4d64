#pragma once
// Gaussian expectations written over shared moments: E[q(x)] for x ~ N(m, P) as
// sum_a c_a E[x^a], each moment E[x^a] (a polynomial in m and P) built once in the graph and
// multiplied by its coefficient wherever an expectation reads x^a. The expanded polynomial
// E[q] collects its terms by monomials of m and P instead, so every coefficient c_a multiplies
// each of E[x^a]'s terms again (a cubic monomial's moment has four: m_a m_b m_c + m_a P_bc +
// m_b P_ac + m_c P_ab); with many polynomials reading the same monomials (a dense drift, its
// Jacobian), sharing the moments is far cheaper. The value is the same polynomial, summed in
// another order.
#include <cstddef>
#include <map>

#include "pfgen/algebra/polynomial.hpp"
#include "pfgen/codegen/graph_builder.hpp"
#include "pfgen/derivation/filter_variables.hpp"
#include "pfgen/derivation/gaussian_expectation.hpp"

namespace pfgen::codegen {

class MomentForm {
 public:
  MomentForm(GraphBuilder& builder, const FilterVariables& variables) : builder_(builder), moments_(variables) {}
  // The node of E[q], q a polynomial in the states (variable i is x_i).
  std::size_t expectation(const Polynomial& q);

 private:
  std::size_t moment(const Monomial& a);
  GraphBuilder& builder_;
  GaussianExpectation moments_;
  std::map<Monomial, std::size_t> nodes_;
};

}  // namespace pfgen::codegen
