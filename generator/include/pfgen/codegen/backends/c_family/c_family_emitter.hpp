#pragma once
// What C and C++ share in writing an ExpressionGraph: operators, literals of float and double
// (`0.1f`, `0.1`: never a bare double in float code), `const <scalar> name = ...;` statements, and
// the body of a generated function: `(void)` for each argument its outputs do not read, each input
// named once, then every operation once (or, without CSE, each output as one expression). A body
// of more operations than split_above() allows is written in parts by the language's own means
// (split_body: C++ lambdas, C static functions). The C++ and C backends derive from this.
#include <map>
#include <set>
#include <string>
#include <utility>
#include <vector>

#include "pfgen/codegen/emitter.hpp"
#include "pfgen/codegen/expression_graph.hpp"
#include "pfgen/codegen/p_drift_loops.hpp"
#include "pfgen/codegen/scalar_mode.hpp"

namespace pfgen::codegen {

// A generated function's name and arguments, in no language's syntax: the time, the arrays its
// inputs are read from (state, then a delayed filter's `delayed`), the parameter record and the
// array its outputs are written to.
struct FunctionSignature {
  std::string function;  // "derivatives", "gain", ...
  std::string time;
  std::vector<std::string> arrays;
  std::string params;
  std::string target;
};

// A function's body, and the functions it calls that must precede it (C's parts of a split body).
struct FunctionBody {
  std::string helpers;
  std::string statements;
};

class CFamilyEmitter : public Emitter {
 public:
  // `scalar_type`: how declarations spell the scalar (C++: the alias `Scalar`; C: `double`).
  // Temporaries are named temporary_prefix + 0, 1, ... (LocalNames::temporary_prefix keeps them
  // apart from the model's names).
  CFamilyEmitter(ScalarMode mode, std::string scalar_type, std::string temporary_prefix)
      : mode_(mode), scalar_type_(std::move(scalar_type)), temporary_prefix_(std::move(temporary_prefix)) {}

  // A literal of the scalar type (`0.1f`, `0.1`, C++'s `Scalar(0.1)`); CodegenError for a constant
  // outside its range, or a nonzero one that would round to 0.
  std::string literal(const GiNaC::numeric& value) const;

  // Emitter: one method per node kind.
  std::string constant(const GiNaC::numeric& value) const override { return literal(value); }
  std::string input(const Node& node) const override { return node.name(); }
  std::string add(const std::string& a, const std::string& b) const override { return a + " + " + b; }
  std::string sub(const std::string& a, const std::string& b) const override { return a + " - " + b; }
  std::string mul(const std::string& a, const std::string& b) const override { return a + " * " + b; }
  std::string div(const std::string& a, const std::string& b) const override { return a + " / " + b; }
  std::string neg(const std::string& a) const override { return "-" + a; }
  std::string zero_where_zero(const std::string& guard, const std::string& value) const override;

  // How a function reads an input: `state[3]`, `params.a` (C: `params->a`), or an argument's name.
  std::string input_source(const Node& node) const;
  const std::string& scalar_type() const { return scalar_type_; }
  ScalarMode mode() const { return mode_; }

  // `const <scalar> <name> = <source>;` for each input of `order` that the outputs read, in that
  // order: the top of a function, so that its body reads each input by its own name. Inputs
  // without a source (arguments read directly) are skipped.
  std::string input_declarations(const ExpressionGraph& graph, const std::vector<std::size_t>& outputs,
                                 const std::vector<std::size_t>& order) const;
  // `(void)<argument>;` for each argument of `signature` (the target aside) that the outputs do
  // not read: the functions of a filter share one signature, and -Wunused-parameter stays quiet.
  std::string unused_arguments(const ExpressionGraph& graph, const std::vector<std::size_t>& outputs,
                               const FunctionSignature& signature) const;

  // Temporaries for every needed operation, each computed once, then `target[k] = ...;` for
  // output k. Indented by two spaces.
  std::string shared_body(const ExpressionGraph& graph, const std::vector<std::size_t>& outputs,
                          const std::string& target) const;
  // The same with `destinations[k] = ...;` for output k.
  std::string shared_body(const ExpressionGraph& graph, const std::vector<std::size_t>& outputs,
                          const std::vector<std::string>& destinations) const;
  // Every output as one nested expression, without temporaries: the same equations with no
  // common-subexpression elimination (benchmark baseline).
  std::string tree_body(const ExpressionGraph& graph, const std::vector<std::size_t>& outputs,
                        const std::string& target) const;

  // The whole body of a generated function writing `outputs` to signature.target: unused
  // arguments, input declarations in `order`, then the shared body (with `shared`; split when it
  // is too large) or the tree body.
  FunctionBody function_body(const ExpressionGraph& graph, const std::vector<std::size_t>& outputs,
                             const FunctionSignature& signature, const std::vector<std::size_t>& order,
                             bool shared) const;

  // The loops of `loops` (p_drift_loops.hpp): P's drift into names.out from the work array the
  // graph filled and the full P (full_P's), and m's drift copied from the work array. Indented by
  // two.
  std::string p_drift_loops(const PDriftLoops& loops, const PDriftLoopNames& names) const;
  // names.full_P, the n x n P, unpacked from the state's triangle; it opens the function, before
  // the graph's statements, so that its stores are done when the loops read its rows.
  std::string full_P(const PDriftLoops& loops, const PDriftLoopNames& names) const;

  // From now on function_body() splits a body of more than `max_ops` operations into parts of at
  // most `max_ops`; `shared_array` names the local array through which the parts pass the values
  // later parts read, a name clear of the function's others. 0: never split.
  void split_above(std::size_t max_ops, std::string shared_array);

 protected:
  // "." (C++: a reference) or "->" (C: a pointer): how a field of the parameter record is read.
  virtual std::string field_access() const = 0;
  // A body of more than max_ops_ operations in parts (the part of function_body after its
  // argument checks; split_plan() says which operation goes where).
  virtual FunctionBody split_body(const ExpressionGraph& graph, const std::vector<std::size_t>& outputs,
                                  const FunctionSignature& signature, const std::vector<std::size_t>& order) const = 0;
  // The inputs the outputs read (their node ids), and the two parts of a body's top for a given
  // set of inputs (a part of a split body reads fewer than the whole).
  static std::set<std::size_t> inputs_read(const ExpressionGraph& graph, const std::vector<std::size_t>& outputs);
  std::string declarations_of(const ExpressionGraph& graph, const std::set<std::size_t>& inputs,
                              const std::vector<std::size_t>& order) const;
  std::string unused_arguments_of(const ExpressionGraph& graph, const std::set<std::size_t>& inputs,
                                  const FunctionSignature& signature) const;
  // `const <scalar> name = value;` (a language with other statements spells it its own way).
  virtual std::string declaration(const std::string& name, const std::string& value) const {
    return "const " + scalar_type_ + " " + name + " = " + value + ";";
  }
  // The statement that marks an argument as read, for the compiler's unused-argument warning:
  // `(void)name;`.
  virtual std::string ignored(const std::string& argument) const { return "(void)" + argument + ";"; }
  // How a split body is cut: the needed operations in topological order, cut into parts of at
  // most max_ops_ consecutive ones; a value a later part reads is stored once in a slot of the
  // shared array.
  struct SplitPlan {
    std::vector<std::size_t> operations;
    std::size_t parts = 0;
    // By node number (the graph's size each; kNone for a node not in the body, or never stored):
    // its part, its temporary's number, its slot in the shared array.
    static constexpr std::size_t kNone = static_cast<std::size_t>(-1);
    std::vector<std::size_t> part, number, slot;
    std::vector<std::set<std::size_t>> reads;               // each part's values from earlier parts
    std::size_t slots = 0;
    // The part that writes an output: its computing part, or the last for an input or constant.
    std::size_t writer(const ExpressionGraph& graph, std::size_t root) const;
  };
  SplitPlan split_plan(const ExpressionGraph& graph, const std::vector<std::size_t>& outputs) const;
  std::string temporary(std::size_t number) const { return temporary_prefix_ + std::to_string(number); }

  ScalarMode mode_;
  std::string scalar_type_;
  std::string temporary_prefix_;
  std::size_t max_ops_ = 0;
  std::string shared_array_;
};

// target[0], target[1], ...
std::vector<std::string> indexed(const std::string& target, std::size_t count);

}  // namespace pfgen::codegen
