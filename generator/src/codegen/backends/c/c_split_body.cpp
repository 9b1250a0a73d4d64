// CEmitter::split_body: a straight-line body too large for one function, split into parts, as
// the C++ backend does (chunked_body.cpp says why: compilers spend time and memory faster than
// linearly in the size of one function). C has no lambdas, so each part is a static function
// <prefix>_<function>_part<k> taking the function's arguments and, when parts pass values on, the
// local array through which they do. A part names only the inputs it reads and casts the
// arguments it does not read to void. Every operation is computed once, in the same order and with
// the same temporaries' numbers as the unsplit body (split_plan), so results are bit-identical.
#include "pfgen/codegen/backends/c/c_emitter.hpp"
#include "pfgen/codegen/backends/c/c_names.hpp"

namespace pfgen::codegen {

FunctionBody CEmitter::split_body(const ExpressionGraph& graph, const std::vector<std::size_t>& outputs,
                                  const FunctionSignature& signature, const std::vector<std::size_t>& order) const {
  const ir::SplitBody split = ir::split_statements(graph, outputs, ir::indexed(signature.target, outputs.size()),
                                                   temporary_prefix_, max_ops_, shared_array_);
  const bool passes = split.plan.slots != 0;
  std::string parameters = scalar_type_ + " " + signature.time;
  std::vector<ir::Expr> arguments = {ir::name(signature.time)};
  for (const std::string& array : signature.arrays) {
    parameters += ", const " + scalar_type_ + "* " + array;
    arguments.push_back(ir::name(array));
  }
  parameters += ", const " + params_type_ + "* " + signature.params + ", " + scalar_type_ + "* " + signature.target;
  arguments.push_back(ir::name(signature.params));
  arguments.push_back(ir::name(signature.target));
  if (passes) {
    parameters += ", " + scalar_type_ + "* " + shared_array_;
    arguments.push_back(ir::name(shared_array_));
  }

  FunctionBody body;
  ir::Block calls = {ir::comment(std::to_string(split.plan.operations.size()) + " operations in " +
                                 std::to_string(split.plan.parts) + " parts of at most " + std::to_string(max_ops_) +
                                 ", each its own function: one function this large takes a compiler minutes.")};
  if (passes) calls.push_back(ir::declare_array(shared_array_, ir::Type::Scalar, split.plan.slots));
  for (std::size_t p = 0; p < split.parts.size(); ++p) {
    const ir::SplitPart& part = split.parts[p];
    const std::string name = c_part_name(symbol_prefix_, signature.function, p);
    ir::Block top = ir::unused_arguments(graph, part.inputs, signature);
    if (part.writes.empty()) top.push_back(ir::unused(signature.target));
    if (passes && part.reads.empty() && part.stores.empty()) top.push_back(ir::unused(shared_array_));
    for (ir::Statement& s : ir::input_declarations(graph, part.inputs, order)) top.push_back(std::move(s));
    body.helpers += "static void " + name + "(" + parameters + ") {\n" + block(top);
    for (const ir::Block* statements : {&part.reads, &part.arithmetic, &part.stores, &part.writes})
      body.helpers += block(*statements);
    body.helpers += "}\n\n";
    calls.push_back(ir::call_statement(name, arguments));
  }
  body.statements = block(calls);
  return body;
}

}  // namespace pfgen::codegen
