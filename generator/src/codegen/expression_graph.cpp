#include "pfgen/codegen/expression_graph.hpp"

#include <algorithm>
#include <sstream>

namespace pfgen::codegen {

namespace {
const std::pair<Function, const char*> kFunctionNames[] = {
    {Function::Sin, "sin"},   {Function::Cos, "cos"},   {Function::Tan, "tan"},   {Function::Exp, "exp"},
    {Function::Log, "log"},   {Function::Sinh, "sinh"}, {Function::Cosh, "cosh"}, {Function::Tanh, "tanh"},
    {Function::Asin, "asin"}, {Function::Acos, "acos"}, {Function::Atan, "atan"}, {Function::Abs, "abs"},
    {Function::Sqrt, "sqrt"}, {Function::Pow, "pow"}};
}  // namespace

const char* function_name(Function function) {
  for (const auto& [f, name] : kFunctionNames)
    if (f == function) return name;
  return "?";
}

std::optional<Function> function_named(const std::string& name) {
  for (const auto& [f, known] : kFunctionNames)
    if (name == known) return f;
  return std::nullopt;
}

namespace {

// A node of `kind` on `args`; the fields of the other kinds (a name, a source, a function, a
// value) keep their defaults.
Node operation(OpKind kind, std::vector<std::size_t> args) {
  Node node{};
  node.kind = kind;
  node.args = std::move(args);
  return node;
}

OpCounts own_cost(const Node& node) {
  OpCounts c;
  switch (node.kind) {
    case OpKind::Add: case OpKind::Sub: case OpKind::Neg: c.adds = 1; break;
    case OpKind::Mul: c.muls = 1; break;
    case OpKind::Div: c.divs = 1; break;
    case OpKind::Call: c.calls = 1; break;
    case OpKind::ZeroWhereZero: c.adds = 1; break;  // a comparison and a select
    case OpKind::Input: case OpKind::Constant: break;
  }
  return c;
}

}  // namespace

OpCounts& OpCounts::operator+=(const OpCounts& other) {
  adds += other.adds;
  muls += other.muls;
  divs += other.divs;
  calls += other.calls;
  return *this;
}

std::size_t ExpressionGraph::intern(Node node) {
  std::ostringstream value;
  if (node.kind == OpKind::Constant) value << node.value;
  const std::string name = node.kind == OpKind::Call ? function_name(node.function) : node.name;
  Key key{static_cast<int>(node.kind), name, value.str(), node.args};
  auto it = index_.find(key);
  if (it != index_.end()) return it->second;
  nodes_.push_back(std::move(node));
  index_.emplace(std::move(key), nodes_.size() - 1);
  return nodes_.size() - 1;
}

std::size_t ExpressionGraph::input(const std::string& name, InputSource source) {
  Node node = operation(OpKind::Input, {});
  node.name = name;
  node.source = std::move(source);
  return intern(std::move(node));
}

std::size_t ExpressionGraph::constant(const GiNaC::numeric& value) {
  Node node = operation(OpKind::Constant, {});
  node.value = value;
  return intern(std::move(node));
}

// Commutative operations list their operands in a fixed order, so a*b and b*a share a node.
std::size_t ExpressionGraph::add(std::size_t a, std::size_t b) {
  return intern(operation(OpKind::Add, {std::min(a, b), std::max(a, b)}));
}
std::size_t ExpressionGraph::sub(std::size_t a, std::size_t b) { return intern(operation(OpKind::Sub, {a, b})); }
std::size_t ExpressionGraph::mul(std::size_t a, std::size_t b) {
  return intern(operation(OpKind::Mul, {std::min(a, b), std::max(a, b)}));
}
std::size_t ExpressionGraph::div(std::size_t a, std::size_t b) { return intern(operation(OpKind::Div, {a, b})); }
std::size_t ExpressionGraph::zero_where_zero(std::size_t guard, std::size_t value) {
  return intern(operation(OpKind::ZeroWhereZero, {guard, value}));
}
std::size_t ExpressionGraph::neg(std::size_t a) { return intern(operation(OpKind::Neg, {a})); }
std::size_t ExpressionGraph::call(Function function, const std::vector<std::size_t>& args) {
  Node node = operation(OpKind::Call, args);
  node.function = function;
  return intern(std::move(node));
}

bool ExpressionGraph::is_leaf(std::size_t id) const {
  return nodes_[id].kind == OpKind::Input || nodes_[id].kind == OpKind::Constant;
}

std::vector<bool> ExpressionGraph::needed(const std::vector<std::size_t>& outputs) const {
  std::vector<bool> needed(nodes_.size(), false);
  for (std::size_t out : outputs) needed.at(out) = true;
  // Operands have smaller numbers than their users: one backward sweep marks everything needed.
  for (std::size_t id = nodes_.size(); id-- > 0;)
    if (needed[id])
      for (std::size_t arg : nodes_[id].args) needed[arg] = true;
  return needed;
}

std::vector<std::size_t> ExpressionGraph::needed_operations(const std::vector<std::size_t>& outputs) const {
  const std::vector<bool> needed = this->needed(outputs);
  std::vector<std::size_t> order;
  for (std::size_t id = 0; id < nodes_.size(); ++id)
    if (needed[id] && !is_leaf(id)) order.push_back(id);
  return order;
}

OpCounts ExpressionGraph::shared_counts(const std::vector<std::size_t>& outputs) const {
  OpCounts total;
  for (std::size_t id : needed_operations(outputs)) total += own_cost(nodes_[id]);
  return total;
}

OpCounts ExpressionGraph::tree_counts(const std::vector<std::size_t>& outputs) const {
  std::vector<OpCounts> tree(nodes_.size());
  for (std::size_t id = 0; id < nodes_.size(); ++id) {
    tree[id] = own_cost(nodes_[id]);
    for (std::size_t arg : nodes_[id].args) tree[id] += tree[arg];
  }
  OpCounts total;
  for (std::size_t out : outputs) total += tree[out];
  return total;
}

}  // namespace pfgen::codegen
