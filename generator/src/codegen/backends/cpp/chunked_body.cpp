// CppEmitter::chunked_body: a straight-line body too large for one function, split into parts.
//
// Why: g++ -O2 spends time and memory faster than linearly in the size of one function (register
// allocation, dead-store elimination and the combiner dominate -ftime-report for a 33k-operation
// body: 84 s of CPU and 1.8 GB). The same operations in parts of a few thousand each compile in a
// fraction of that. Each part is a lambda marked noinline, so that the compiler cannot merge the
// parts back into one function; the lambdas capture everything by reference, so they read the
// function's arguments and named inputs like the unsplit body does.
//
// Sharing is kept: every operation is still computed once. The operations are cut into parts of at
// most max_ops_ consecutive operations in the graph's topological order; a value that a later part
// reads (or a later output) is stored once in the local array shared_array_ and read back by name
// at the top of each part that needs it. Temporaries keep the numbers the unsplit body gives them.
#include <map>
#include <set>

#include "pfgen/codegen/backends/cpp/cpp_emitter.hpp"

namespace pfgen::codegen {

std::string CppEmitter::chunked_body(const ExpressionGraph& graph, const std::vector<std::size_t>& outputs,
                                     const std::vector<std::string>& destinations) const {
  const std::vector<std::size_t> operations = graph.needed_operations(outputs);
  const std::size_t parts = (operations.size() + max_ops_ - 1) / max_ops_;
  std::map<std::size_t, std::size_t> part_of, number;  // operation -> its part, its temporary's number
  for (std::size_t k = 0; k < operations.size(); ++k) {
    part_of[operations[k]] = k / max_ops_;
    number[operations[k]] = k;
  }
  // An output is written by the part that computes it; an output that is an input or a constant,
  // by the last part.
  auto writer = [&](std::size_t root) { return graph.is_leaf(root) ? parts - 1 : part_of.at(root); };

  // The values some part reads from an earlier part: their slots in the shared array, by number.
  std::vector<std::set<std::size_t>> reads(parts);
  for (std::size_t id : operations)
    for (std::size_t arg : graph.node(id).args)
      if (!graph.is_leaf(arg) && part_of.at(arg) != part_of.at(id)) reads[part_of.at(id)].insert(arg);
  std::map<std::size_t, std::size_t> slot;
  for (const auto& part : reads)
    for (std::size_t id : part) slot.emplace(id, 0);
  std::size_t slots = 0;
  for (auto& entry : slot) entry.second = slots++;

  auto temporary = [&](std::size_t id) { return temporary_prefix_ + std::to_string(number.at(id)); };
  auto spell = [&](std::size_t id) {
    return graph.is_leaf(id) ? expression(graph.node(id), {}) : temporary(id);
  };
  std::string body = "  // " + std::to_string(operations.size()) + " operations in " + std::to_string(parts) +
                     " parts of at most " + std::to_string(max_ops_) +
                     ", each its own function: one function this large takes g++ minutes to compile.\n";
  body +=
      "#ifndef PFGEN_NOINLINE\n#if defined(__GNUC__)\n#define PFGEN_NOINLINE __attribute__((noinline))\n#else\n"
      "#define PFGEN_NOINLINE\n#endif\n#endif\n";
  if (slots != 0) body += "  Scalar " + shared_array_ + "[" + std::to_string(slots) + "];\n";
  std::size_t next = 0;
  for (std::size_t p = 0; p < parts; ++p) {
    body += "  [&]() PFGEN_NOINLINE {\n";
    std::string stores;  // after the part's arithmetic (see above)
    for (std::size_t id : reads[p])
      body += "    const Scalar " + temporary(id) + " = " + shared_array_ + "[" + std::to_string(slot.at(id)) + "];\n";
    for (; next < operations.size() && part_of.at(operations[next]) == p; ++next) {
      const std::size_t id = operations[next];
      std::vector<std::string> operands;
      for (std::size_t arg : graph.node(id).args) operands.push_back(spell(arg));
      body += "    const Scalar " + temporary(id) + " = " + expression(graph.node(id), operands) + ";\n";
      auto shared = slot.find(id);
      if (shared != slot.end())
        stores += "    " + shared_array_ + "[" + std::to_string(shared->second) + "] = " + temporary(id) + ";\n";
    }
    body += stores;
    for (std::size_t k = 0; k < outputs.size(); ++k)
      if (writer(outputs[k]) == p) body += "    " + destinations.at(k) + " = " + spell(outputs[k]) + ";\n";
    body += "  }();\n";
  }
  return body;
}

}  // namespace pfgen::codegen
