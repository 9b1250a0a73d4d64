#pragma once
// A straight-line program as a DAG of scalar operations, built by hash-consing:
// asking twice for the same operation on the same operands returns the same
// node, so common subexpressions across every output of a filter (derived P
// equations repeat products such as P_ij * m_k heavily) are computed once.
// Node numbers are assigned in creation order, which is deterministic and
// topological (operands always exist before their users).
#include <cstddef>
#include <map>
#include <string>
#include <tuple>
#include <vector>

#include <ginac/ginac.h>

namespace pfgen::codegen {

// ZeroWhereZero(guard, value): 0 where guard == 0, else value (a Cholesky entry below a zero pivot).
enum class OpKind { Input, Constant, Add, Sub, Mul, Div, Neg, Call, ZeroWhereZero };

struct Node {
  OpKind kind;
  std::string name;           // Input: its C++ name in the function ("P12", "a", "t"); Call: function name
  std::string source;         // Input: what the function reads it from ("state[3]", "params.a"); empty
                              // when the name is itself an argument of the function (the time)
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
  std::size_t input(const std::string& name, const std::string& source = "");
  std::size_t constant(const GiNaC::numeric& value);
  std::size_t add(std::size_t a, std::size_t b);
  std::size_t sub(std::size_t a, std::size_t b);
  std::size_t mul(std::size_t a, std::size_t b);
  std::size_t div(std::size_t a, std::size_t b);
  std::size_t neg(std::size_t a);
  std::size_t call(const std::string& function, const std::vector<std::size_t>& args);
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
