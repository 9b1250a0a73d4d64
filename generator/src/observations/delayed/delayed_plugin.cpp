// The delayed observation in a simulation plugin (ABI version 3): each filter's step behind the ABI's
// signature with its history after its state, the table with each filter's extra state and fixed
// grid step, and h, dt and D = h / dt, with which the runtime reads the truth's observation(t, A0,
// A, B) at x D steps back; version 8: step_at and predicted_observation at given parameter values,
// for recorded data.
#include "pfgen/codegen/backends/cpp/cpp_emitter.hpp"
#include "pfgen/codegen/backends/cpp/simulation_plugin.hpp"
#include "pfgen/observations/continuous/continuous_code.hpp"
#include "pfgen/observations/delayed/delayed_code.hpp"
#include "pfgen_support/shortest_double.hpp"

namespace pfgen::codegen {

// The plugin's filters are generated for the simulation's grid: the truth reads x(t - h) D steps
// back, the filters keep D steps.
void DelayedCode::plugin_options(const Model& model, std::optional<double> grid_step, CodegenOptions& options) const {
  if (!grid_step) throw CodegenError("a model with delayed observations needs the grid step dt for its plugin");
  const DelaySteps steps = delay_steps(model.observation.delay(), *grid_step);
  if (!steps.problem.empty()) throw CodegenError("observation.delay: " + steps.problem);
  options.grid_step = grid_step;
}

// The ABI's flat state is [F's state (m, P, x*), F's history]; the grid index k of the step from t:
// the loader accepts only the grid t_k = k F::dt (fixed_dt).
std::string DelayedCode::plugin_wrappers(const Model& model, const std::vector<std::string>& names,
                                        const std::vector<PluginFilterFacts>&) const {
  std::string out;
  for (const auto& name : names) {
    const std::string alias = "  namespace F = " + plugin_filter_namespace(model, name) + ";\n";
    out += "void " + name + "_initial_state(double* state) {\n" + alias +
           "  F::initial_state(state);\n  F::initial_history(state, state + F::state_size);\n}\n";
    out += "void " + name + "_step(double* state, double t, double dt, const double* dy) {\n" + alias +
           "  (void)dt;  // F::dt(), the table's fixed_dt\n"
           "  F::step(state, state + F::state_size, static_cast<std::size_t>(std::llround(t / F::dt())), dy,\n"
           "          F::Params<double>{});\n}\n";
    // Recorded data (ABI version 8): the same step at the given parameters, and the rate its
    // predictor reads, A0 + A m(t - h) with m(t - h) from the history at grid index k - D.
    out += "void " + name + "_step_at(double* state, const double* values, double t, double dt, const double* dy) {\n" +
           alias +
           "  (void)dt;\n"
           "  F::step(state, state + F::state_size, static_cast<std::size_t>(std::llround(t / F::dt())), dy,\n"
           "          ::pfgen_simulation::parameters::from<F::Params<double>>(values));\n}\n";
    out += "void " + name + "_predicted_observation(const double* state, const double* values, double t, double* h) {\n" +
           alias +
           "  const std::size_t k = static_cast<std::size_t>(std::llround(t / F::dt()));\n"
           "  std::array<double, F::delayed_size> delayed{};\n"
           "  F::detail::delayed_inputs(state + F::state_size, state, state, k, 0, delayed.data());\n"
           "  F::predicted_observation(static_cast<double>(k) * F::dt(), state, delayed.data(),\n"
           "                           ::pfgen_simulation::parameters::from<F::Params<double>>(values), h);\n}\n\n";
  }
  return out;
}

std::map<std::string, std::string> DelayedCode::plugin_table(const Model& model, const std::vector<std::string>& names,
                                                             const std::vector<std::string>& labels,
                                                             std::optional<double> grid_step,
                                                             const std::vector<PluginFilterFacts>&) const {
  // The ABI's state_size is m and P; x* and the history follow as extra state.
  auto state_fields = [](const std::string& item, const std::string& ns, std::size_t) {
    const std::string mP = ns + "::n + " + ns + "::n * (" + ns + "::n + 1) / 2";
    return item + "state_size = " + mP + ";\n" + item + "extra_state_size = " + ns + "::state_size + " + ns +
           "::history_size - (" + mP + ");\n" + item + "fixed_dt = " + ns + "::dt();\n";
  };
  auto fields = [&](const std::string& item, const std::string& ns, std::size_t k) {
    return state_fields(item, ns, k) + item + "step_at = &pfgen_simulation::entry::" + names[k] + "_step_at;\n" + item +
           "predicted_observation = &pfgen_simulation::entry::" + names[k] + "_predicted_observation;\n";
  };
  return {
      {"filter_table", rate_filter_table(model, names, labels, fields)},
      {"filter_count", std::to_string(names.size())},
      {"filters", names.empty() ? "nullptr" : "filters.data()"},
      {"delay", CppEmitter(ScalarMode::Double).literal(model.observation.delay())},
      {"delay_dt", pfgen_support::shortest_double(*grid_step)},
      {"delay_steps", std::to_string(delay_steps(model.observation.delay(), *grid_step).steps)},
  };
}

}  // namespace pfgen::codegen
