#include "pfgen/codegen/backends/cpp/cpp_emitter.hpp"

namespace pfgen::codegen {

std::string CppEmitter::call(Function function, const std::vector<std::string>& args) const {
  std::string out = std::string("std::") + function_name(function) + "(";
  for (std::size_t k = 0; k < args.size(); ++k) out += (k ? ", " : "") + args[k];
  return out + ")";
}

std::string CppEmitter::arrays(const ir::LocalArrays& node, const std::string&) const {
  std::string text = "std::array<" + type(node.type) + ", " + expression(node.length) + "> ";
  for (std::size_t k = 0; k < node.names.size(); ++k)
    text += (k ? ", " : "") + node.names[k] + (node.written_first ? "" : "{}");
  return text + (node.written_first ? ";  // written before they are read" : ";");
}

}  // namespace pfgen::codegen
