#pragma once
// The polynomial observation dy = h(x, t) dt + B dW2 in code generation: PolynomialCode, its
// methods by file (polynomial_code.cpp: its filter's file, layout "polynomial_filter", described in
// no language; polynomial_plugin.cpp: the truth's observation rate and the plugin's table). A model whose h is
// linear in the states is the continuous observation written A0 + A x: its code is the continuous
// module's, byte for byte.
#include <map>
#include <optional>
#include <string>

#include "pfgen/codegen/filter_functions.hpp"
#include "pfgen/codegen/observation_code.hpp"

namespace pfgen::codegen {

class PolynomialCode final : public ObservationCode {
 public:
  FilterFile filter_file(const Model& model, const FilterEquations& eq, const CodegenOptions& options,
                         const FunctionNames& names, const StatementEmitter& emitter) const override;
  // A nonlinear h's only: a linear h's filters are the continuous module's (observation_code).
  std::vector<std::string> layouts() const override { return {"polynomial_filter"}; }
  std::vector<std::string> declaring_frames() const override { return {"realisability_margins"}; }  // moment filters'
  void plugin_options(const Model& model, std::optional<double> grid_step, CodegenOptions& options) const override;
  std::string plugin_wrappers(const Model& model, const std::vector<std::string>& names,
                              const std::vector<PluginFilterFacts>& facts) const override;
  std::map<std::string, std::string> plugin_table(const Model& model, const std::vector<std::string>& names,
                                                  const std::vector<std::string>& labels,
                                                  std::optional<double> grid_step,
                                                  const std::vector<PluginFilterFacts>& facts) const override;
};

// The functions of a filter for a nonlinear h (docs/theory.md §2.9), with s = [m, P's upper
// triangle] and dnu = dy - yhat dt:
//   ds = F dt + sigma dnu,  F = derivatives(),  sigma = [gain(); covariance_gain()],
//   yhat = predicted_observation(),  c = stratonovich_correction(): the drift the step subtracts
// so that Heun's scheme, which holds dy fixed across a step, converges to the Ito filter.
struct PolynomialFunctions {
  FunctionCode derivatives, gain, covariance_gain, observation, correction;
  std::optional<FunctionCode> realisability;  // a moment filter's margins (realisability_margins)
  // Their statistics in the order of the file's banner and --stats.
  std::vector<FunctionStats> stats() const;
};
PolynomialFunctions polynomial_functions(const Model& model, const FilterEquations& eq, const CodegenOptions& options,
                                         const FunctionNames& names, const StatementEmitter& emitter);

}  // namespace pfgen::codegen
