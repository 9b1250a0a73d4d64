#include "pfgen/codegen/backends/c/c_filter_code.hpp"

#include <regex>

#include "pfgen/codegen/backends/c/c_names.hpp"
#include "pfgen/codegen/observation_code.hpp"

namespace pfgen::codegen {

std::vector<std::string> c_filter_paths(const std::string& model_name, const std::string& filter_name) {
  const std::string stem = model_name + "/" + filter_identifier(filter_name);
  return {stem + ".h", stem + ".c"};
}

std::string c_symbol_prefix(const std::string& name_space, const std::string& model_name, const std::string& filter_name) {
  return std::regex_replace(name_space, std::regex("::"), "_") + "_" + model_name + "_" + filter_identifier(filter_name);
}

GeneratedFilter c_filter_code(const Model& model, const FilterEquations& eq, const CodegenOptions& options) {
  try {
    return observation_code(eq.observation).c_filter(model, eq, options);
  } catch (const CPartNameError& e) {
    throw CodegenError(source_place(model) + e.what());
  }
}

}  // namespace pfgen::codegen
