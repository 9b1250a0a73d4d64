// CppEmitter::split_body: a straight-line body too large for one function, split into parts.
//
// Why: g++ -O2 spends time and memory faster than linearly in the size of one function (register
// allocation, dead-store elimination and the combiner dominate -ftime-report for a 33k-operation
// body: 84 s of CPU and 1.8 GB). The same operations in parts of a few thousand each compile in a
// fraction of that. Each part is a lambda marked noinline, so that the compiler cannot merge the
// parts back into one function; the lambdas capture everything by reference, so they read the
// function's arguments and named inputs like the unsplit body does.
//
// Sharing is kept: every operation is still computed once. The operations are cut into parts of at
// most max_ops_ consecutive operations in the graph's topological order (split_plan); a value that
// a later part reads (or a later output) is stored once in the local array shared_array_ and read
// back by name at the top of each part that needs it. Temporaries keep the numbers the unsplit
// body gives them.
#include "pfgen/codegen/backends/cpp/cpp_emitter.hpp"

namespace pfgen::codegen {

FunctionBody CppEmitter::split_body(const ExpressionGraph& graph, const std::vector<std::size_t>& outputs,
                                    const FunctionSignature& signature, const std::vector<std::size_t>& order) const {
  const ir::SplitBody split = ir::split_statements(graph, outputs, ir::indexed(signature.target, outputs.size()),
                                                   temporary_prefix_, max_ops_, shared_array_);
  std::string body = unused_arguments(graph, outputs, signature) + input_declarations(graph, outputs, order);
  body += "  // " + std::to_string(split.plan.operations.size()) + " operations in " + std::to_string(split.plan.parts) +
          " parts of at most " + std::to_string(max_ops_) +
          ", each its own function: one function this large takes g++ minutes to compile.\n";
  body +=
      "#ifndef PFGEN_NOINLINE\n#if defined(__GNUC__)\n#define PFGEN_NOINLINE __attribute__((noinline))\n#else\n"
      "#define PFGEN_NOINLINE\n#endif\n#endif\n";
  if (split.plan.slots != 0) body += block({ir::declare_array(shared_array_, ir::Type::Scalar, split.plan.slots)});
  for (const ir::SplitPart& part : split.parts) {
    body += "  [&]() PFGEN_NOINLINE {\n";
    for (const ir::Block* statements : {&part.reads, &part.arithmetic, &part.stores, &part.writes})
      body += block(*statements, "    ");
    body += "  }();\n";
  }
  return {"", body};
}

}  // namespace pfgen::codegen
