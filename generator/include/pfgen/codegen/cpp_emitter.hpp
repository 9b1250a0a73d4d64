#pragma once
// Writes an ExpressionGraph as C++ statements. Literals follow the scalar
// mode so that float code stays float: `0.1f` (float), `0.1` (double) or
// `Scalar(0.1)` (template), never a bare double in float code.
#include <string>
#include <vector>

#include "pfgen/codegen/expression_graph.hpp"

namespace pfgen::codegen {

enum class ScalarMode { Template, Float, Double };

std::string scalar_mode_name(ScalarMode mode);  // "template", "float", "double"

class CppEmitter {
 public:
  explicit CppEmitter(ScalarMode mode) : mode_(mode) {}

  std::string literal(const GiNaC::numeric& value) const;

  // Temporaries for every needed operation, each computed once, then
  // `target[k] = ...;` for output k. Indented by two spaces.
  std::string shared_body(const ExpressionGraph& graph, const std::vector<std::size_t>& outputs,
                          const std::string& target) const;
  // Every output as one nested expression, without temporaries: the same
  // equations with no common-subexpression elimination (benchmark baseline).
  std::string tree_body(const ExpressionGraph& graph, const std::vector<std::size_t>& outputs,
                        const std::string& target) const;

 private:
  std::string operation(const ExpressionGraph& graph, const Node& node,
                        const std::vector<std::string>& operand_text) const;
  ScalarMode mode_;
};

}  // namespace pfgen::codegen
