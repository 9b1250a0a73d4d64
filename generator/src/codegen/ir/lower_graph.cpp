#include "pfgen/codegen/ir/lower_graph.hpp"

#include <functional>
#include <map>
#include <utility>

namespace pfgen::codegen::ir {

std::vector<Expr> indexed(const std::string& target, std::size_t count) {
  std::vector<Expr> out;
  for (std::size_t k = 0; k < count; ++k) out.push_back(element(target, k));
  return out;
}

std::set<std::size_t> inputs_read(const ExpressionGraph& graph, const std::vector<std::size_t>& outputs) {
  const std::vector<bool> needed = graph.needed(outputs);
  std::set<std::size_t> inputs;
  for (std::size_t id = 0; id < graph.size(); ++id)
    if (needed[id] && graph.node(id).kind == OpKind::Input) inputs.insert(id);
  return inputs;
}

Expr input_source(const Node& node) {
  switch (node.source().kind) {
    case InputSource::Kind::Argument: return name(node.name());
    case InputSource::Kind::Element: return element(node.source().container, node.source().index);
    case InputSource::Kind::Field: return field(node.source().container, node.name());
  }
  return name(node.name());
}

Expr leaf(const Node& node) {
  return node.kind == OpKind::Constant ? held_number(node.held_value()) : name(node.name());
}

Expr operation(const Node& node, std::vector<Expr> a) {
  switch (node.kind) {
    case OpKind::Input:
    case OpKind::Constant: return leaf(node);
    // The operands' vector becomes the node's (no copy, no second allocation).
    case OpKind::Add: return operator_node(Expr::Kind::Add, std::move(a));
    case OpKind::Sub: return operator_node(Expr::Kind::Sub, std::move(a));
    case OpKind::Mul: return operator_node(Expr::Kind::Mul, std::move(a));
    case OpKind::Div: return operator_node(Expr::Kind::Div, std::move(a));
    case OpKind::Neg: return operator_node(Expr::Kind::Neg, std::move(a));
    case OpKind::Call: return call(node.function, std::move(a));
    case OpKind::ZeroWhereZero: return operator_node(Expr::Kind::ZeroWhereZero, std::move(a));
  }
  return leaf(node);
}

Block input_declarations(const ExpressionGraph& graph, const std::set<std::size_t>& inputs,
                         const std::vector<std::size_t>& order) {
  Block block;
  for (std::size_t id : order) {
    const Node& node = graph.node(id);
    if (inputs.count(id) && node.source().kind != InputSource::Kind::Argument)
      block.push_back(declare(node.name(), Type::Scalar, input_source(node)));
  }
  return block;
}

Block unused_arguments(const ExpressionGraph& graph, const std::set<std::size_t>& inputs,
                       const FunctionSignature& signature) {
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
  Block block;
  if (!time) block.push_back(unused(signature.time));
  for (const std::string& array : signature.arrays)
    if (!arrays.count(array)) block.push_back(unused(array));
  if (!params) block.push_back(unused(signature.params));
  return block;
}

void shared_statements(const ExpressionGraph& graph, const std::vector<std::size_t>& outputs,
                       const std::vector<Expr>& destinations, const std::string& temporary_prefix,
                       const StatementSink& sink) {
  std::map<std::size_t, std::string> names;
  auto spell = [&](std::size_t id) { return graph.is_leaf(id) ? leaf(graph.node(id)) : name(names.at(id)); };
  for (std::size_t id : graph.needed_operations(outputs)) {
    const Node& node = graph.node(id);
    std::vector<Expr> operands;
    operands.reserve(node.args.size());
    for (std::size_t arg : node.args) operands.push_back(spell(arg));
    std::string temporary = temporary_prefix + std::to_string(names.size());
    sink(declare(temporary, Type::Scalar, operation(node, std::move(operands))));
    names[id] = std::move(temporary);
  }
  for (std::size_t k = 0; k < outputs.size(); ++k) sink(assign(destinations.at(k), spell(outputs[k])));
}

Block shared_statements(const ExpressionGraph& graph, const std::vector<std::size_t>& outputs,
                        const std::vector<Expr>& destinations, const std::string& temporary_prefix) {
  Block block;
  shared_statements(graph, outputs, destinations, temporary_prefix,
                    [&](Statement&& s) { block.push_back(std::move(s)); });
  return block;
}

Block tree_statements(const ExpressionGraph& graph, const std::vector<std::size_t>& outputs,
                      const std::vector<Expr>& destinations) {
  std::function<Expr(std::size_t)> spell = [&](std::size_t id) -> Expr {
    const Node& node = graph.node(id);
    if (graph.is_leaf(id)) return leaf(node);
    std::vector<Expr> operands;
    operands.reserve(node.args.size());
    for (std::size_t arg : node.args) operands.push_back(spell(arg));
    Expr e = operation(node, std::move(operands));
    return node.kind == OpKind::Call ? e : grouped(std::move(e));
  };
  Block block;
  for (std::size_t k = 0; k < outputs.size(); ++k) block.push_back(assign(destinations.at(k), spell(outputs[k])));
  return block;
}

std::size_t SplitPlan::writer(const ExpressionGraph& graph, std::size_t root) const {
  return graph.is_leaf(root) ? parts - 1 : part.at(root);
}

SplitPlan split_plan(const ExpressionGraph& graph, const std::vector<std::size_t>& outputs, std::size_t max_ops) {
  SplitPlan plan;
  plan.max_ops = max_ops;
  plan.operations = graph.needed_operations(outputs);
  plan.parts = (plan.operations.size() + max_ops - 1) / max_ops;
  plan.part.assign(graph.size(), SplitPlan::kNone);
  plan.number.assign(graph.size(), SplitPlan::kNone);
  plan.slot.assign(graph.size(), SplitPlan::kNone);
  for (std::size_t k = 0; k < plan.operations.size(); ++k) {
    plan.part[plan.operations[k]] = k / max_ops;
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

SplitBody split_statements(const ExpressionGraph& graph, const std::vector<std::size_t>& outputs,
                           const std::vector<Expr>& destinations, const std::string& temporary_prefix,
                           std::size_t max_ops, const std::string& shared_array) {
  SplitBody body;
  body.plan = split_statements(graph, outputs, destinations, temporary_prefix, max_ops, shared_array,
                               [&](const SplitPlan&, SplitPart&& part) { body.parts.push_back(std::move(part)); });
  return body;
}

SplitPlan split_statements(const ExpressionGraph& graph, const std::vector<std::size_t>& outputs,
                           const std::vector<Expr>& destinations, const std::string& temporary_prefix,
                           std::size_t max_ops, const std::string& shared_array,
                           const std::function<void(const SplitPlan& plan, SplitPart&& part)>& each) {
  SplitPlan plan = split_plan(graph, outputs, max_ops);
  // Each temporary's name made once (a name is read by every use of its value: formatting it at each
  // use was a tenth of the lowering's cost).
  std::vector<std::string> names(plan.operations.size());
  for (std::size_t k = 0; k < names.size(); ++k) names[k] = temporary_prefix + std::to_string(k);
  auto temporary = [&](std::size_t id) -> const std::string& { return names[plan.number.at(id)]; };
  auto spell = [&](std::size_t id) { return graph.is_leaf(id) ? leaf(graph.node(id)) : name(temporary(id)); };
  auto note_input = [&](SplitPart& part, std::size_t id) {
    if (graph.node(id).kind == OpKind::Input) part.inputs.insert(id);
  };
  std::size_t next = 0;
  for (std::size_t p = 0; p < plan.parts; ++p) {
    SplitPart part;
    part.reads.reserve(plan.reads[p].size());
    part.arithmetic.reserve(max_ops);
    for (std::size_t id : plan.reads[p])
      part.reads.push_back(declare(temporary(id), Type::Scalar, element(shared_array, plan.slot.at(id))));
    for (; next < plan.operations.size() && plan.part.at(plan.operations[next]) == p; ++next) {
      const std::size_t id = plan.operations[next];
      std::vector<Expr> operands;
      operands.reserve(graph.node(id).args.size());
      for (std::size_t arg : graph.node(id).args) {
        note_input(part, arg);
        operands.push_back(spell(arg));
      }
      part.arithmetic.push_back(declare(temporary(id), Type::Scalar, operation(graph.node(id), std::move(operands))));
      if (plan.slot[id] != SplitPlan::kNone)
        part.stores.push_back(assign(element(shared_array, plan.slot[id]), spell(id)));
    }
    for (std::size_t k = 0; k < outputs.size(); ++k)
      if (plan.writer(graph, outputs[k]) == p) {
        note_input(part, outputs[k]);
        part.writes.push_back(assign(destinations.at(k), spell(outputs[k])));
      }
    each(plan, std::move(part));
  }
  return plan;
}

}  // namespace pfgen::codegen::ir
