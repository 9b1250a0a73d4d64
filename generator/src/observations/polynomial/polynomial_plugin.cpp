// The polynomial observation in a simulation plugin: its filters behind the ABI's step signature
// and their table, as the continuous observation's (the truth's observation_rate(t, x, h) is
// composed from the axes in backends/cpp/truth_codegen). A linear h takes the continuous
// observation's part (observation_code's composition).
#include "pfgen/codegen/backends/cpp/simulation_plugin.hpp"
#include "pfgen/observations/continuous/continuous_code.hpp"
#include "pfgen/observations/polynomial/polynomial_code.hpp"

namespace pfgen::codegen {

void PolynomialCode::plugin_options(const Model& model, std::optional<double> grid_step, CodegenOptions& options) const {
  continuous_observation_code().plugin_options(model, grid_step, options);
}

std::string PolynomialCode::plugin_wrappers(const Model& model, const std::vector<std::string>& names,
                                            const std::vector<PluginFilterFacts>& facts) const {
  return continuous_observation_code().plugin_wrappers(model, names, facts);
}

std::map<std::string, std::string> PolynomialCode::plugin_table(const Model& model, const std::vector<std::string>& names,
                                                                const std::vector<std::string>& labels,
                                                                std::optional<double> grid_step,
                                                                const std::vector<PluginFilterFacts>& facts) const {
  return continuous_observation_code().plugin_table(model, names, labels, grid_step, facts);
}

}  // namespace pfgen::codegen
