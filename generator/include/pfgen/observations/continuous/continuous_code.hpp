#pragma once
// The continuous observation dy = (A0 + A x) dt + B dW2 in code generation: ContinuousCode, its
// methods by file (continuous_code.cpp: its filter's file, layout "filter", described in no
// language; continuous_plugin.cpp: the truth's observation and the plugin's table), and what the
// delayed module, whose filters have the same functions and matrices, takes from it.
#include <functional>
#include <map>
#include <optional>
#include <string>
#include <vector>

#include "pfgen/codegen/observation_code.hpp"

namespace pfgen::codegen {

class ContinuousCode final : public ObservationCode {
 public:
  FilterFile filter_file(const Model& model, const FilterEquations& eq, const CodegenOptions& options,
                         const FunctionNames& names, const StatementEmitter& emitter) const override;
  // A moment filter's file is the polynomial observation's (filter_file).
  std::vector<std::string> layouts() const override { return {"filter", "polynomial_filter"}; }
  std::vector<std::string> declaring_frames() const override { return {"realisability_margins"}; }
  void plugin_options(const Model& model, std::optional<double> grid_step, CodegenOptions& options) const override;
  std::string plugin_wrappers(const Model& model, const std::vector<std::string>& names,
                              const std::vector<PluginFilterFacts>& facts) const override;
  std::map<std::string, std::string> plugin_table(const Model& model, const std::vector<std::string>& names,
                                                  const std::vector<std::string>& labels,
                                                  std::optional<double> grid_step,
                                                  const std::vector<PluginFilterFacts>& facts) const override;
};

// The three functions of a filter whose observation is a rate (continuous or delayed):
// derivatives(), gain() and predicted_observation(); `with_rates` (the continuous filter's step),
// also rates(), the three in one body (rates_code).
struct ContinuousFunctions {
  FunctionCode derivatives, gain, observation;
  std::optional<FunctionCode> rates;
  // Their statistics in the order of the file's banner and --stats (rates() last, when built).
  std::vector<FunctionStats> stats() const;
};
ContinuousFunctions continuous_functions(const Model& model, const FilterEquations& eq, const CodegenOptions& options,
                                         const FunctionNames& names, const StatementEmitter& emitter,
                                         bool with_rates = false);

// What gain() computes, for the templates' comment.
std::string gain_meaning(const FilterEquations& eq);

// A rate filter's functions in its file (filter and delayed_filter): `derivatives`, `gain`,
// `observation` (and `rates` when computed), the output arrays' names `K` and `h`, and
// `gain_meaning`; the statistics in their order.
void add_rate_functions(FilterFile& file, ContinuousFunctions functions, const FunctionNames& names,
                        const FilterEquations& eq);

// The plugin's table of pfgen_plugin_filter entries (names: C++ identifiers, filter_identifier;
// labels: the filters' own names, for the runtime), `state_fields` writing each entry's fields
// beyond name, sizes and the two functions, from its item prefix ("    list[0]."), its filter's
// namespace alias ("F0") and its index k in `names`.
using StateFields = std::function<std::string(const std::string& item, const std::string& ns, std::size_t k)>;
std::string rate_filter_table(const Model& model, const std::vector<std::string>& names,
                              const std::vector<std::string>& labels, const StateFields& state_fields);

}  // namespace pfgen::codegen
