#include "pfgen/codegen/backends/cpp/cpp_filter_code.hpp"

#include "pfgen/codegen/observation_code.hpp"

namespace pfgen::codegen {

std::vector<std::string> cpp_filter_paths(const std::string& model_name, const std::string& filter_name,
                                          bool eigen_wrapper) {
  const std::string stem = model_name + "/" + filter_identifier(filter_name);
  if (!eigen_wrapper) return {stem + ".hpp"};
  return {stem + ".hpp", stem + "_eigen.hpp"};
}

GeneratedFilter cpp_filter_code(const Model& model, const FilterEquations& eq, const CodegenOptions& options) {
  return observation_code(eq.observation).cpp_filter(model, eq, options);
}

}  // namespace pfgen::codegen
