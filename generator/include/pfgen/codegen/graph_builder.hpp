#pragma once
// Turns derived polynomials (over FilterVariables) and their coefficients
// (numbers, parameters, functions of time) into nodes of an ExpressionGraph.
// Sums follow the canonical term order; integer powers become products
// (x^4 = (x*x)*(x*x)), never pow(); monomials are built variable by variable,
// so monomials with a common prefix share its product.
#include <stdexcept>
#include <string>

#include "pfgen/algebra/polynomial.hpp"
#include "pfgen/codegen/expression_graph.hpp"
#include "pfgen/derivation/filter_variables.hpp"
#include "pfgen/model/model.hpp"

namespace pfgen::codegen {

class CodegenError : public std::runtime_error {
 public:
  using std::runtime_error::runtime_error;
};

class GraphBuilder {
 public:
  // Filter variable v reads state[v]; parameters read params.<name>; time reads t.
  GraphBuilder(ExpressionGraph& graph, const Model& model, const FilterVariables& variables);
  // Variable v < count reads array[v]: the truth's x[i] (state x_i is polynomial variable i,
  // Polynomial::from_ex(e, model.states)), so truth code reads as the model is written.
  GraphBuilder(ExpressionGraph& graph, const Model& model, std::size_t count, std::string array);

  std::size_t polynomial(const Polynomial& p);
  std::size_t variable(std::uint32_t variable) { return variable_power(variable, 1); }
  std::size_t expression(const GiNaC::ex& e);

 private:
  std::size_t variable_power(std::uint32_t variable, std::uint32_t exponent);
  std::size_t integer_power(std::size_t base, long exponent);
  std::size_t monomial(const Monomial& m);

  std::string input_name(std::uint32_t variable) const;

  ExpressionGraph& graph_;
  std::string array_;
  std::map<GiNaC::ex, std::size_t, GiNaC::ex_is_less> symbols_;
};

}  // namespace pfgen::codegen
