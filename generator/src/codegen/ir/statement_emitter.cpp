#include "pfgen/codegen/ir/statement_emitter.hpp"

#include <utility>

namespace pfgen::codegen {

std::string StatementEmitter::expression(const ir::Expr& e) const {
  using Kind = ir::Expr::Kind;
  std::vector<std::string> a;
  for (const ir::Expr& operand : e.operands) a.push_back(expression(operand));
  std::string text;
  switch (e.kind) {
    case Kind::Name: text = name(e.name); break;
    case Kind::Integer: text = integer(e.integer); break;
    case Kind::Number: text = constant(e.number); break;
    case Kind::Boolean: text = boolean(e.integer != 0); break;
    case Kind::Element: text = element(e.name, a.at(0)); break;
    case Kind::Field: text = field(a.at(0), e.name); break;
    case Kind::Add: text = add(a.at(0), a.at(1)); break;
    case Kind::Sub: text = sub(a.at(0), a.at(1)); break;
    case Kind::Mul: text = mul(a.at(0), a.at(1)); break;
    case Kind::Div: text = div(a.at(0), a.at(1)); break;
    case Kind::Neg: text = neg(a.at(0)); break;
    case Kind::Call: text = call(e.function, a); break;
    case Kind::ZeroWhereZero: text = zero_where_zero(a.at(0), a.at(1)); break;
    case Kind::Greater: text = greater(a.at(0), a.at(1)); break;
    case Kind::Not: text = logical_not(a.at(0)); break;
    case Kind::LocalArray: text = local_array(e.name, e.integer != 0); break;
    case Kind::Dimension: text = dimension(e.name); break;
    case Kind::WholeScalar: text = whole_scalar(e.integer); break;
  }
  return e.grouped ? grouped(text) : text;
}

std::string StatementEmitter::statement(const ir::Statement& s, const std::string& indent) const {
  using Kind = ir::Statement::Kind;
  switch (s.kind) {
    case Kind::Declaration: return declaration(s.declaration(), indent);
    case Kind::View: return view(s.view(), indent);
    case Kind::Assignment: return assignment(s.assignment(), indent);
    case Kind::Loop: return loop(s.loop(), indent);
    case Kind::Call: return call_statement(s.call(), indent);
    case Kind::Conditional: return conditional(s.conditional(), indent);
    case Kind::Return: return return_statement(s.result(), indent);
    case Kind::Comment: return comment(s.comment(), indent);
    case Kind::Unused: return unused(s.unused(), indent);
    case Kind::Arrays: return arrays(s.arrays(), indent);
  }
  return "";
}

std::string StatementEmitter::block(const ir::Block& statements, const std::string& indent) const {
  std::string text;
  for (const ir::Statement& s : statements) text += indent + statement(s, indent) + "\n";
  return text;
}

std::string StatementEmitter::input_declarations(const ExpressionGraph& graph, const std::vector<std::size_t>& outputs,
                                                 const std::vector<std::size_t>& order) const {
  return block(ir::input_declarations(graph, ir::inputs_read(graph, outputs), order));
}

std::string StatementEmitter::unused_arguments(const ExpressionGraph& graph, const std::vector<std::size_t>& outputs,
                                               const FunctionSignature& signature) const {
  return block(ir::unused_arguments(graph, ir::inputs_read(graph, outputs), signature));
}

std::string StatementEmitter::shared_body(const ExpressionGraph& graph, const std::vector<std::size_t>& outputs,
                                          const std::string& target) const {
  return block(ir::shared_statements(graph, outputs, ir::indexed(target, outputs.size()), temporary_prefix_));
}

std::string StatementEmitter::shared_body(const ExpressionGraph& graph, const std::vector<std::size_t>& outputs,
                                          const std::vector<std::string>& destinations) const {
  std::vector<ir::Expr> targets;
  for (const std::string& destination : destinations) targets.push_back(ir::name(destination));
  return block(ir::shared_statements(graph, outputs, targets, temporary_prefix_));
}

std::string StatementEmitter::tree_body(const ExpressionGraph& graph, const std::vector<std::size_t>& outputs,
                                        const std::string& target) const {
  return block(ir::tree_statements(graph, outputs, ir::indexed(target, outputs.size())));
}

FunctionBody StatementEmitter::function_body(const ExpressionGraph& graph, const std::vector<std::size_t>& outputs,
                                             const FunctionSignature& signature,
                                             const std::vector<std::size_t>& order, bool shared) const {
  if (shared && max_ops_ != 0 && graph.needed_operations(outputs).size() > max_ops_)
    return split_body(graph, outputs, signature, order);
  const std::set<std::size_t> inputs = ir::inputs_read(graph, outputs);
  const std::vector<ir::Expr> targets = ir::indexed(signature.target, outputs.size());
  std::string text =
      block(ir::unused_arguments(graph, inputs, signature)) + block(ir::input_declarations(graph, inputs, order));
  // Each statement written as it is made: a function's statements are not all held at once.
  const std::string indent = "  ";
  if (shared)
    ir::shared_statements(graph, outputs, targets, temporary_prefix_,
                          [&](ir::Statement&& s) { text += indent + statement(s, indent) + "\n"; });
  else
    text += block(ir::tree_statements(graph, outputs, targets));
  return {"", text};
}

void StatementEmitter::split_above(std::size_t max_ops, std::string shared_array) {
  max_ops_ = max_ops;
  shared_array_ = std::move(shared_array);
}

}  // namespace pfgen::codegen
