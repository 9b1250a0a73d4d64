#pragma once
// What C and C++ share in writing the statement IR (ir/statement_emitter.hpp): operators, literals
// of float and double (`0.1f`, `0.1`: never a bare double in float code), `const <scalar> name =
// ...;` declarations, `for` loops whose one statement stays on the loop's line, `(void)` for an
// argument a function does not read. A body too large for one function is written in parts by
// each language's own means (split_body: C++ lambdas, C static functions). The C++ and C backends
// derive from this.
#include <string>
#include <utility>
#include <vector>

#include "pfgen/codegen/expression_graph.hpp"
#include "pfgen/codegen/ir/statement_emitter.hpp"
#include "pfgen/codegen/scalar_mode.hpp"

namespace pfgen::codegen {

class CFamilyEmitter : public StatementEmitter {
 public:
  // `scalar_type`: how declarations spell the scalar (C++: the alias `Scalar`; C: `double`).
  CFamilyEmitter(ScalarMode mode, std::string scalar_type, std::string temporary_prefix)
      : StatementEmitter(std::move(temporary_prefix)), mode_(mode), scalar_type_(std::move(scalar_type)) {}

  // A literal of the scalar type (`0.1f`, `0.1`, C++'s `Scalar(0.1)`); CodegenError for a constant
  // outside its range, or a nonzero one that would round to 0.
  std::string literal(const GiNaC::numeric& value) const;
  const std::string& scalar_type() const { return scalar_type_; }
  ScalarMode mode() const { return mode_; }

  // Emitter: one method per node kind.
  std::string constant(const GiNaC::numeric& value) const override { return literal(value); }
  std::string input(const Node& node) const override { return node.name(); }
  std::string add(const std::string& a, const std::string& b) const override { return a + " + " + b; }
  std::string sub(const std::string& a, const std::string& b) const override { return a + " - " + b; }
  std::string mul(const std::string& a, const std::string& b) const override { return a + " * " + b; }
  std::string div(const std::string& a, const std::string& b) const override { return a + " / " + b; }
  std::string neg(const std::string& a) const override { return "-" + a; }
  std::string zero_where_zero(const std::string& guard, const std::string& value) const override;
  // StatementEmitter's expressions.
  std::string element(const std::string& array, const std::string& index) const override {
    return array + "[" + index + "]";
  }
  std::string field(const std::string& record, const std::string& name) const override {
    return record + field_access() + name;
  }
  std::string greater(const std::string& a, const std::string& b) const override { return a + " > " + b; }
  std::string logical_not(const std::string& a) const override { return "!" + a; }
  std::string less(const std::string& a, const std::string& b) const override { return a + " < " + b; }
  std::string equal(const std::string& a, const std::string& b) const override { return a + " == " + b; }
  std::string logical_or(const std::string& a, const std::string& b) const override { return a + " || " + b; }
  std::string logical_and(const std::string& a, const std::string& b) const override { return a + " && " + b; }
  std::string rem(const std::string& a, const std::string& b) const override { return a + " % " + b; }
  std::string select(const std::string& condition, const std::string& if_true,
                     const std::string& if_false) const override {
    return condition + " ? " + if_true + " : " + if_false;
  }
  // A pointer into the array: `array` or `array + offset`.
  std::string slice(const ir::Expr& node) const override;
  std::string local_array(const std::string& array, bool) const override { return array; }
  std::string array_from(const std::string& array, const std::string& offset, bool writable) const override {
    return local_array(array, writable) + " + " + offset;
  }
  std::string post_increment(const std::string& index) const override { return index + "++"; }
  // A cast: `(double)s`.
  std::string to_scalar(const std::string& index) const override { return "(" + scalar_type_ + ")" + index; }
  // StatementEmitter's statements.
  std::string declaration(const ir::Declaration& node, const std::string& indent) const override;
  std::string view(const ir::View& node, const std::string& indent) const override;
  std::string assignment(const ir::Assignment& node, const std::string& indent) const override;
  std::string loop(const ir::Loop& node, const std::string& indent) const override;
  std::string call_statement(const ir::CallStatement& node, const std::string& indent) const override;
  std::string conditional(const ir::Conditional& node, const std::string& indent) const override;
  std::string return_statement(const ir::Return& node, const std::string& indent) const override;
  std::string comment(const ir::Comment& node, const std::string& indent) const override;
  std::string unused(const ir::Unused& node, const std::string& indent) const override;
  std::string arrays(const ir::LocalArrays& node, const std::string& indent) const override;
  std::string scope(const ir::Scope& node, const std::string& indent) const override;

 protected:
  // "." (C++: a reference) or "->" (C: a pointer): how a field of the parameter record is read.
  virtual std::string field_access() const = 0;
  // How the language spells a size (C++: std::size_t; C: size_t).
  virtual std::string size_type() const = 0;
  // How the language spells a truth value's type (C++: bool; C: int, as its truth values are 1 and 0).
  virtual std::string truth_type() const { return "bool"; }
  // How a conditional on the file's constants alone begins (C++: `if constexpr`; C: `if`).
  virtual std::string compile_time_if() const { return "if"; }
  // Whether a symmetric store (ir::assign_symmetric) is one chained assignment `a = b = value;` (C++)
  // or two statements, `a = value;` and `b = a;` (C), which a loop's block then braces.
  virtual bool chains_symmetric_store() const { return true; }
  std::string type(ir::Type type) const;
  // A loop's or a conditional's header followed by its block as `layout` says (ir::Layout).
  std::string with_block(const std::string& header, const ir::Block& body, const std::string& indent,
                         ir::Layout layout) const;

  ScalarMode mode_;
  std::string scalar_type_;
};

}  // namespace pfgen::codegen
