#pragma once
// The delayed observation dy = (A0 + A x(t - h)) dt + B dW2 in code generation (docs/theory.md
// §2.6): DelayedCode, its methods by file (delayed_code.cpp: its filter's file, layout
// delayed_filter, described in no language, with the history ring's statements of
// delayed_history.hpp; delayed_plugin.cpp: the truth's observation and the plugin's table, ABI
// version 3). Its filters have the continuous module's functions
// (continuous_code.hpp), reading m(t - h) and Phi* from a second array, and step on the fixed grid
// they are generated for, keeping a history of m (and x*) in a ring the caller owns.
#include <map>
#include <optional>
#include <string>
#include <vector>

#include "pfgen/codegen/observation_code.hpp"
#include "pfgen/model/delay_grid.hpp"

namespace pfgen::codegen {

class DelayedCode final : public ObservationCode {
 public:
  FilterFile filter_file(const Model& model, const FilterEquations& eq, const CodegenOptions& options,
                         const FunctionNames& names, const StatementEmitter& emitter) const override;
  std::vector<std::string> layouts() const override { return {"delayed_filter"}; }
  void plugin_options(const Model& model, std::optional<double> grid_step, CodegenOptions& options) const override;
  std::string plugin_wrappers(const Model& model, const std::vector<std::string>& names,
                              const std::vector<PluginFilterFacts>& facts) const override;
  std::map<std::string, std::string> plugin_table(const Model& model, const std::vector<std::string>& names,
                                                  const std::vector<std::string>& labels,
                                                  std::optional<double> grid_step,
                                                  const std::vector<PluginFilterFacts>& facts) const override;
};

// The filter's delay in steps of options.grid_step: CodegenError when there is no grid step or the
// delay is not a whole number of it.
DelaySteps filter_delay_steps(const FilterEquations& eq, const CodegenOptions& options);

// The banner's line on the grid: "// Delayed observations: h = 0.5 = 50 steps of dt = 0.01; ...".
std::string delay_banner_line(const FilterEquations& eq, const DelaySteps& steps, double grid_step);

}  // namespace pfgen::codegen
