#include "pfgen/codegen/backends/c_family/c_family_emitter.hpp"

#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <functional>

#include "pfgen/codegen/codegen_error.hpp"
#include "pfgen/model/decimal_literals.hpp"
#include "pfgen/notation/number_format.hpp"

namespace pfgen::codegen {
namespace {

std::string with_point(std::string text) {
  if (text.find_first_of(".eE") == std::string::npos) text += ".0";
  return text;
}

std::string shortest_float(float value) {
  char buffer[40];
  for (int precision = 1; precision <= 9; ++precision) {
    std::snprintf(buffer, sizeof buffer, "%.*g", precision, static_cast<double>(value));
    if (std::strtof(buffer, nullptr) == value) break;
  }
  return buffer;
}

}  // namespace

std::vector<std::string> indexed(const std::string& target, std::size_t count) {
  std::vector<std::string> out;
  for (std::size_t k = 0; k < count; ++k) out.push_back(target + "[" + std::to_string(k) + "]");
  return out;
}

std::string scalar_mode_name(ScalarMode mode) {
  switch (mode) {
    case ScalarMode::Template: return "template";
    case ScalarMode::Float: return "float";
    case ScalarMode::Double: return "double";
  }
  return "?";
}

std::string CFamilyEmitter::literal(const GiNaC::numeric& value) const {
  const double d = value.to_double();
  // A constant beyond the scalar's range would print as `inf`, which is no literal.
  if (!std::isfinite(d))
    throw CodegenError("the constant, about " + approximate_text(value) +
                       ", is beyond the largest double (about 1.8e308 in magnitude); a lower degree keeps the "
                       "equations' numbers in range");
  if (mode_ == ScalarMode::Float && !std::isfinite(static_cast<float>(d)))
    throw CodegenError("the constant " + shortest_double(d) +
                       " is out of the range of float (above 3.4e38 in magnitude); use --scalar double or template");
  // Nor may a nonzero constant become 0 unnoticed: below float's (or double's) range it would,
  // which changes the equations rather than rounding them. GiNaC gives no subnormal doubles
  // (1e-310 becomes 0), so double's limit is the smallest normal one.
  if (!value.is_zero() && d == 0)
    throw CodegenError("the constant, about " + approximate_text(value) +
                       ", is below the smallest normal double (about 2.2e-308 in magnitude) and would be 0");
  if (mode_ == ScalarMode::Float && d != 0 && static_cast<float>(d) == 0.0f)
    throw CodegenError("the constant " + shortest_double(d) +
                       " is below the smallest positive float (1.4e-45 in magnitude) and would be 0; use --scalar "
                       "double or template");
  std::string text;
  switch (mode_) {
    case ScalarMode::Float: text = with_point(shortest_float(static_cast<float>(d))) + "f"; break;
    case ScalarMode::Double: text = with_point(shortest_double(d)); break;
    case ScalarMode::Template:
      text = value.is_integer() && GiNaC::abs(value) < 1000000 ? "Scalar(" + shortest_double(d) + ")"
                                                              : "Scalar(" + with_point(shortest_double(d)) + ")";
      break;
  }
  return d < 0 ? "(" + text + ")" : text;
}

std::string CFamilyEmitter::zero_where_zero(const std::string& guard, const std::string& value) const {
  const std::string zero = literal(GiNaC::numeric(0));
  return "(" + guard + " == " + zero + " ? " + zero + " : " + value + ")";
}

std::string CFamilyEmitter::input_source(const Node& node) const {
  switch (node.source().kind) {
    case InputSource::Kind::Argument: return node.name();
    case InputSource::Kind::Element: return node.source().container + "[" + std::to_string(node.source().index) + "]";
    case InputSource::Kind::Field: return node.source().container + field_access() + node.name();
  }
  return "?";
}

std::set<std::size_t> CFamilyEmitter::inputs_read(const ExpressionGraph& graph, const std::vector<std::size_t>& outputs) {
  const std::vector<bool> needed = graph.needed(outputs);
  std::set<std::size_t> inputs;
  for (std::size_t id = 0; id < graph.size(); ++id)
    if (needed[id] && graph.node(id).kind == OpKind::Input) inputs.insert(id);
  return inputs;
}

std::string CFamilyEmitter::declarations_of(const ExpressionGraph& graph, const std::set<std::size_t>& inputs,
                                            const std::vector<std::size_t>& order) const {
  std::string text;
  for (std::size_t id : order) {
    const Node& node = graph.node(id);
    if (inputs.count(id) && node.source().kind != InputSource::Kind::Argument)
      text += "  " + declaration(node.name(), input_source(node)) + "\n";
  }
  return text;
}

std::string CFamilyEmitter::input_declarations(const ExpressionGraph& graph, const std::vector<std::size_t>& outputs,
                                               const std::vector<std::size_t>& order) const {
  return declarations_of(graph, inputs_read(graph, outputs), order);
}

std::string CFamilyEmitter::unused_arguments_of(const ExpressionGraph& graph, const std::set<std::size_t>& inputs,
                                                const FunctionSignature& signature) const {
  bool time = false, params = false;
  std::set<std::string> arrays;
  for (std::size_t id : inputs) {
    const Node& node = graph.node(id);
    switch (node.source().kind) {
      case InputSource::Kind::Argument: time = time || node.name() == signature.time; break;
      case InputSource::Kind::Element: arrays.insert(node.source().container); break;
      case InputSource::Kind::Field: params = true; break;
    }
  }
  std::string text;
  if (!time) text += "  " + ignored(signature.time) + "\n";
  for (const std::string& array : signature.arrays)
    if (!arrays.count(array)) text += "  " + ignored(array) + "\n";
  if (!params) text += "  " + ignored(signature.params) + "\n";
  return text;
}

std::string CFamilyEmitter::unused_arguments(const ExpressionGraph& graph, const std::vector<std::size_t>& outputs,
                                             const FunctionSignature& signature) const {
  return unused_arguments_of(graph, inputs_read(graph, outputs), signature);
}

std::string CFamilyEmitter::shared_body(const ExpressionGraph& graph, const std::vector<std::size_t>& outputs,
                                        const std::string& target) const {
  return shared_body(graph, outputs, indexed(target, outputs.size()));
}

std::string CFamilyEmitter::shared_body(const ExpressionGraph& graph, const std::vector<std::size_t>& outputs,
                                        const std::vector<std::string>& destinations) const {
  std::map<std::size_t, std::string> names;
  auto spell = [&](std::size_t id) {
    if (graph.is_leaf(id)) return expression(graph.node(id), {});
    return names.at(id);
  };
  std::string body;
  for (std::size_t id : graph.needed_operations(outputs)) {
    const Node& node = graph.node(id);
    std::vector<std::string> operands;
    for (std::size_t arg : node.args) operands.push_back(spell(arg));
    std::string name = temporary(names.size());
    body += "  " + declaration(name, expression(node, operands)) + "\n";
    names[id] = name;
  }
  for (std::size_t k = 0; k < outputs.size(); ++k)
    body += "  " + destinations.at(k) + " = " + spell(outputs[k]) + ";\n";
  return body;
}

std::string CFamilyEmitter::tree_body(const ExpressionGraph& graph, const std::vector<std::size_t>& outputs,
                                      const std::string& target) const {
  std::function<std::string(std::size_t)> spell = [&](std::size_t id) -> std::string {
    const Node& node = graph.node(id);
    if (graph.is_leaf(id)) return expression(node, {});
    std::vector<std::string> operands;
    for (std::size_t arg : node.args) operands.push_back(spell(arg));
    std::string text = expression(node, operands);
    return node.kind == OpKind::Call ? text : "(" + text + ")";
  };
  std::string body;
  const std::vector<std::string> destinations = indexed(target, outputs.size());
  for (std::size_t k = 0; k < outputs.size(); ++k) body += "  " + destinations[k] + " = " + spell(outputs[k]) + ";\n";
  return body;
}

FunctionBody CFamilyEmitter::function_body(const ExpressionGraph& graph, const std::vector<std::size_t>& outputs,
                                           const FunctionSignature& signature, const std::vector<std::size_t>& order,
                                           bool shared) const {
  if (shared && max_ops_ != 0 && graph.needed_operations(outputs).size() > max_ops_)
    return split_body(graph, outputs, signature, order);
  FunctionBody body;
  body.statements = unused_arguments(graph, outputs, signature) + input_declarations(graph, outputs, order) +
                    (shared ? shared_body(graph, outputs, signature.target) : tree_body(graph, outputs, signature.target));
  return body;
}

void CFamilyEmitter::split_above(std::size_t max_ops, std::string shared_array) {
  max_ops_ = max_ops;
  shared_array_ = std::move(shared_array);
}

std::size_t CFamilyEmitter::SplitPlan::writer(const ExpressionGraph& graph, std::size_t root) const {
  return graph.is_leaf(root) ? parts - 1 : part.at(root);
}

CFamilyEmitter::SplitPlan CFamilyEmitter::split_plan(const ExpressionGraph& graph,
                                                     const std::vector<std::size_t>& outputs) const {
  SplitPlan plan;
  plan.operations = graph.needed_operations(outputs);
  plan.parts = (plan.operations.size() + max_ops_ - 1) / max_ops_;
  plan.part.assign(graph.size(), SplitPlan::kNone);
  plan.number.assign(graph.size(), SplitPlan::kNone);
  plan.slot.assign(graph.size(), SplitPlan::kNone);
  for (std::size_t k = 0; k < plan.operations.size(); ++k) {
    plan.part[plan.operations[k]] = k / max_ops_;
    plan.number[plan.operations[k]] = k;
  }
  plan.reads.resize(plan.parts);
  for (std::size_t id : plan.operations)
    for (std::size_t arg : graph.node(id).args)
      if (!graph.is_leaf(arg) && plan.part[arg] != plan.part[id]) plan.reads[plan.part[id]].insert(arg);
  // Slots in the order of the values' node numbers.
  std::vector<bool> stored(graph.size(), false);
  for (const auto& part : plan.reads)
    for (std::size_t id : part) stored[id] = true;
  for (std::size_t id = 0; id < graph.size(); ++id)
    if (stored[id]) plan.slot[id] = plan.slots++;
  return plan;
}

}  // namespace pfgen::codegen
