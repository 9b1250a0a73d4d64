#pragma once
// A straight-line program as a DAG of scalar operations, in no language's syntax (each backend's
// emitter spells it; codegen/backends/cpp/cpp_emitter for C++), built by hash-consing:
// asking twice for the same operation on the same operands returns the same
// node, so common subexpressions across every output of a filter (derived P
// equations repeat products such as P_ij * m_k heavily) are computed once.
// Node numbers are assigned in creation order, which is deterministic and
// topological (operands always exist before their users).
//
// Compact by design: the expanded P drift of a dense cubic n = 20 filter is 3.6 million terms,
// about 12 million operations before sharing. A node is 24 bytes (its operands in place, an input's
// or constant's data apart, in `Leaf`), and the hash-consing index is an open-addressing table of
// node numbers and hashes (8 bytes a slot, at most half full).
#include <memory>
#include <cstddef>
#include <cstdint>
#include <deque>
#include <initializer_list>
#include <map>
#include <optional>
#include <string>
#include <vector>

#include <ginac/ginac.h>

namespace pfgen::codegen {

// ZeroWhereZero(guard, value): 0 where guard == 0, else value (a Cholesky entry below a zero pivot).
enum class OpKind { Input, Constant, Add, Sub, Mul, Div, Neg, Call, ZeroWhereZero };

// The functions generated code calls: the model file's functions that every output language has,
// and sqrt and pow for non-integer powers. Each backend spells them its own way.
// Every function a model may call (kinds/model_functions.hpp), then the powers GiNaC holds as such.
enum class Function {
  Sin, Cos, Tan, Exp, Log, Sinh, Cosh, Tanh, Asin, Acos, Atan, Atan2, Asinh, Acosh, Atanh, Abs, Tgamma, Lgamma,
  Sqrt, Pow
};
// "sin", ..., "sqrt", "pow": the function's name in a model file.
const char* function_name(Function function);
// The function of that name, if it has one (GiNaC's and the model file's names).
std::optional<Function> function_named(const std::string& name);

// Where a generated function reads an input from, named, not spelled: the argument itself (the
// time), element `index` of an argument array (`state`, 3), or the input's own field of an
// argument record (`params`, whose field `a` holds parameter a).
struct InputSource {
  enum class Kind { Argument, Element, Field };
  Kind kind = Kind::Argument;
  std::string container;   // Element, Field: the argument's name
  std::size_t index = 0;   // Element: the position in it
  static InputSource element(std::string array, std::size_t index) { return {Kind::Element, std::move(array), index}; }
  static InputSource field(std::string record) { return {Kind::Field, std::move(record), 0}; }
};

// An input's or a constant's own data.
struct Leaf {
  std::string name;      // Input: its name in the function ("P12", "a", "t")
  InputSource source;    // Input: what the function reads it from
  GiNaC::numeric value;  // Constant: an exact rational or a float
  std::shared_ptr<const GiNaC::numeric> held;  // Constant: the same value, which lowered code shares
};

// A node's operands in place: every operation takes one or two (calls: sin one, pow two).
class Operands {
 public:
  static constexpr std::size_t kMax = 2;
  Operands() = default;
  Operands(std::initializer_list<std::size_t> ids);
  explicit Operands(const std::vector<std::size_t>& ids);
  std::size_t size() const { return size_; }
  bool empty() const { return size_ == 0; }
  const std::uint32_t* begin() const { return ids_; }
  const std::uint32_t* end() const { return ids_ + size_; }
  std::size_t operator[](std::size_t k) const { return ids_[k]; }
  bool operator==(const Operands& other) const;

 private:
  std::uint32_t ids_[kMax] = {0, 0};
  std::uint32_t size_ = 0;
};

struct Node {
  OpKind kind = OpKind::Input;
  Function function = Function::Sin;  // Call only
  Operands args;
  const Leaf* leaf = nullptr;         // Input and Constant only

  const std::string& name() const { return leaf_data().name; }        // Input
  const InputSource& source() const { return leaf_data().source; }    // Input
  const GiNaC::numeric& value() const { return leaf_data().value; }   // Constant
  const std::shared_ptr<const GiNaC::numeric>& held_value() const { return leaf_data().held; }  // for ir::held_number
 private:
  const Leaf& leaf_data() const;
};

struct OpCounts {
  std::size_t adds = 0;   // additions, subtractions, negations
  std::size_t muls = 0;
  std::size_t divs = 0;
  std::size_t calls = 0;  // sin, cos, exp, pow, ...
  std::size_t total() const { return adds + muls + divs + calls; }
  OpCounts& operator+=(const OpCounts& other);
};

class ExpressionGraph {
 public:
  // Move-only: a node points at its leaf data in this graph's own storage, which a move keeps.
  ExpressionGraph() = default;
  ExpressionGraph(const ExpressionGraph&) = delete;
  ExpressionGraph& operator=(const ExpressionGraph&) = delete;
  ExpressionGraph(ExpressionGraph&&) = default;
  ExpressionGraph& operator=(ExpressionGraph&&) = default;

  // The same name always gives the same node: its source is that of its first creation.
  std::size_t input(const std::string& name, InputSource source = {});
  std::size_t constant(const GiNaC::numeric& value);
  std::size_t add(std::size_t a, std::size_t b);
  std::size_t sub(std::size_t a, std::size_t b);
  std::size_t mul(std::size_t a, std::size_t b);
  std::size_t div(std::size_t a, std::size_t b);
  std::size_t neg(std::size_t a);
  std::size_t call(Function function, const std::vector<std::size_t>& args);
  std::size_t zero_where_zero(std::size_t guard, std::size_t value);

  const Node& node(std::size_t id) const { return nodes_.at(id); }
  std::size_t size() const { return nodes_.size(); }
  bool is_leaf(std::size_t id) const;

  // Operations evaluated once each (with sharing) for these outputs.
  OpCounts shared_counts(const std::vector<std::size_t>& outputs) const;
  // Operations if every output were evaluated as its own expression tree.
  OpCounts tree_counts(const std::vector<std::size_t>& outputs) const;
  // Nodes the outputs need, in topological order (leaves excluded).
  std::vector<std::size_t> needed_operations(const std::vector<std::size_t>& outputs) const;
  // Whether the outputs need node `id` (an output needs itself).
  std::vector<bool> needed(const std::vector<std::size_t>& outputs) const;

 private:
  // The operation node equal to `node` (kind, function and operands), created if new.
  std::size_t intern(const Node& node);
  std::size_t leaf(OpKind kind, Leaf data);
  void grow_index();
  bool is_exact_one(std::size_t id) const;

  std::vector<Node> nodes_;
  std::deque<Leaf> leaves_;  // a deque: nodes point into it, and it never moves what it holds
  // Operation nodes by content: open addressing with linear probing, kEmptySlot where free, at
  // most half full. Inputs by name; constants by exact value (rationals) or printed text (floats).
  static constexpr std::uint64_t kEmptySlot = ~std::uint64_t{0};
  static constexpr std::size_t kMaxNodes = 0xffffffffu;
  std::vector<std::uint64_t> index_;
  std::size_t indexed_ = 0;
  std::map<std::string, std::size_t> inputs_;
  std::map<std::string, std::size_t> float_constants_;
  struct NumericLess {
    bool operator()(const GiNaC::numeric& a, const GiNaC::numeric& b) const { return a.compare(b) < 0; }
  };
  std::map<GiNaC::numeric, std::size_t, NumericLess> rational_constants_;
};

}  // namespace pfgen::codegen
