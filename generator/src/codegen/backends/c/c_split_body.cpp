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
  const ir::SplitPlan plan = ir::split_plan(graph, outputs, max_ops_);
  const std::vector<std::string> destinations = indexed(signature.target, outputs.size());
  auto spell = [&](std::size_t id) {
    return graph.is_leaf(id) ? expression(graph.node(id), {}) : temporary(plan.number.at(id));
  };
  const bool passes = plan.slots != 0;
  std::string parameters = scalar_type_ + " " + signature.time;
  std::string arguments = signature.time;
  for (const std::string& array : signature.arrays) {
    parameters += ", const " + scalar_type_ + "* " + array;
    arguments += ", " + array;
  }
  parameters += ", const " + params_type_ + "* " + signature.params + ", " + scalar_type_ + "* " + signature.target;
  arguments += ", " + signature.params + ", " + signature.target;
  if (passes) {
    parameters += ", " + scalar_type_ + "* " + shared_array_;
    arguments += ", " + shared_array_;
  }

  FunctionBody body;
  body.statements = "  // " + std::to_string(plan.operations.size()) + " operations in " + std::to_string(plan.parts) +
                    " parts of at most " + std::to_string(max_ops_) +
                    ", each its own function: one function this large takes a compiler minutes.\n";
  if (passes) body.statements += "  " + scalar_type_ + " " + shared_array_ + "[" + std::to_string(plan.slots) + "];\n";
  std::size_t next = 0;
  for (std::size_t p = 0; p < plan.parts; ++p) {
    const std::string part = c_part_name(symbol_prefix_, signature.function, p);
    std::string reads, arithmetic, stores, writes;
    std::set<std::size_t> inputs;
    auto note_input = [&](std::size_t id) {
      if (graph.node(id).kind == OpKind::Input) inputs.insert(id);
    };
    for (std::size_t id : plan.reads[p])
      reads += "  " + declaration(spell(id), shared_array_ + "[" + std::to_string(plan.slot.at(id)) + "]") + "\n";
    for (; next < plan.operations.size() && plan.part.at(plan.operations[next]) == p; ++next) {
      const std::size_t id = plan.operations[next];
      std::vector<std::string> operands;
      for (std::size_t arg : graph.node(id).args) {
        note_input(arg);
        operands.push_back(spell(arg));
      }
      arithmetic += "  " + declaration(spell(id), expression(graph.node(id), operands)) + "\n";
      if (plan.slot[id] != ir::SplitPlan::kNone)
        stores += "  " + shared_array_ + "[" + std::to_string(plan.slot[id]) + "] = " + spell(id) + ";\n";
    }
    for (std::size_t k = 0; k < outputs.size(); ++k)
      if (plan.writer(graph, outputs[k]) == p) {
        note_input(outputs[k]);
        writes += "  " + destinations.at(k) + " = " + spell(outputs[k]) + ";\n";
      }
    std::string top = unused_arguments_of(graph, inputs, signature);
    if (writes.empty()) top += "  (void)" + signature.target + ";\n";
    if (passes && reads.empty() && stores.empty()) top += "  (void)" + shared_array_ + ";\n";
    body.helpers += "static void " + part + "(" + parameters + ") {\n" + top +
                    declarations_of(graph, inputs, order) + reads + arithmetic + stores + writes + "}\n\n";
    body.statements += "  " + part + "(" + arguments + ");\n";
  }
  return body;
}

}  // namespace pfgen::codegen
