#pragma once
// An ExpressionGraph lowered to statements (statements.hpp), for every language alike: a
// generated function's top (the arguments it does not read, each input it reads named once),
// then every operation once as a constant temporary, then its outputs; or, without sharing, each
// output as one expression tree. And the plan by which a body too large for one function is cut
// into parts (split_plan), which each language writes by its own means.
#include <cstddef>
#include <set>
#include <string>
#include <vector>

#include "pfgen/codegen/expression_graph.hpp"
#include "pfgen/codegen/ir/statements.hpp"

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

}  // namespace pfgen::codegen

namespace pfgen::codegen::ir {

// target[0], target[1], ...
std::vector<Expr> indexed(const std::string& target, std::size_t count);

// The inputs the outputs read (their node ids).
std::set<std::size_t> inputs_read(const ExpressionGraph& graph, const std::vector<std::size_t>& outputs);
// Where a function reads an input: an argument's name, an array's element (`state[3]`) or a field
// of the parameter record (`params.a`).
Expr input_source(const Node& node);
// A leaf of the graph as a body reads it: an input by its name, a constant as a number.
Expr leaf(const Node& node);
// An operation of the graph on its operands' expressions.
Expr operation(const Node& node, std::vector<Expr> operands);

// A constant declaration `name = source` for each of `inputs` in `order` that has a source (inputs
// read as the arguments they are are not declared): the top of a function, so that its body reads
// each input by its own name.
Block input_declarations(const ExpressionGraph& graph, const std::set<std::size_t>& inputs,
                         const std::vector<std::size_t>& order);
// Unused for each argument of `signature` (the target aside) that none of `inputs` is read from:
// the functions of a filter share one signature.
Block unused_arguments(const ExpressionGraph& graph, const std::set<std::size_t>& inputs,
                       const FunctionSignature& signature);
// Every needed operation once, as the temporary prefix + its number, then destinations[k] = output k.
Block shared_statements(const ExpressionGraph& graph, const std::vector<std::size_t>& outputs,
                        const std::vector<Expr>& destinations, const std::string& temporary_prefix);
// destinations[k] = output k as one expression tree, each operation but a call grouped.
Block tree_statements(const ExpressionGraph& graph, const std::vector<std::size_t>& outputs,
                      const std::vector<Expr>& destinations);

// How a body too large for one function is cut: the needed operations in topological order, cut
// into parts of at most max_ops consecutive ones; a value a later part reads is stored once in a
// slot of a shared array.
struct SplitPlan {
  std::size_t max_ops = 0;
  std::vector<std::size_t> operations;
  std::size_t parts = 0;
  // By node number (the graph's size each; kNone for a node not in the body, or never stored):
  // its part, its temporary's number, its slot in the shared array.
  static constexpr std::size_t kNone = static_cast<std::size_t>(-1);
  std::vector<std::size_t> part, number, slot;
  std::vector<std::set<std::size_t>> reads;  // each part's values from earlier parts
  std::size_t slots = 0;
  // The part that writes an output: its computing part, or the last for an input or constant.
  std::size_t writer(const ExpressionGraph& graph, std::size_t root) const;
};
SplitPlan split_plan(const ExpressionGraph& graph, const std::vector<std::size_t>& outputs, std::size_t max_ops);

// A body cut by its split plan, as statements: each part's reads of earlier parts' values from the
// shared array, its operations (temporaries numbered as the unsplit body numbers them), its stores
// of the values later parts read, and the outputs it writes; and the inputs it reads, which a
// language whose parts are functions of their own (C) declares in each part.
struct SplitPart {
  std::set<std::size_t> inputs;
  Block reads, arithmetic, stores, writes;
};
struct SplitBody {
  SplitPlan plan;
  std::vector<SplitPart> parts;
};
SplitBody split_statements(const ExpressionGraph& graph, const std::vector<std::size_t>& outputs,
                           const std::vector<Expr>& destinations, const std::string& temporary_prefix,
                           std::size_t max_ops, const std::string& shared_array);

}  // namespace pfgen::codegen::ir
