// The sampled observation in a simulation plugin (ABI version 2): each filter's predict and update
// behind the ABI's signatures, the period and the table of pfgen_plugin_sampled_filter (the truth's
// sampled_observation is composed from the axes in backends/cpp/truth_codegen).
#include "pfgen/codegen/backends/cpp/cpp_emitter.hpp"
#include "pfgen/codegen/backends/cpp/simulation_plugin.hpp"
#include "pfgen/observations/sampled/sampled_code.hpp"

namespace pfgen::codegen {
namespace {

// The sampled filters' table: substeps from each filter's own header (the model's, or NAME@S's).
std::string sampled_filter_table(const Model& model, const std::vector<std::string>& names,
                                 const std::vector<std::string>& labels, const std::vector<PluginFilterFacts>& facts) {
  if (names.empty()) return "";
  const std::string count = std::to_string(names.size());
  std::string out = "  static const std::array<pfgen_plugin_sampled_filter, " + count + "> sampled_filters = [] {\n" +
                    "    std::array<pfgen_plugin_sampled_filter, " + count + "> list{};\n";
  for (std::size_t k = 0; k < names.size(); ++k) {
    const std::string item = "    list[" + std::to_string(k) + "].";
    const std::string ns = "F" + std::to_string(k);
    out += "    namespace " + ns + " = " + plugin_filter_namespace(model, names[k]) + ";\n";
    out += item + "name = " + plugin_c_string(labels[k]) + ";\n";
    out += item + "n = " + ns + "::n;\n";
    out += item + "p = " + ns + "::p;\n";
    out += plugin_state_fields(item, ns, names[k], facts[k]);
    out += item + "substeps = " + ns + "::substeps;\n";
    out += item + "initial_state = &pfgen_simulation::entry::" + names[k] + "_initial_state;\n";
    out += item + "predict = &pfgen_simulation::entry::" + names[k] + "_predict;\n";
    out += item + "update = &pfgen_simulation::entry::" + names[k] + "_update;\n";
    out += item + "predict_at = &pfgen_simulation::entry::" + names[k] + "_predict_at;\n";
    out += item + "update_at = &pfgen_simulation::entry::" + names[k] + "_update_at;\n";
    out += item + "innovation = &pfgen_simulation::entry::" + names[k] + "_innovation;\n";
  }
  return out + "    return list;\n  }();\n";
}

}  // namespace

// The ABI's predict and update have no parameters argument: the model's defaults; predict_at,
// update_at and innovation read the parameters' values from their argument. innovation unpacks
// innovation_terms' upper triangle of S (after P C^T) into the ABI's full p x p matrix.
std::string SampledCode::plugin_wrappers(const Model& model, const std::vector<std::string>& names,
                                        const std::vector<PluginFilterFacts>& facts) const {
  std::string out;
  for (std::size_t k = 0; k < names.size(); ++k) {
    const std::string& name = names[k];
    const std::string alias = "  namespace F = " + plugin_filter_namespace(model, name) + ";\n";
    out += "void " + name + "_initial_state(double* state) {\n" + alias + "  F::initial_state(state);\n}\n";
    out += "void " + name + "_predict(double* state, double t, double dt) {\n" + alias +
           "  F::predict(state, t, dt, F::Params<double>{});\n}\n";
    out += "int " + name + "_update(double* state, double t, const double* y) {\n" + alias +
           "  return F::update(state, t, y, F::Params<double>{}) ? 1 : 0;\n}\n";
    const std::string at = "  const auto params = ::pfgen_simulation::parameters::from<F::Params<double>>(values);\n";
    out += "void " + name + "_predict_at(double* state, const double* values, double t, double dt) {\n" + alias + at +
           "  F::predict(state, t, dt, params);\n}\n";
    out += "int " + name + "_update_at(double* state, const double* values, double t, const double* y) {\n" + alias +
           at + "  return F::update(state, t, y, params) ? 1 : 0;\n}\n";
    out += "void " + name + "_innovation(const double* state, const double* values, double t, double* yhat, double* S) {\n" +
           alias + at +
           "  std::array<double, F::n * F::p + F::p * (F::p + 1) / 2> u;\n"
           "  F::innovation_terms(t, state, params, u.data());\n"
           "  F::predicted_observation(t, state, params, yhat);\n"
           "  std::size_t k = F::n * F::p;\n"
           "  for (std::size_t i = 0; i < F::p; ++i)\n"
           "    for (std::size_t j = i; j < F::p; ++j) S[i * F::p + j] = S[j * F::p + i] = u[k++];\n}\n";
    out += realisability_wrapper(model, name, facts[k]) + "\n";
  }
  return out;
}

std::map<std::string, std::string> SampledCode::plugin_table(const Model& model, const std::vector<std::string>& names,
                                                             const std::vector<std::string>& labels,
                                                             std::optional<double>,
                                                             const std::vector<PluginFilterFacts>& facts) const {
  return {
      {"filter_table", sampled_filter_table(model, names, labels, facts)},
      {"period", CppEmitter(ScalarMode::Double).literal(model.observation.samples()->period)},
      {"sampled_filter_count", std::to_string(names.size())},
      {"sampled_filters", names.empty() ? "nullptr" : "sampled_filters.data()"},
  };
}

}  // namespace pfgen::codegen
