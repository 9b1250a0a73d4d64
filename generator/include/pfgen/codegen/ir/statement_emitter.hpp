#pragma once
// What an output language supplies to write the statement IR (statements.hpp): one method per
// expression node (Emitter's, for the node kinds of an ExpressionGraph, and the IR's own) and one per
// statement node, as wrenfold's emitters have one per AST node. block() dispatches each statement to
// its method, expression() each Expr, so the code that builds statements never writes a language.
//
// A generated function's body from its graph is written here once for every language
// (function_body): the arguments it does not read, its inputs named once, then every operation once
// (or, without CSE, each output as one expression), each lowered to statements (lower_graph.hpp).
// A body of more operations than split_above() allows is written in parts by the language's own
// means (split_body: C++ lambdas, C static functions).
#include <cstddef>
#include <set>
#include <string>
#include <vector>

#include "pfgen/codegen/emitter.hpp"
#include "pfgen/codegen/ir/lower_graph.hpp"
#include "pfgen/codegen/ir/statements.hpp"

namespace pfgen::codegen {

// A function's body, and the functions it calls that must precede it (C's parts of a split body).
struct FunctionBody {
  std::string helpers;
  std::string statements;
};

class StatementEmitter : public Emitter {
 public:
  // Temporaries are named temporary_prefix + 0, 1, ... (LocalNames::temporary_prefix keeps them
  // apart from the model's names).
  explicit StatementEmitter(std::string temporary_prefix) : temporary_prefix_(std::move(temporary_prefix)) {}

  // Expressions, beyond Emitter's node kinds (each given its operands' text).
  virtual std::string name(const std::string& name) const { return name; }
  virtual std::string integer(std::size_t value) const { return std::to_string(value); }
  virtual std::string boolean(bool value) const = 0;
  virtual std::string element(const std::string& array, const std::string& index) const = 0;
  virtual std::string field(const std::string& record, const std::string& field) const = 0;
  virtual std::string greater(const std::string& a, const std::string& b) const = 0;
  virtual std::string logical_not(const std::string& a) const = 0;
  virtual std::string less(const std::string& a, const std::string& b) const = 0;
  virtual std::string equal(const std::string& a, const std::string& b) const = 0;
  virtual std::string logical_or(const std::string& a, const std::string& b) const = 0;
  virtual std::string logical_and(const std::string& a, const std::string& b) const = 0;
  virtual std::string rem(const std::string& a, const std::string& b) const = 0;
  virtual std::string select(const std::string& condition, const std::string& if_true,
                             const std::string& if_false) const = 0;
  // A Slice node (its operands written by the method, which may drop their grouping).
  virtual std::string slice(const ir::Expr& node) const = 0;
  virtual std::string grouped(const std::string& a) const { return "(" + a + ")"; }
  virtual std::string local_array(const std::string& array, bool writable) const = 0;
  // A local array from `offset` on, passed to a call.
  virtual std::string array_from(const std::string& array, const std::string& offset, bool writable) const = 0;
  // An index's value, which then steps by one.
  virtual std::string post_increment(const std::string& index) const = 0;
  // An index or a size in the scalar type (ir::to_scalar).
  virtual std::string to_scalar(const std::string& index) const = 0;
  // The same as a cast (ir::cast_to_scalar), given the index's node: to_scalar by default.
  virtual std::string cast_to_scalar(const ir::Expr& index) const { return to_scalar(expression(index)); }
  // A comment after a statement on its line, from the statement's end: `  // text` by default.
  virtual std::string trailing_comment(const std::string& text) const { return "  // " + text; }
  // The file's function of no arguments giving a scalar (ir::file_scalar), called.
  virtual std::string file_scalar(const std::string& name) const { return file_function(name) + "()"; }
  // Entry (a, b) of the packed symmetric matrix `matrix` (ir::packed_entry): by default the file's
  // function packed_at(matrix, a, b), which C's and Rust's templates define.
  virtual std::string packed_entry(const std::string& matrix, const std::string& a, const std::string& b) const {
    return file_function("packed_at") + "(" + matrix + ", " + a + ", " + b + ")";
  }
  // A size the file declares, by its language-neutral name; as it is by default.
  virtual std::string dimension(const std::string& name) const { return name; }
  // A function the file declares, by its language-neutral name; as it is by default.
  virtual std::string file_function(const std::string& name) const { return name; }
  // A function the file keeps out of its interface (ir::CallStatement::internal); as file_function by default.
  virtual std::string internal_function(const std::string& name) const { return file_function(name); }
  // The function a call statement calls, as the language spells it.
  std::string callee(const ir::CallStatement& node) const {
    if (node.internal) return internal_function(node.function);
    return node.of_file ? file_function(node.function) : node.function;
  }
  // `callee(arguments...)`: a call statement's text before its `;`, and a file's function called for
  // its value (FileCall), written alike.
  std::string call_text(const std::string& callee, const std::vector<ir::Expr>& arguments) const;
  // A whole number in the scalar type; its constant by default.
  virtual std::string whole_scalar(std::size_t value) const { return constant(GiNaC::numeric(static_cast<long>(value))); }
  using Emitter::expression;
  std::string expression(const ir::Expr& expr) const;

  // Statements: each method writes its node from its first character to its last, without the
  // line's indentation and end; a statement of several lines indents the lines after its first
  // from `indent`, its own depth. block() writes each statement on its own line(s) at `indent`.
  virtual std::string declaration(const ir::Declaration& node, const std::string& indent) const = 0;
  virtual std::string view(const ir::View& node, const std::string& indent) const = 0;
  virtual std::string assignment(const ir::Assignment& node, const std::string& indent) const = 0;
  virtual std::string loop(const ir::Loop& node, const std::string& indent) const = 0;
  virtual std::string call_statement(const ir::CallStatement& node, const std::string& indent) const = 0;
  virtual std::string conditional(const ir::Conditional& node, const std::string& indent) const = 0;
  virtual std::string return_statement(const ir::Return& node, const std::string& indent) const = 0;
  virtual std::string comment(const ir::Comment& node, const std::string& indent) const = 0;
  virtual std::string unused(const ir::Unused& node, const std::string& indent) const = 0;
  virtual std::string arrays(const ir::LocalArrays& node, const std::string& indent) const = 0;
  virtual std::string scope(const ir::Scope& node, const std::string& indent) const = 0;
  std::string statement(const ir::Statement& statement, const std::string& indent) const;
  std::string block(const ir::Block& block, const std::string& indent = "  ") const;

  // The lowerings of lower_graph.hpp written out (indented by two): the top of a function for the
  // inputs `outputs` read, in `order`; the shared body to `target[k]` or to `destinations[k]` (each
  // as the language writes it); the tree body; an input's source.
  std::string input_declarations(const ExpressionGraph& graph, const std::vector<std::size_t>& outputs,
                                 const std::vector<std::size_t>& order) const;
  std::string unused_arguments(const ExpressionGraph& graph, const std::vector<std::size_t>& outputs,
                               const FunctionSignature& signature) const;
  std::string shared_body(const ExpressionGraph& graph, const std::vector<std::size_t>& outputs,
                          const std::string& target) const;
  std::string shared_body(const ExpressionGraph& graph, const std::vector<std::size_t>& outputs,
                          const std::vector<std::string>& destinations) const;
  std::string tree_body(const ExpressionGraph& graph, const std::vector<std::size_t>& outputs,
                        const std::string& target) const;
  std::string input_source(const Node& node) const { return expression(ir::input_source(node)); }

  // The whole body of a generated function writing `outputs` to signature.target: unused
  // arguments, input declarations in `order`, then the shared body (with `shared`; split when it
  // is too large) or the tree body (lower_graph.hpp).
  FunctionBody function_body(const ExpressionGraph& graph, const std::vector<std::size_t>& outputs,
                             const FunctionSignature& signature, const std::vector<std::size_t>& order,
                             bool shared) const;
  // From now on function_body() splits a body of more than `max_ops` operations into parts of at
  // most `max_ops`; `shared_array` names the local array through which the parts pass the values
  // later parts read, a name clear of the function's others. 0: never split.
  void split_above(std::size_t max_ops, std::string shared_array);
  const std::string& temporary_prefix() const { return temporary_prefix_; }

 protected:
  // A body of more than max_ops_ operations in parts (the part of function_body after its
  // argument checks; ir::split_plan() says which operation goes where).
  virtual FunctionBody split_body(const ExpressionGraph& graph, const std::vector<std::size_t>& outputs,
                                  const FunctionSignature& signature,
                                  const std::vector<std::size_t>& order) const = 0;
  std::string temporary(std::size_t number) const { return temporary_prefix_ + std::to_string(number); }

  std::string temporary_prefix_;
  std::size_t max_ops_ = 0;
  std::string shared_array_;
};

}  // namespace pfgen::codegen
