#pragma once
// Turns derived polynomials (over FilterVariables) and their coefficients
// (numbers, parameters, functions of time) into nodes of an ExpressionGraph.
// Sums follow the canonical term order; integer powers become products
// (x^4 = (x*x)*(x*x)), never pow(); monomials are built variable by variable,
// so monomials with a common prefix share its product.
#include <map>
#include <set>
#include <stdexcept>
#include <string>
#include <utility>
#include <vector>

#include "pfgen/algebra/polynomial.hpp"
#include "pfgen/codegen/codegen_error.hpp"
#include "pfgen/codegen/expression_graph.hpp"
#include "pfgen/derivation/filter_variables.hpp"
#include "pfgen/model/model.hpp"

namespace pfgen::codegen {

// What a function's outputs read of its arguments.
struct InputUse {
  bool variables = false;   // the array of variables (the filter state, the truth's x)
  std::set<std::string> arrays;  // each array a variable is read from (a delayed filter has two)
  bool parameters = false;
  bool time = false;
};

// Terms added one at a time into a sum, each with its sign: a negative term is subtracted.
// -s - t is -(s + t) exactly, and -s + t is t - s: the leading negative terms are summed as they
// are and subtracted from the first positive one, which saves their negation.
class SignedSum {
 public:
  explicit SignedSum(ExpressionGraph& graph) : graph_(graph) {}
  void add(std::size_t term, bool negative);
  // A node whose sign the graph shows: -a (a Neg node) is added as a, subtracted.
  void add(std::size_t term) {
    const bool negated = graph_.node(term).kind == OpKind::Neg;
    add(negated ? graph_.node(term).args[0] : term, negated);
  }
  // The sum so far, doubled: 2 s as s + s, exact, its sign kept for the terms that follow.
  void double_it() {
    if (!empty_) sum_ = graph_.add(sum_, sum_);
  }
  bool empty() const { return empty_; }
  std::size_t result() const;

 private:
  ExpressionGraph& graph_;
  std::size_t sum_ = 0;
  bool empty_ = true, negated_ = false;  // negated: the terms so far sum to -sum_
};

class GraphBuilder {
 public:
  // Inputs are named as the equations name them. Filter variable v is named as printed
  // (variables.text_name(v): m1, P12, P1_10) and read from array[v]; parameter a is named a and
  // read from params.a; the time is named as in the model and is the function's argument itself.
  GraphBuilder(ExpressionGraph& graph, const Model& model, const FilterVariables& variables,
               const std::string& array = "state", const std::string& params = "params");
  // Variable v < names.size() is named names[v] and read from array[v]: the truth reads state
  // x_i (polynomial variable i, Polynomial::from_ex(e, model.states)) from x[i] as its own name.
  GraphBuilder(ExpressionGraph& graph, const Model& model, std::vector<std::string> names,
               const std::string& array, const std::string& params);
  // Variable v is named names[v] and read from arrays[v][indices[v]]: a delayed filter reads m, P
  // and x* from its state and m(t - h), Phi* from a second array.
  GraphBuilder(ExpressionGraph& graph, const Model& model, std::vector<std::string> names,
               const std::vector<std::string>& arrays, const std::vector<std::size_t>& indices,
               const std::string& params);

  // A user filter's definitions (FilterEquations::definitions), in order: each name becomes the
  // node of its value, which reads filter variable v as variable_symbols[v]. Call before building
  // anything that reads them; a definition no output reads is never emitted.
  void define(const std::vector<FilterDefinition>& definitions, const std::vector<GiNaC::ex>& variable_symbols);

  std::size_t polynomial(const Polynomial& p);
  // sum_k c_k x_k for terms (c_k, node of x_k), x_k = kOne for the number 1: the coefficients
  // and signs taken as polynomial() takes a polynomial's.
  static constexpr std::size_t kOne = static_cast<std::size_t>(-1);
  std::size_t combination(const std::vector<std::pair<GiNaC::ex, std::size_t>>& terms);
  std::size_t variable(std::uint32_t variable) { return variable_power(variable, 1); }
  std::size_t expression(const GiNaC::ex& e);

  // The inputs read from an argument, in the order a function declares them: the variables in
  // their order, then the parameters in the model's order.
  std::vector<std::size_t> declaration_order() const;
  InputUse uses(const std::vector<std::size_t>& outputs) const;

 private:
  std::size_t variable_power(std::uint32_t variable, std::uint32_t exponent);
  std::size_t integer_power(std::size_t base, long exponent);
  std::size_t monomial(const Monomial& m);
  std::size_t product(const GiNaC::ex& e);  // a GiNaC mul, its sums' signs made canonical
  // coefficient * factor() (just the coefficient when `unit`), its coefficient made positive, and
  // whether it was negative: factor() is called only when needed, so nodes are made in one order.
  template <class Factor>
  std::pair<std::size_t, bool> scaled(const GiNaC::ex& coefficient, bool unit, Factor factor);

  ExpressionGraph& graph_;
  std::vector<std::size_t> variable_inputs_;
  std::vector<std::string> variable_arrays_;
  std::vector<std::size_t> parameter_inputs_;
  std::size_t time_input_;
  std::map<GiNaC::ex, std::size_t, GiNaC::ex_is_less> symbols_;
};

}  // namespace pfgen::codegen
