#pragma once
// The C++ backend's emitter: writes an ExpressionGraph as C++ statements. Literals follow the scalar
// mode so that float code stays float: `0.1f` (float), `0.1` (double) or
// `Scalar(0.1)` (template), never a bare double in float code.
#include <string>
#include <utility>
#include <vector>

#include "pfgen/codegen/emitter.hpp"
#include "pfgen/codegen/expression_graph.hpp"

namespace pfgen::codegen {

enum class ScalarMode { Template, Float, Double };

std::string scalar_mode_name(ScalarMode mode);  // "template", "float", "double"

class CppEmitter : public Emitter {
 public:
  // Temporaries are named temporary_prefix + 0, 1, ... (CppNames::temporary_prefix keeps them
  // apart from the model's names).
  explicit CppEmitter(ScalarMode mode, std::string temporary_prefix = "tmp")
      : mode_(mode), temporary_prefix_(std::move(temporary_prefix)) {}

  std::string literal(const GiNaC::numeric& value) const;

  // Emitter: one method per node kind (C++ operators, <cmath>'s std:: functions).
  std::string constant(const GiNaC::numeric& value) const override { return literal(value); }
  std::string input(const Node& node) const override { return node.name; }
  std::string add(const std::string& a, const std::string& b) const override { return a + " + " + b; }
  std::string sub(const std::string& a, const std::string& b) const override { return a + " - " + b; }
  std::string mul(const std::string& a, const std::string& b) const override { return a + " * " + b; }
  std::string div(const std::string& a, const std::string& b) const override { return a + " / " + b; }
  std::string neg(const std::string& a) const override { return "-" + a; }
  std::string call(Function function, const std::vector<std::string>& args) const override;
  std::string zero_where_zero(const std::string& guard, const std::string& value) const override;
  // How the function reads an input: `state[3]`, `params.a`, or an argument's own name.
  std::string input_source(const Node& node) const;

  // `const Scalar <name> = <source>;` for each input of `order` that the outputs read, in that
  // order: the top of a function, so that its body reads each input by its own name. Inputs
  // without a source (arguments read directly) are skipped.
  std::string input_declarations(const ExpressionGraph& graph, const std::vector<std::size_t>& outputs,
                                 const std::vector<std::size_t>& order) const;

  // Temporaries for every needed operation, each computed once, then
  // `target[k] = ...;` for output k. Indented by two spaces.
  std::string shared_body(const ExpressionGraph& graph, const std::vector<std::size_t>& outputs,
                          const std::string& target) const;
  // The same with `destinations[k] = ...;` for output k.
  std::string shared_body(const ExpressionGraph& graph, const std::vector<std::size_t>& outputs,
                          const std::vector<std::string>& destinations) const;
  // From now on shared_body() splits a body of more than `max_ops` operations into parts of at
  // most `max_ops` (chunked_body.cpp); `shared_array` names the local array through which the
  // parts pass the values later parts read, a name clear of the function's others. 0: never split.
  void split_above(std::size_t max_ops, std::string shared_array);
  // Every output as one nested expression, without temporaries: the same
  // equations with no common-subexpression elimination (benchmark baseline).
  std::string tree_body(const ExpressionGraph& graph, const std::vector<std::size_t>& outputs,
                        const std::string& target) const;

 private:
  std::string chunked_body(const ExpressionGraph& graph, const std::vector<std::size_t>& outputs,
                           const std::vector<std::string>& destinations) const;
  ScalarMode mode_;
  std::string temporary_prefix_;
  std::size_t max_ops_ = 0;
  std::string shared_array_;
};

}  // namespace pfgen::codegen
