// The continuous observation in a simulation plugin: each filter's step(state, t, dt, dy) behind the
// ABI's signature, and the table of pfgen_plugin_filter (the truth's observation is composed from
// the axes in backends/cpp/truth_codegen).
#include "pfgen/codegen/backends/cpp/simulation_plugin.hpp"
#include "pfgen/observations/continuous/continuous_code.hpp"

namespace pfgen::codegen {

std::string rate_filter_table(const Model& model, const std::vector<std::string>& names,
                              const std::vector<std::string>& labels,
                              const StateFields& state_fields) {
  if (names.empty()) return "";
  const std::string count = std::to_string(names.size());
  std::string out = "  static const std::array<pfgen_plugin_filter, " + count + "> filters = [] {\n" +
                    "    std::array<pfgen_plugin_filter, " + count + "> list{};\n";
  for (std::size_t k = 0; k < names.size(); ++k) {
    const std::string item = "    list[" + std::to_string(k) + "].";
    const std::string ns = "F" + std::to_string(k);
    out += "    namespace " + ns + " = " + plugin_filter_namespace(model, names[k]) + ";\n";
    out += item + "name = " + plugin_c_string(labels[k]) + ";\n";
    out += item + "n = " + ns + "::n;\n";
    out += item + "p = " + ns + "::p;\n";
    out += state_fields(item, ns, k);
    out += item + "initial_state = &pfgen_simulation::entry::" + names[k] + "_initial_state;\n";
    out += item + "step = &pfgen_simulation::entry::" + names[k] + "_step;\n";
  }
  return out + "    return list;\n  }();\n";
}

// The filters are written with a template Scalar, so that step_lanes can instantiate them on
// batch::Lanes; step<double> is the same text as the double form.
void ContinuousCode::plugin_options(const Model&, std::optional<double>, CodegenOptions& options) const {
  options.scalar = ScalarMode::Template;
}

// The ABI's step and initial_state have no parameters argument: the model's defaults; step_at and
// predicted_observation read the parameters' values from their argument.
std::string ContinuousCode::plugin_wrappers(const Model& model, const std::vector<std::string>& names,
                                            const std::vector<PluginFilterFacts>& facts) const {
  std::string out;
  for (std::size_t k = 0; k < names.size(); ++k) {
    const std::string& name = names[k];
    const std::string alias = "  namespace F = " + plugin_filter_namespace(model, name) + ";\n";
    out += "void " + name + "_initial_state(double* state) {\n" + alias + "  F::initial_state(state);\n}\n";
    out += "void " + name + "_step(double* state, double t, double dt, const double* dy) {\n" + alias +
           "  F::step(state, t, dt, dy, F::Params<double>{});\n}\n";
    out += "void " + name + "_step_at(double* state, const double* values, double t, double dt, const double* dy) {\n" +
           alias + "  F::step(state, t, dt, dy, ::pfgen_simulation::parameters::from<F::Params<double>>(values));\n}\n";
    out += "void " + name + "_predicted_observation(const double* state, const double* values, double t, double* h) {\n" +
           alias +
           "  F::predicted_observation(t, state, ::pfgen_simulation::parameters::from<F::Params<double>>(values), h);\n}\n";
    out += realisability_wrapper(model, name, facts[k]);
    if (!facts[k].in_lanes) {
      out += "\n";
      continue;
    }
    // The same step over batch::kLanes runs: the generated step<Scalar> on batch::Lanes.
    out += "void " + name + "_step_lanes(double* state, double t, double dt, const double* dy) {\n" + alias +
           "  using L = ::pfgen_simulation::batch::Lanes;\n"
           "  ::pfgen_simulation::batch::step_lanes<F::state_size, F::p>(\n"
           "      [](L* state, L t, L dt, const L* dy) { F::step(state, t, dt, dy, F::Params<L>{}); }, state, t, dt, dy);\n"
           "}\n\n";
  }
  return out;
}

std::map<std::string, std::string> ContinuousCode::plugin_table(const Model& model, const std::vector<std::string>& names,
                                                                const std::vector<std::string>& labels,
                                                                std::optional<double>,
                                                                const std::vector<PluginFilterFacts>& facts) const {
  auto state_fields = [&](const std::string& item, const std::string& ns, std::size_t k) {
    const std::string entry = item + "step_at = &pfgen_simulation::entry::" + names[k] + "_step_at;\n" + item +
                              "predicted_observation = &pfgen_simulation::entry::" + names[k] +
                              "_predicted_observation;\n";
    const std::string size = entry + plugin_state_fields(item, ns, names[k], facts[k]);
    if (!facts[k].in_lanes) return size;  // step_lanes NULL, lanes 0
    return size + item + "step_lanes = &pfgen_simulation::entry::" + names[k] + "_step_lanes;\n" + item +
           "lanes = pfgen_simulation::batch::kLanes;\n";
  };
  return {
      {"filter_table", rate_filter_table(model, names, labels, state_fields)},
      {"filter_count", std::to_string(names.size())},
      {"filters", names.empty() ? "nullptr" : "filters.data()"},
  };
}

}  // namespace pfgen::codegen
