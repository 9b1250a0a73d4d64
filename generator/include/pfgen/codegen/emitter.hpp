#pragma once
// What an output language supplies to write an ExpressionGraph: one method per kind of node,
// each given the text of its operands, as wrenfold's emitters and GiNaC's print contexts do. The
// graph holds no language's syntax; a backend (codegen/backends/<language>/) derives from
// Emitter and spells it. expression() dispatches a node to the method of its kind, so the code
// that walks a graph (a backend's bodies) never switches on node kinds itself.
#include <string>
#include <vector>

#include "pfgen/codegen/expression_graph.hpp"

namespace pfgen::codegen {

class Emitter {
 public:
  virtual ~Emitter() = default;

  virtual std::string constant(const GiNaC::numeric& value) const = 0;
  // An input as a body reads it: its name, declared at the top of the function.
  virtual std::string input(const Node& node) const = 0;
  virtual std::string add(const std::string& a, const std::string& b) const = 0;
  virtual std::string sub(const std::string& a, const std::string& b) const = 0;
  virtual std::string mul(const std::string& a, const std::string& b) const = 0;
  virtual std::string div(const std::string& a, const std::string& b) const = 0;
  virtual std::string neg(const std::string& a) const = 0;
  virtual std::string call(Function function, const std::vector<std::string>& args) const = 0;
  // 0 where guard is 0, else value.
  virtual std::string zero_where_zero(const std::string& guard, const std::string& value) const = 0;

  // The node's text from its operands' texts, by the method of its kind.
  std::string expression(const Node& node, const std::vector<std::string>& operands) const;
};

}  // namespace pfgen::codegen
