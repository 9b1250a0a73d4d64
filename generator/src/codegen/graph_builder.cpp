#include "pfgen/codegen/graph_builder.hpp"

#include <algorithm>
#include <utility>

#include "pfgen/kinds/model_functions.hpp"
#include "pfgen/notation/text_printer.hpp"

namespace pfgen::codegen {
namespace {

// Operands of sums and products in the order of their canonical text, so the
// generated code does not depend on GiNaC's address-seeded term order.
std::vector<GiNaC::ex> canonical_operands(const GiNaC::ex& e) {
  std::vector<std::pair<std::string, GiNaC::ex>> keyed;
  TextPrinter printer;
  for (std::size_t k = 0; k < e.nops(); ++k) keyed.emplace_back(printer.print(e.op(k)), e.op(k));
  std::stable_sort(keyed.begin(), keyed.end(), [](const auto& a, const auto& b) { return a.first < b.first; });
  std::vector<GiNaC::ex> out;
  for (auto& k : keyed) out.push_back(k.second);
  return out;
}

std::vector<std::string> text_names(const FilterVariables& variables) {
  std::vector<std::string> names;
  for (std::size_t v = 0; v < variables.count(); ++v)
    names.push_back(variables.text_name(static_cast<std::uint32_t>(v)));
  return names;
}

}  // namespace

GraphBuilder::GraphBuilder(ExpressionGraph& graph, const Model& model, const FilterVariables& variables,
                           const std::string& array, const std::string& params)
    : GraphBuilder(graph, model, text_names(variables), array, params) {}

// The inputs are created first, parameters, time, then the variables in their order, so that
// node numbers (and with them the operand order of every commutative operation) do not depend
// on which input an equation happens to read first.
GraphBuilder::GraphBuilder(ExpressionGraph& graph, const Model& model, std::vector<std::string> names,
                           const std::string& array, const std::string& params)
    : GraphBuilder(graph, model, names, std::vector<std::string>(names.size(), array),
                   [&] {
                     std::vector<std::size_t> indices(names.size());
                     for (std::size_t v = 0; v < indices.size(); ++v) indices[v] = v;
                     return indices;
                   }(),
                   params) {}

GraphBuilder::GraphBuilder(ExpressionGraph& graph, const Model& model, std::vector<std::string> names,
                           const std::vector<std::string>& arrays, const std::vector<std::size_t>& indices,
                           const std::string& params)
    : graph_(graph), variable_arrays_(arrays) {
  for (const auto& p : model.parameters) {
    parameter_inputs_.push_back(graph_.input(p.name, InputSource::field(params)));
    symbols_[p.symbol] = parameter_inputs_.back();
  }
  time_input_ = graph_.input(model.time.get_name());
  symbols_[model.time] = time_input_;
  for (std::size_t v = 0; v < names.size(); ++v)
    variable_inputs_.push_back(graph_.input(names[v], InputSource::element(arrays.at(v), indices.at(v))));
}

std::vector<std::size_t> GraphBuilder::declaration_order() const {
  std::vector<std::size_t> order = variable_inputs_;
  order.insert(order.end(), parameter_inputs_.begin(), parameter_inputs_.end());
  return order;
}

InputUse GraphBuilder::uses(const std::vector<std::size_t>& outputs) const {
  const std::vector<bool> needed = graph_.needed(outputs);
  auto any = [&](const std::vector<std::size_t>& ids) {
    return std::any_of(ids.begin(), ids.end(), [&](std::size_t id) { return needed[id]; });
  };
  InputUse use;
  use.variables = any(variable_inputs_);
  for (std::size_t v = 0; v < variable_inputs_.size(); ++v)
    if (needed[variable_inputs_[v]]) use.arrays.insert(variable_arrays_[v]);
  use.parameters = any(parameter_inputs_);
  use.time = needed[time_input_];
  return use;
}

void GraphBuilder::define(const std::vector<FilterDefinition>& definitions,
                          const std::vector<GiNaC::ex>& variable_symbols) {
  for (std::size_t v = 0; v < variable_symbols.size() && v < variable_inputs_.size(); ++v)
    symbols_[variable_symbols[v]] = variable_inputs_[v];
  for (const auto& d : definitions) {
    const std::size_t value = expression(d.value);
    symbols_[d.name] = d.zero_where_zero ? graph_.zero_where_zero(expression(*d.zero_where_zero), value) : value;
  }
}

std::size_t GraphBuilder::variable_power(std::uint32_t variable, std::uint32_t exponent) {
  return integer_power(variable_inputs_.at(variable), exponent);
}

std::size_t GraphBuilder::integer_power(std::size_t base, long exponent) {
  if (exponent < 0) return graph_.div(graph_.constant(1), integer_power(base, -exponent));
  if (exponent == 0) return graph_.constant(1);
  if (exponent == 1) return base;
  std::size_t half = integer_power(base, exponent / 2);
  std::size_t square = graph_.mul(half, half);
  return exponent % 2 ? graph_.mul(square, base) : square;
}

std::size_t GraphBuilder::monomial(const Monomial& m) {
  std::size_t product = 0;
  bool first = true;
  for (const auto& [variable, exponent] : m.factors()) {
    std::size_t power = variable_power(variable, exponent);
    product = first ? power : graph_.mul(product, power);
    first = false;
  }
  return first ? graph_.constant(1) : product;
}

void SignedSum::add(std::size_t term, bool negative) {
  if (empty_) {
    sum_ = term;
    negated_ = negative;
    empty_ = false;
  } else if (negated_) {
    sum_ = negative ? graph_.add(sum_, term) : graph_.sub(term, sum_);
    negated_ = negative;
  } else {
    sum_ = negative ? graph_.sub(sum_, term) : graph_.add(sum_, term);
  }
}

std::size_t SignedSum::result() const {
  if (empty_) return graph_.constant(0);
  return negated_ ? graph_.neg(sum_) : sum_;
}

template <class Factor>
std::pair<std::size_t, bool> GraphBuilder::scaled(const GiNaC::ex& coefficient, bool unit, Factor factor) {
  if (GiNaC::is_exactly_a<GiNaC::numeric>(coefficient)) {
    GiNaC::numeric c = GiNaC::ex_to<GiNaC::numeric>(coefficient);
    const bool negative = c.is_negative();
    if (negative) c = -c;
    return {unit ? graph_.constant(c) : (c == 1 ? factor() : graph_.mul(graph_.constant(c), factor())), negative};
  }
  // A product with a negative number (-mu, -2 a b) is subtracted as its positive (mu, 2 a b): the
  // same value exactly, without the operation that negates the coefficient.
  const bool negative = GiNaC::is_exactly_a<GiNaC::mul>(coefficient) &&
                        coefficient.op(coefficient.nops() - 1).info(GiNaC::info_flags::negative);
  const GiNaC::ex positive = negative ? -coefficient : coefficient;
  return {unit ? expression(positive) : graph_.mul(expression(positive), factor()), negative};
}

std::size_t GraphBuilder::polynomial(const Polynomial& p) {
  SignedSum sum(graph_);
  for (const auto* entry : p.ordered_view()) {
    const auto& [m, coefficient] = *entry;
    const auto [term, negative] = scaled(coefficient, m.is_one(), [&] { return monomial(m); });
    sum.add(term, negative);
  }
  return sum.result();
}

std::size_t GraphBuilder::combination(const std::vector<std::pair<GiNaC::ex, std::size_t>>& terms) {
  SignedSum sum(graph_);
  for (const auto& [coefficient, node] : terms) {
    const auto [term, negative] = scaled(coefficient, node == kOne, [node = node] { return node; });
    sum.add(term, negative);
  }
  return sum.result();
}

// A product's factors in the order of their printed text, its sums with pfgen's sign
// (canonical_sum_factor, as the printers take them): a negated sum's odd power moves its sign to
// the product's number, so that every run gives one graph. The negated sum's power is built here,
// not by GiNaC, which would move the sign back out.
std::size_t GraphBuilder::product(const GiNaC::ex& e) {
  struct Factor {
    std::string key;       // the printed text the factors are ordered by
    GiNaC::ex value;       // the factor, or the sum a power is taken of
    long exponent = 0;     // 0: `value` is the factor itself
  };
  const TextPrinter printer;
  std::vector<Factor> factors;
  GiNaC::numeric number = 1;
  for (std::size_t k = 0; k < e.nops(); ++k) {
    const GiNaC::ex op = e.op(k);
    if (GiNaC::is_exactly_a<GiNaC::numeric>(op)) {
      number *= GiNaC::ex_to<GiNaC::numeric>(op);
      continue;
    }
    const std::optional<CanonicalSumFactor> sum = canonical_sum_factor(op, printer);
    if (!sum || !sum->negated) {
      factors.push_back(Factor{printer.print(op), op, 0});
      continue;
    }
    if (sum->flips_sign()) number = -number;
    // Keyed by the text of the factor it stands for, as the other run's factor is keyed (the
    // printer makes that text canonical too, however GiNaC holds the power).
    factors.push_back(Factor{printer.print(GiNaC::pow(sum->sum, sum->exponent)), sum->sum, sum->exponent});
  }
  // The number as GiNaC would hold it: a factor unless it is 1; -1 negates the product instead of
  // multiplying it (the same value exactly), which a sum then takes as a subtraction.
  const bool negated = number == -1;
  if (number != 1 && !negated) factors.push_back(Factor{printer.print(number), number, 0});
  std::stable_sort(factors.begin(), factors.end(), [](const Factor& a, const Factor& b) { return a.key < b.key; });
  auto node = [&](const Factor& f) {
    if (f.exponent == 0) return expression(f.value);
    const std::size_t base = expression(f.value);
    return f.exponent == 1 ? base : integer_power(base, f.exponent);
  };
  std::size_t out = node(factors[0]);
  for (std::size_t k = 1; k < factors.size(); ++k) out = graph_.mul(out, node(factors[k]));
  return negated ? graph_.neg(out) : out;
}

std::size_t GraphBuilder::expression(const GiNaC::ex& e) {
  if (GiNaC::is_exactly_a<GiNaC::numeric>(e)) {
    const GiNaC::numeric& value = GiNaC::ex_to<GiNaC::numeric>(e);
    if (!value.is_real()) throw CodegenError("complex number in a coefficient");
    return value.is_negative() ? graph_.neg(graph_.constant(-value)) : graph_.constant(value);
  }
  if (GiNaC::is_exactly_a<GiNaC::symbol>(e)) {
    auto it = symbols_.find(e);
    if (it == symbols_.end()) throw CodegenError("unknown symbol in a coefficient");
    return it->second;
  }
  if (GiNaC::is_exactly_a<GiNaC::add>(e)) {
    std::vector<GiNaC::ex> ops = canonical_operands(e);
    std::size_t sum = expression(ops[0]);
    for (std::size_t k = 1; k < ops.size(); ++k) sum = graph_.add(sum, expression(ops[k]));
    return sum;
  }
  if (GiNaC::is_exactly_a<GiNaC::mul>(e)) return product(e);
  if (GiNaC::is_exactly_a<GiNaC::power>(e)) {
    const GiNaC::ex& exponent = e.op(1);
    std::size_t base = expression(e.op(0));
    if (exponent.info(GiNaC::info_flags::integer))
      return integer_power(base, GiNaC::ex_to<GiNaC::numeric>(exponent).to_long());
    if (exponent == GiNaC::numeric(1, 2)) return graph_.call(Function::Sqrt, {base});
    return graph_.call(Function::Pow, {base, expression(exponent)});
  }
  if (GiNaC::is_a<GiNaC::function>(e)) {
    std::string name = GiNaC::ex_to<GiNaC::function>(e).get_name();
    // A model's functions of time and parameters; sqrt and pow are powers in GiNaC, never functions.
    const std::optional<Function> function = function_named(name);
    if (!function || *function == Function::Sqrt || *function == Function::Pow)
      throw CodegenError("function '" + name + "' is not one a model may call (" + model_function_list() + ")");
    std::vector<std::size_t> args;
    for (std::size_t k = 0; k < e.nops(); ++k) args.push_back(expression(e.op(k)));
    return graph_.call(*function, args);
  }
  if (GiNaC::is_exactly_a<GiNaC::constant>(e)) return graph_.constant(GiNaC::ex_to<GiNaC::numeric>(e.evalf()));
  throw CodegenError("cannot generate code for '" + TextPrinter().print(e) + "'");
}

}  // namespace pfgen::codegen
