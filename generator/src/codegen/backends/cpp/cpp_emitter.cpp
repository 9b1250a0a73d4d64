#include "pfgen/codegen/backends/cpp/cpp_emitter.hpp"

#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <functional>
#include <map>

#include "pfgen/codegen/graph_builder.hpp"
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

// target[0], target[1], ...
std::vector<std::string> indexed(const std::string& target, std::size_t count) {
  std::vector<std::string> out;
  for (std::size_t k = 0; k < count; ++k) out.push_back(target + "[" + std::to_string(k) + "]");
  return out;
}

}  // namespace

std::string scalar_mode_name(ScalarMode mode) {
  switch (mode) {
    case ScalarMode::Template: return "template";
    case ScalarMode::Float: return "float";
    case ScalarMode::Double: return "double";
  }
  return "?";
}

std::string CppEmitter::literal(const GiNaC::numeric& value) const {
  const double d = value.to_double();
  // A constant beyond the scalar's range would print as `inf`, which is no C++ literal.
  if (!std::isfinite(d)) throw CodegenError("a constant is out of the range of double (above 1.8e308 in magnitude)");
  if (mode_ == ScalarMode::Float && !std::isfinite(static_cast<float>(d)))
    throw CodegenError("the constant " + shortest_double(d) +
                       " is out of the range of float (above 3.4e38 in magnitude); use --scalar double or template");
  // Nor may a nonzero constant become 0 unnoticed: below float's (or double's) smallest
  // subnormal it would, which changes the equations rather than rounding them.
  if (!value.is_zero() && d == 0)
    throw CodegenError("a nonzero constant is below the smallest positive double (4.9e-324 in magnitude) and would be 0");
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

std::string CppEmitter::call(Function function, const std::vector<std::string>& args) const {
  std::string out = std::string("std::") + function_name(function) + "(";
  for (std::size_t k = 0; k < args.size(); ++k) out += (k ? ", " : "") + args[k];
  return out + ")";
}

std::string CppEmitter::zero_where_zero(const std::string& guard, const std::string& value) const {
  const std::string zero = literal(GiNaC::numeric(0));
  return "(" + guard + " == " + zero + " ? " + zero + " : " + value + ")";
}

// The C++ that reads an input: `state[3]`, `params.a`, or the argument's own name.
std::string CppEmitter::input_source(const Node& node) const {
  switch (node.source.kind) {
    case InputSource::Kind::Argument: return node.name;
    case InputSource::Kind::Element: return node.source.container + "[" + std::to_string(node.source.index) + "]";
    case InputSource::Kind::Field: return node.source.container + "." + node.name;
  }
  return "?";
}

std::string CppEmitter::input_declarations(const ExpressionGraph& graph, const std::vector<std::size_t>& outputs,
                                           const std::vector<std::size_t>& order) const {
  const std::vector<bool> needed = graph.needed(outputs);
  std::string text;
  for (std::size_t id : order) {
    const Node& node = graph.node(id);
    if (needed.at(id) && node.kind == OpKind::Input && node.source.kind != InputSource::Kind::Argument)
      text += "  const Scalar " + node.name + " = " + input_source(node) + ";\n";
  }
  return text;
}

std::string CppEmitter::shared_body(const ExpressionGraph& graph, const std::vector<std::size_t>& outputs,
                                    const std::string& target) const {
  return shared_body(graph, outputs, indexed(target, outputs.size()));
}

std::string CppEmitter::shared_body(const ExpressionGraph& graph, const std::vector<std::size_t>& outputs,
                                    const std::vector<std::string>& destinations) const {
  if (max_ops_ != 0 && graph.needed_operations(outputs).size() > max_ops_)
    return chunked_body(graph, outputs, destinations);
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
    std::string name = temporary_prefix_ + std::to_string(names.size());
    body += "  const Scalar " + name + " = " + expression(node, operands) + ";\n";
    names[id] = name;
  }
  for (std::size_t k = 0; k < outputs.size(); ++k)
    body += "  " + destinations.at(k) + " = " + spell(outputs[k]) + ";\n";
  return body;
}

void CppEmitter::split_above(std::size_t max_ops, std::string shared_array) {
  max_ops_ = max_ops;
  shared_array_ = std::move(shared_array);
}

std::string CppEmitter::tree_body(const ExpressionGraph& graph, const std::vector<std::size_t>& outputs,
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

}  // namespace pfgen::codegen
