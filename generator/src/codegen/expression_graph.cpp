#include "pfgen/codegen/expression_graph.hpp"

#include <algorithm>
#include <sstream>

#include "pfgen/codegen/codegen_error.hpp"

namespace pfgen::codegen {

namespace {
const std::pair<Function, const char*> kFunctionNames[] = {
    {Function::Sin, "sin"},   {Function::Cos, "cos"},   {Function::Tan, "tan"},   {Function::Exp, "exp"},
    {Function::Log, "log"},   {Function::Sinh, "sinh"}, {Function::Cosh, "cosh"}, {Function::Tanh, "tanh"},
    {Function::Asin, "asin"}, {Function::Acos, "acos"}, {Function::Atan, "atan"}, {Function::Atan2, "atan2"},
    {Function::Asinh, "asinh"}, {Function::Acosh, "acosh"}, {Function::Atanh, "atanh"}, {Function::Abs, "abs"},
    {Function::Tgamma, "tgamma"}, {Function::Lgamma, "lgamma"}, {Function::Sqrt, "sqrt"}, {Function::Pow, "pow"}};
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

// A node of `kind` on `args`; the fields of the other kinds keep their defaults.
Node operation(OpKind kind, Operands args) {
  Node node{};
  node.kind = kind;
  node.args = args;
  return node;
}

// 32 well-mixed bits of an operation's content (murmur3's finaliser over kind, function, operands).
std::uint32_t content_hash(const Node& node) {
  std::uint64_t h = static_cast<std::uint64_t>(node.kind) | static_cast<std::uint64_t>(node.function) << 8 |
                    static_cast<std::uint64_t>(node.args.size()) << 16;
  for (std::uint32_t arg : node.args) {
    h = (h ^ arg) * 0xff51afd7ed558ccdull;
    h ^= h >> 33;
  }
  h *= 0xc4ceb9fe1a85ec53ull;
  h ^= h >> 33;
  return static_cast<std::uint32_t>(h >> 32);
}

bool same_operation(const Node& a, const Node& b) {
  return a.kind == b.kind && a.function == b.function && a.args == b.args;
}

const Leaf kNoLeaf;

Leaf constant_leaf(const GiNaC::numeric& value) {
  Leaf data;
  data.value = value;
  data.held = std::make_shared<const GiNaC::numeric>(value);  // one per distinct constant, not one per use
  return data;
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

namespace {
template <class Ids>
void fill_operands(const Ids& ids, std::uint32_t* out, std::uint32_t& size) {
  if (ids.size() > Operands::kMax) throw CodegenError("an operation of more than two operands");
  for (std::size_t id : ids) out[size++] = static_cast<std::uint32_t>(id);
}
}  // namespace

Operands::Operands(std::initializer_list<std::size_t> ids) { fill_operands(ids, ids_, size_); }
Operands::Operands(const std::vector<std::size_t>& ids) { fill_operands(ids, ids_, size_); }

bool Operands::operator==(const Operands& other) const {
  return size_ == other.size_ && std::equal(begin(), end(), other.begin());
}

const Leaf& Node::leaf_data() const { return leaf ? *leaf : kNoLeaf; }

// A slot holds a node's number in its low 32 bits and its content hash in its high 32 bits, so a
// probe compares nodes only when their hashes agree, and growing rehashes no node.
void ExpressionGraph::grow_index() {
  std::vector<std::uint64_t> old = std::move(index_);
  index_.assign(old.empty() ? 1024 : 2 * old.size(), kEmptySlot);
  const std::size_t mask = index_.size() - 1;
  for (std::uint64_t entry : old) {
    if (entry == kEmptySlot) continue;
    std::size_t slot = (entry >> 32) & mask;
    while (index_[slot] != kEmptySlot) slot = (slot + 1) & mask;
    index_[slot] = entry;
  }
}

std::size_t ExpressionGraph::intern(const Node& node) {
  if (2 * (indexed_ + 1) > index_.size()) grow_index();
  const std::size_t mask = index_.size() - 1;
  const std::uint64_t hash = content_hash(node);
  std::size_t slot = hash & mask;
  for (; index_[slot] != kEmptySlot; slot = (slot + 1) & mask) {
    const std::uint64_t entry = index_[slot];
    if (entry >> 32 == hash && same_operation(nodes_[entry & 0xffffffffu], node)) return entry & 0xffffffffu;
  }
  if (nodes_.size() >= kMaxNodes) throw CodegenError("the expression graph outgrew 2^32 nodes");
  nodes_.push_back(node);
  index_[slot] = hash << 32 | (nodes_.size() - 1);
  ++indexed_;
  return nodes_.size() - 1;
}

std::size_t ExpressionGraph::leaf(OpKind kind, Leaf data) {
  if (nodes_.size() >= kMaxNodes) throw CodegenError("the expression graph outgrew 2^32 nodes");
  leaves_.push_back(std::move(data));
  Node node{};
  node.kind = kind;
  node.leaf = &leaves_.back();
  nodes_.push_back(node);
  return nodes_.size() - 1;
}

std::size_t ExpressionGraph::input(const std::string& name, InputSource source) {
  auto it = inputs_.find(name);
  if (it != inputs_.end()) return it->second;
  Leaf data;
  data.name = name;
  data.source = std::move(source);
  const std::size_t id = leaf(OpKind::Input, std::move(data));
  inputs_.emplace(name, id);
  return id;
}

// Equal rationals print alike, so they are one constant; floats are one constant only if they
// print alike, as the emitters would spell them apart otherwise (Scalar(2) and Scalar(2.0)).
std::size_t ExpressionGraph::constant(const GiNaC::numeric& value) {
  if (value.is_rational()) {
    auto it = rational_constants_.find(value);
    if (it != rational_constants_.end()) return it->second;
    const std::size_t id = leaf(OpKind::Constant, constant_leaf(value));
    rational_constants_.emplace(value, id);
    return id;
  }
  std::ostringstream text;
  text << value;
  auto it = float_constants_.find(text.str());
  if (it != float_constants_.end()) return it->second;
  const std::size_t id = leaf(OpKind::Constant, constant_leaf(value));
  float_constants_.emplace(text.str(), id);
  return id;
}

bool ExpressionGraph::is_exact_one(std::size_t id) const {
  const Node& node = nodes_[id];
  return node.kind == OpKind::Constant && node.value().is_rational() && node.value() == 1;
}

// Commutative operations list their operands in a fixed order, so a*b and b*a share a node.
// Signs are folded where that is exact in floating point and costs no operation: a + (-b) is
// a - b, a - (-b) is a + b, -(-a) is a (negation is exact, and rounding is symmetric about zero).
std::size_t ExpressionGraph::add(std::size_t a, std::size_t b) {
  if (nodes_[b].kind == OpKind::Neg && nodes_[a].kind != OpKind::Neg) return sub(a, nodes_[b].args[0]);
  if (nodes_[a].kind == OpKind::Neg && nodes_[b].kind != OpKind::Neg) return sub(b, nodes_[a].args[0]);
  return intern(operation(OpKind::Add, {std::min(a, b), std::max(a, b)}));
}
std::size_t ExpressionGraph::sub(std::size_t a, std::size_t b) {
  if (nodes_[b].kind == OpKind::Neg) return add(a, nodes_[b].args[0]);
  return intern(operation(OpKind::Sub, {a, b}));
}
// A product with an exact 1 is the other factor (x * 1 is x exactly).
std::size_t ExpressionGraph::mul(std::size_t a, std::size_t b) {
  if (is_exact_one(a)) return b;
  if (is_exact_one(b)) return a;
  return intern(operation(OpKind::Mul, {std::min(a, b), std::max(a, b)}));
}
std::size_t ExpressionGraph::div(std::size_t a, std::size_t b) { return intern(operation(OpKind::Div, {a, b})); }
std::size_t ExpressionGraph::zero_where_zero(std::size_t guard, std::size_t value) {
  return intern(operation(OpKind::ZeroWhereZero, {guard, value}));
}
std::size_t ExpressionGraph::neg(std::size_t a) {
  if (nodes_[a].kind == OpKind::Neg) return nodes_[a].args[0];
  return intern(operation(OpKind::Neg, {a}));
}
std::size_t ExpressionGraph::call(Function function, const std::vector<std::size_t>& args) {
  Node node = operation(OpKind::Call, Operands(args));
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
