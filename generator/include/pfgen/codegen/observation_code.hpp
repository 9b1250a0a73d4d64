#pragma once
// What code generation needs of an observation model: its filters' code in each output language,
// and its part of a simulation plugin (the truth's observation function and the ABI table's
// observation fields). Each module in observations/ implements it (observations/<kind>/<kind>_code.hpp,
// its methods in <kind>_cpp_filter, <kind>_c_filter and <kind>_plugin); generate_filter_code, the
// backends' entry points, the truth and the plugin call the model's part and never ask which kind
// it is.
#include <map>
#include <optional>
#include <string>
#include <vector>

#include "pfgen/codegen/filter_codegen.hpp"

namespace pfgen::codegen {

class ObservationCode {
 public:
  virtual ~ObservationCode() = default;

  // Refuses (CodegenError), before any graph is built, a filter whose code this observation's
  // form cannot hold at its size; nothing by default.
  virtual void check_size(const Model& model, const FilterEquations& eq) const;
  // The filter's files (GeneratedFilter::files in filter_file_paths' order) from the module's
  // templates for each backend (generator/src/observations/<kind>/templates/): cpp/ (header-only
  // C++, with CodegenOptions::eigen_wrapper its Eigen layer where the observation has one) and c/
  // (a .h/.c pair).
  virtual GeneratedFilter cpp_filter(const Model& model, const FilterEquations& eq, const CodegenOptions& options) const = 0;
  virtual GeneratedFilter c_filter(const Model& model, const FilterEquations& eq, const CodegenOptions& options) const = 0;
  // rust/ (a no_std module, templates/rust/), written with codegen/backends/rust/rust_filter_writer.hpp.
  virtual GeneratedFilter rust_filter(const Model& model, const FilterEquations& eq, const CodegenOptions& options) const = 0;
  // Every C template c_filter fills, partials included: the names its files declare after the
  // filter's prefix are read from them (backends/c/c_names.hpp).
  virtual std::vector<std::string> c_templates() const = 0;

  // The simulation plugin (backends/cpp/simulation_plugin.hpp; the truth's observation is composed
  // from the axes, backends/cpp/truth_codegen). The options the plugin's filters are generated with, from the simulation's grid step (a
  // delayed observation's filters step on that grid; CodegenError without one); unchanged by default.
  virtual void plugin_options(const Model& model, std::optional<double> grid_step, CodegenOptions& options) const;
  // The functions behind the ABI's signatures for the filters of these identifiers. in_lanes[k]:
  // filter k is also instantiated on the plugin's lane type (batch::Lanes), to step several runs at
  // once (its code is arithmetic alone and small: kMaxLaneOps, simulation_plugin.hpp).
  virtual std::string plugin_wrappers(const Model& model, const std::vector<std::string>& names,
                                      const std::vector<bool>& in_lanes) const = 0;
  // The ABI table's fields this observation's filters have (the others keep
  // plugin_table_defaults()): the filters' table and its count, the period or the delay (the
  // truth's observation functions are the truth's, TruthCode).
  virtual std::map<std::string, std::string> plugin_table(const Model& model, const std::vector<std::string>& names,
                                                          const std::vector<std::string>& labels,
                                                          std::optional<double> grid_step,
                                                          const std::vector<bool>& in_lanes) const = 0;
};

// The modules' parts (observations/<kind>/<kind>_code.cpp), and the model's, by kind.
const ObservationCode& continuous_observation_code();
const ObservationCode& sampled_observation_code();
const ObservationCode& delayed_observation_code();
const ObservationCode& polynomial_observation_code();
const ObservationCode& observation_code(ObservationKind kind);
// The model's part composed from its axes, as the derivation's (observation_derivation): samples,
// a delay, an affine rate (a linear h included, so its filters are the continuous module's), rows.
const ObservationCode& observation_code(const ObservationModel& observation);

}  // namespace pfgen::codegen
