#pragma once
// What code generation needs of an observation model: its filters' code in each output language,
// and its part of a simulation plugin (the truth's observation function and the ABI table's
// observation fields). Each module in observations/ implements it (observations/<kind>/<kind>_code.hpp,
// its filters' files described in <kind>_code, its plugin part in <kind>_plugin); the backends'
// writers, the truth and the plugin call the model's part and never ask which kind it is.
#include <map>
#include <optional>
#include <string>
#include <vector>

#include "pfgen/codegen/filter_codegen.hpp"
#include "pfgen/codegen/filter_file.hpp"

namespace pfgen::codegen {

// What the plugin's table says of each filter besides its name: whether it also steps several runs at once
// (step_lanes: its code is arithmetic alone and small, kMaxLaneOps, simulation_plugin.hpp), and a moment
// filter's state beyond m and P and its realisability margins (none for the others).
struct PluginFilterFacts {
  bool in_lanes = false;
  std::size_t extra_state = 0;
  std::vector<std::string> margin_names;
};

class ObservationCode {
 public:
  virtual ~ObservationCode() = default;

  // Refuses (CodegenError), before any graph is built, a filter whose code this observation's
  // form cannot hold at its size; nothing by default.
  virtual void check_size(const Model& model, const FilterEquations& eq) const;
  // The filter's file as this observation describes it, in no language (filter_file.hpp): its
  // layout, its functions with their bodies written by `emitter` (the backend's, with `names`), its
  // statements, words and statistics. Each backend's writer (backends/<language>/) turns it into
  // that language's files.
  virtual FilterFile filter_file(const Model& model, const FilterEquations& eq, const CodegenOptions& options,
                                 const FunctionNames& names, const StatementEmitter& emitter) const = 0;
  // Every layout filter_file may give (FilterFile::layout): the C backend reads the names its
  // templates of these declare (backends/c/c_names.hpp).
  virtual std::vector<std::string> layouts() const = 0;
  // Every frame filter_file may choose that declares a function of the file (FilterFile::frames'
  // partials, as cd-euler's euler_square): the C backend reads the names those declare too.
  virtual std::vector<std::string> declaring_frames() const { return {}; }

  // The simulation plugin (backends/cpp/simulation_plugin.hpp; the truth's observation is composed
  // from the axes, backends/cpp/truth_codegen). The options the plugin's filters are generated with,
  // from the simulation's grid step (a delayed observation's filters step on that grid; CodegenError
  // without one); unchanged by default.
  virtual void plugin_options(const Model& model, std::optional<double> grid_step, CodegenOptions& options) const;
  // The functions behind the ABI's signatures for the filters of these identifiers; facts[k].in_lanes:
  // filter k is also instantiated on the plugin's lane type (batch::Lanes), to step several runs at once.
  virtual std::string plugin_wrappers(const Model& model, const std::vector<std::string>& names,
                                      const std::vector<PluginFilterFacts>& facts) const = 0;
  // The ABI table's fields this observation's filters have (the others keep
  // plugin_table_defaults()): the filters' table and its count, the period or the delay (the
  // truth's observation functions are the truth's, TruthCode).
  virtual std::map<std::string, std::string> plugin_table(const Model& model, const std::vector<std::string>& names,
                                                          const std::vector<std::string>& labels,
                                                          std::optional<double> grid_step,
                                                          const std::vector<PluginFilterFacts>& facts) const = 0;
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
