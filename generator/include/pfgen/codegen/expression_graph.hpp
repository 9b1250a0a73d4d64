#pragma once
// A straight-line program as a DAG of scalar operations, in no language's syntax (each backend's
// emitter spells it; codegen/backends/cpp/cpp_emitter for C++), built by hash-consing:
// asking twice for the same operation on the same operands returns the same
// node, so common subexpressions across every output of a filter (derived P
// equations repeat products such as P_ij * m_k heavily) are computed once.
// Node numbers are assigned in creation order, which is deterministic and
// topological (operands always exist before their users).
#include <cstddef>
#include <map>
#include <optional>
#include <string>
#include <tuple>
#include <vector>

#include <ginac/ginac.h>

namespace pfgen::codegen {

// ZeroWhereZero(guard, value): 0 where guard == 0, else value (a Cholesky entry below a zero pivot).
enum class OpKind { Input, Constant, Add, Sub, Mul, Div, Neg, Call, ZeroWhereZero };

// The functions generated code calls: the model file's functions that every output language has,
// and sqrt and pow for non-integer powers. Each backend spells them its own way.
enum class Function { Sin, Cos, Tan, Exp, Log, Sinh, Cosh, Tanh, Asin, Acos, Atan, Abs, Sqrt, Pow };
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

struct Node {
  OpKind kind;
  std::string name;           // Input: its name in the function ("P12", "a", "t")
  InputSource source;         // Input: what the function reads it from
  Function function = Function::Sin;  // Call only
  GiNaC::numeric value;       // Constant only (exact rational or float)
  std::vector<std::size_t> args;
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
  using Key = std::tuple<int, std::string, std::string, std::vector<std::size_t>>;
  std::size_t intern(Node node);
  std::vector<Node> nodes_;
  std::map<Key, std::size_t> index_;
};

}  // namespace pfgen::codegen
