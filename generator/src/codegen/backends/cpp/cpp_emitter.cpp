#include "pfgen/codegen/backends/cpp/cpp_emitter.hpp"

namespace pfgen::codegen {

std::string CppEmitter::call(Function function, const std::vector<std::string>& args) const {
  std::string out = std::string("std::") + function_name(function) + "(";
  for (std::size_t k = 0; k < args.size(); ++k) out += (k ? ", " : "") + args[k];
  return out + ")";
}

}  // namespace pfgen::codegen
