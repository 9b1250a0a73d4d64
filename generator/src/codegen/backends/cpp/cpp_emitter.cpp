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
  if (!node.written_first) return text + ";";
  return text + ";" + trailing_comment(node.written_by.empty() ? "written before they are read"
                                                                : "every entry written by " + node.written_by);
}

std::string CppEmitter::cast_to_scalar(const ir::Expr& index) const {
  ir::Expr bare = index;
  bare.grouped = false;  // the cast's own parentheses hold it
  return "static_cast<Scalar>(" + expression(bare) + ")";
}

std::string CppEmitter::view(const ir::View& node, const std::string& indent) const {
  std::string text = CFamilyEmitter::view(node, indent);
  if (!node.packed_rows) return text;
  const std::string rows = expression(*node.packed_rows);
  return text + "\n" + indent + "auto " + node.name + "_at = [&](std::size_t a, std::size_t b) {\n" + indent +
         "  if (a > b) { const std::size_t c = a; a = b; b = c; }\n" + indent + "  return " + node.name + "[a * " + rows +
         " - a * (a + 1) / 2 + b];\n" + indent + "};";
}

}  // namespace pfgen::codegen
