#pragma once
// The C++ source of a simulation plugin: one self-contained translation unit holding a model's
// truth (truth_codegen.hpp), its filters (filter_codegen.hpp, double) and the table of the
// plugin ABI (runtime/include/pfgen_runtime/plugin_abi.h, pasted in verbatim), for
// `pfgen simulate` to compile into a shared object (toolchain/plugin_compiler.hpp) and load
// (pfgen_runtime::SimulationPlugin). The text is deterministic: it is the cache key's input.
#include <optional>
#include <string>
#include <vector>

#include "pfgen/codegen/filter_codegen.hpp"
#include "pfgen/codegen/observation_code.hpp"
#include "pfgen/derivation/filter_equations.hpp"
#include "pfgen/model/model.hpp"

namespace pfgen::codegen {

// The filters in the given order, each named by its own name (FilterEquations::name, e.g.
// "ekf-additive") for the runtime and by filter_identifier(name) in the C++. Throws
// CodegenError when two filters share an identifier, or for what the code generator cannot write.
// A model with delayed observations needs grid_step, the simulation's dt: its filters are
// generated for that grid (CodegenOptions::grid_step), and the table records h, dt and D = h / dt.
// Other models ignore it, so their plugin source does not depend on dt.
std::string generate_simulation_plugin(const Model& model, const std::vector<FilterEquations>& filters,
                                       std::optional<double> grid_step = std::nullopt);

// Whether a filter also steps runs side by side in the plugin (the ABI's step_lanes: its step
// instantiated on the template's batch::Lanes): its code calls no function (batch::Lanes has
// arithmetic only) and has at most kMaxLaneOps operations after CSE. The lanes pay where the
// bookkeeping around a small step costs as much as the step; a large step is compute-bound
// already, and its instantiation on 8 lanes costs the compiler several times the double one (the
// 16-state INS's filters of 3 500 operations: 83 s against 11 s).
inline constexpr std::size_t kMaxLaneOps = 500;
bool steps_in_lanes(const GeneratedFilter& filter);

// The text of pfgen_runtime/plugin_abi.h, compiled into pfgen at build time.
const std::string& plugin_abi_header();

// For the observation modules' parts of the plugin (ObservationCode::plugin_wrappers, plugin_table):
// a C string literal of `text`, and the namespace of the plugin's filter of that identifier,
// ::pfgen_simulation::filters::<model>::<identifier>.
std::string plugin_c_string(const std::string& text);
std::string plugin_filter_namespace(const Model& model, const std::string& identifier);
// A moment filter's realisability margins behind the ABI's signature, <identifier>_realisability_margins, and their
// names, <identifier>_margin_names (empty for another filter): continuous and sampled filters alike.
std::string realisability_wrapper(const Model& model, const std::string& identifier, const PluginFilterFacts& facts);
// A table entry's state_size (m and P) and, for a moment filter, its extra state and margins (the wrapper's above):
// the lines `item`state_size = ... of the filter `identifier`, namespace alias `ns`. Continuous and sampled tables.
std::string plugin_state_fields(const std::string& item, const std::string& ns, const std::string& identifier,
                                const PluginFilterFacts& facts);

}  // namespace pfgen::codegen
