#include "pfgen/codegen/ir/statement_emitter.hpp"

#include <utility>

namespace pfgen::codegen {

std::string StatementEmitter::expression(const ir::Expr& e) const {
  using Kind = ir::Expr::Kind;
  // Leaves and operators (nearly every node of a lowered graph) without a vector of their
  // operands' texts: this is the inner loop of writing a function of 10^5 operations. Operands are
  // written first to last (a constant out of range throws, and the first one names itself).
  auto first = [&] { return expression(e.operands.at(0)); };
  std::string text;
  switch (e.kind) {
    case Kind::Name: text = name(e.name); break;
    case Kind::Integer: text = integer(e.integer); break;
    case Kind::Number: text = constant(*e.number); break;
    case Kind::Boolean: text = boolean(e.integer != 0); break;
    case Kind::Element: text = element(e.name, first()); break;
    case Kind::Field: text = field(first(), e.name); break;
    case Kind::Neg: text = neg(first()); break;
    case Kind::Not: text = logical_not(first()); break;
    case Kind::LocalArray: text = local_array(e.name, e.integer != 0); break;
    case Kind::Dimension: text = dimension(e.name); break;
    case Kind::WholeScalar: text = whole_scalar(e.integer); break;
    case Kind::ArrayFrom: text = array_from(e.name, first(), e.integer != 0); break;
    case Kind::PostIncrement: text = post_increment(e.name); break;
    case Kind::FileCall:
      text = call_text(e.integer != 0 ? internal_function(e.name) : file_function(e.name), e.operands);
      break;
    case Kind::ToScalar: text = e.integer != 0 ? cast_to_scalar(e.operands.at(0)) : to_scalar(first()); break;
    case Kind::FileScalar: text = file_scalar(e.name); break;
    case Kind::PackedEntry: {
      const std::string a = first();
      text = packed_entry(e.name, a, expression(e.operands.at(1)));
      break;
    }
    case Kind::Add:
    case Kind::Sub:
    case Kind::Mul:
    case Kind::Div:
    case Kind::ZeroWhereZero:
    case Kind::Greater:
    case Kind::Less:
    case Kind::Equal:
    case Kind::Or:
    case Kind::And:
    case Kind::Rem: {
      const std::string a = first();
      const std::string b = expression(e.operands.at(1));
      if (e.kind == Kind::Add) text = add(a, b);
      if (e.kind == Kind::Sub) text = sub(a, b);
      if (e.kind == Kind::Mul) text = mul(a, b);
      if (e.kind == Kind::Div) text = div(a, b);
      if (e.kind == Kind::ZeroWhereZero) text = zero_where_zero(a, b);
      if (e.kind == Kind::Greater) text = greater(a, b);
      if (e.kind == Kind::Less) text = less(a, b);
      if (e.kind == Kind::Equal) text = equal(a, b);
      if (e.kind == Kind::Or) text = logical_or(a, b);
      if (e.kind == Kind::And) text = logical_and(a, b);
      if (e.kind == Kind::Rem) text = rem(a, b);
      break;
    }
    case Kind::Select: {
      const std::string condition = first();
      const std::string if_true = expression(e.operands.at(1));
      text = select(condition, if_true, expression(e.operands.at(2)));
      break;
    }
    case Kind::Slice: text = slice(e); break;
    case Kind::Call: {
      std::vector<std::string> a;
      a.reserve(e.operands.size());
      for (const ir::Expr& operand : e.operands) a.push_back(expression(operand));
      text = call(e.function, a);
      break;
    }
  }
  if (e.grouped) return grouped(text);
  return text;
}

std::string StatementEmitter::call_text(const std::string& callee, const std::vector<ir::Expr>& arguments) const {
  std::string text = callee + "(";
  for (std::size_t k = 0; k < arguments.size(); ++k) text += (k ? ", " : "") + expression(arguments[k]);
  return text + ")";
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
    case Kind::Scope: return scope(s.scope(), indent);
  }
  return "";
}

std::string StatementEmitter::block(const ir::Block& statements, const std::string& indent) const {
  std::string text;
  for (const ir::Statement& s : statements) {
    text += indent;
    text += statement(s, indent);
    text += '\n';
  }
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
                          [&](ir::Statement&& s) {
                            text += indent;
                            text += statement(s, indent);
                            text += '\n';
                          });
  else
    text += block(ir::tree_statements(graph, outputs, targets));
  return {"", text};
}

void StatementEmitter::split_above(std::size_t max_ops, std::string shared_array) {
  max_ops_ = max_ops;
  shared_array_ = std::move(shared_array);
}

}  // namespace pfgen::codegen
