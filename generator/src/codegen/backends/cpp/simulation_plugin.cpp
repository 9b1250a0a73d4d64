#include "pfgen/codegen/backends/cpp/simulation_plugin.hpp"

#include <algorithm>

#include <map>
#include <set>

#include "pfgen/codegen/backends/cpp/cpp_emitter.hpp"
#include "pfgen/codegen/filter_codegen.hpp"
#include "pfgen/codegen/graph_builder.hpp"
#include "pfgen/codegen/template_text.hpp"
#include "pfgen/codegen/backends/cpp/truth_codegen.hpp"
#include "pfgen/codegen/observation_code.hpp"

namespace pfgen::codegen {
namespace {

// Filters live in pfgen_simulation::filters::<model>::<name>, apart from pfgen_simulation::truth and
// pfgen_simulation::entry, so that no filter name can collide with them.
const char* const kFilterNamespace = "pfgen_simulation::filters";

// A generated header's text as part of one translation unit: `#pragma once` there would draw
// "#pragma once in main file" from the compiler, and each filter appears only once anyway.
std::string without_pragma_once(std::string text) {
  const std::string pragma = "#pragma once\n";
  const std::size_t at = text.find(pragma);
  if (at != std::string::npos) text.erase(at, pragma.size());
  return text;
}

std::string flag(bool value) { return value ? "1" : "0"; }

std::string truth_pointer(bool present, const std::string& name) {
  return present ? "&pfgen_simulation::truth::" + name : "nullptr";
}

// The ABI table's filter and timing fields, each at its value for an observation that does not have
// it (no filters' table of that form, no period, no delay): each observation module's plugin_table
// replaces those its observation has. The truth's observation functions are the truth's
// (generate_simulation_plugin).
std::map<std::string, std::string> plugin_table_defaults() {
  return {
      {"filter_table", ""},
      {"filter_count", "0"},
      {"filters", "nullptr"},
      {"period", "0.0"},
      {"sampled_filter_count", "0"},
      {"sampled_filters", "nullptr"},
      {"delay", CppEmitter(ScalarMode::Double).literal(GiNaC::numeric(0))},
      {"delay_dt", "0.0"},
      {"delay_steps", "0"},
  };
}

// pfgen_simulation::parameters: from<P>(values), a Params (the truth's, or a filter's Params<double>)
// with each parameter read from the ABI's array of values in the model's order, and the names and
// defaults the table points to.
std::string parameter_definitions(const Model& model) {
  const CppEmitter emitter(ScalarMode::Double);
  std::string from = "template <class P>\nP from(const double* values) {\n  P out;\n";
  std::string names, defaults;
  for (std::size_t k = 0; k < model.parameters.size(); ++k) {
    const auto& parameter = model.parameters[k];
    from += "  out." + parameter.name + " = values[" + std::to_string(k) + "];\n";
    names += (k ? ", " : "") + plugin_c_string(parameter.name);
    defaults += (k ? ", " : "") + emitter.literal(parameter.default_value);
  }
  if (model.parameters.empty()) return from + "  (void)values;\n  return out;\n}\n\n";
  return from + "  return out;\n}\n\ninline const char* const names[] = {" + names +
         "};\ninline const double defaults[] = {" + defaults + "};\n\n";
}

}  // namespace

std::string plugin_c_string(const std::string& text) {
  std::string out = "\"";
  for (char c : text) {
    if (c == '"' || c == '\\') out += '\\';
    out += c;
  }
  return out + "\"";
}

std::string plugin_filter_namespace(const Model& model, const std::string& identifier) {
  return std::string("::") + kFilterNamespace + "::" + model.name + "::" + identifier;
}

std::string realisability_wrapper(const Model& model, const std::string& identifier, const PluginFilterFacts& facts) {
  if (facts.margin_names.empty()) return {};
  std::string out = "void " + identifier + "_realisability_margins(const double* state, double* margins) {\n" +
                    "  namespace F = " + plugin_filter_namespace(model, identifier) + ";\n" +
                    "  F::realisability_margins(0.0, state, F::Params<double>{}, margins);\n}\n";
  out += "const char* const " + identifier + "_margin_names[] = {";
  for (std::size_t m = 0; m < facts.margin_names.size(); ++m) out += (m ? ", " : "") + plugin_c_string(facts.margin_names[m]);
  return out + "};\n";
}

std::string plugin_state_fields(const std::string& item, const std::string& ns, const std::string& identifier,
                                const PluginFilterFacts& facts) {
  if (facts.extra_state == 0) return item + "state_size = " + ns + "::state_size;\n";
  // A moment filter: its moments above P are extra state, checked by its margins.
  const std::string extra = std::to_string(facts.extra_state);
  return item + "state_size = " + ns + "::state_size - " + extra + ";\n" + item + "extra_state_size = " + extra +
         ";\n" + item + "margin_count = " + std::to_string(facts.margin_names.size()) + ";\n" + item +
         "realisability_margins = &pfgen_simulation::entry::" + identifier + "_realisability_margins;\n" + item +
         "margin_names = pfgen_simulation::entry::" + identifier + "_margin_names;\n";
}

const std::string& plugin_abi_header() { return embedded_template("pfgen_runtime/plugin_abi.h"); }

bool steps_in_lanes(const GeneratedFilter& filter) {
  std::size_t operations = 0;
  for (const FunctionStats& function : filter.functions) {
    if (function.cse.calls > 0) return false;  // sqrt, sin, ...: not defined on batch::Lanes
    if (function.in_totals) operations += function.cse.total();
  }
  return operations <= kMaxLaneOps;
}

std::string generate_simulation_plugin(const Model& model, const std::vector<FilterEquations>& filters,
                                       std::optional<double> grid_step) {
  CodegenOptions options;
  options.scalar = ScalarMode::Double;
  options.name_space = kFilterNamespace;
  const ObservationCode& observation = observation_code(model.observation);
  // A delayed observation's filters are generated for the grid (and refused without one).
  observation.plugin_options(model, grid_step, options);

  std::vector<std::string> names, labels;
  std::vector<PluginFilterFacts> facts;  // per filter: lanes, a moment filter's extra state and margins
  std::set<std::string> seen;
  std::string filter_sources;
  for (const auto& eq : filters) {
    const std::string name = filter_identifier(eq.name);
    if (!seen.insert(name).second) throw CodegenError("the filter `" + eq.name + "` is given twice for one plugin");
    names.push_back(name);
    labels.push_back(eq.name);
    GeneratedFilter generated = generate_filter_code(model, eq, options);
    filter_sources += without_pragma_once(std::move(generated.files.at(0).contents)) + "\n";
    PluginFilterFacts filter;
    filter.extra_state = eq.higher_drift.size();
    filter.in_lanes = filter.extra_state == 0 && steps_in_lanes(generated);  // lanes step m and P alone
    filter.margin_names = eq.realisability_meaning;
    facts.push_back(std::move(filter));
  }

  const TruthCode truth = generate_truth_code(model);
  const bool has_g = !truth.diffusion_is_zero && !truth.diffusion_is_covariance;
  std::map<std::string, std::string> values = {
      {"banner", "// Generated by pfgen " PFGEN_VERSION " from model `" + model.name +
                     "`: a simulation plugin (truth, observation, filters). Do not edit: `pfgen simulate` rebuilds it."},
      {"abi_header", plugin_abi_header()},
      {"filter_sources", filter_sources},
      {"parameter_definitions", parameter_definitions(model)},
      {"parameter_count", std::to_string(model.parameters.size())},
      {"parameter_names", model.parameters.empty() ? "nullptr" : "pfgen_simulation::parameters::names"},
      {"parameter_defaults", model.parameters.empty() ? "nullptr" : "pfgen_simulation::parameters::defaults"},
      {"truth_definitions", truth.definitions},
      {"filter_wrappers", observation.plugin_wrappers(model, names, facts)},
      {"model_name", plugin_c_string(model.name)},
      {"pfgen_version", plugin_c_string(PFGEN_VERSION)},
      {"n", std::to_string(truth.n)},
      {"q", std::to_string(truth.q)},
      {"p", std::to_string(truth.p)},
      {"r", std::to_string(truth.r)},
      {"diffusion_is_zero", flag(truth.diffusion_is_zero)},
      {"diffusion_is_covariance", flag(truth.diffusion_is_covariance)},
      {"observation_is_constant", flag(truth.observation_is_constant)},
      {"truth_initial_state", truth_pointer(truth.has_initial_state, "initial_state")},
      {"diffusion", truth_pointer(has_g, "diffusion")},
      {"diffusion_jacobian", truth_pointer(has_g, "diffusion_jacobian")},
      {"diffusion_covariance", truth_pointer(truth.diffusion_is_covariance, "diffusion_covariance")},
  };
  values.merge(plugin_table_defaults());
  // The truth's observation functions, those its axes gave it (truth_codegen): the timing's, and a
  // rate's rows that are not affine.
  values["observation_is_sampled"] = flag(truth.observation_is_sampled);
  values["observation"] = truth_pointer(!truth.observation_is_sampled, "observation");
  values["observation_noise"] = truth_pointer(!truth.observation_is_sampled, "observation_noise");
  values["sampled_observation"] = truth_pointer(truth.observation_is_sampled, "sampled_observation");
  values["observation_rate"] = truth_pointer(truth.has_observation_rate, "observation_rate");
  for (auto& [field, value] : observation.plugin_table(model, names, labels, grid_step, facts))
    values[field] = value;
  // The batched forms (the template's batch::lanes over the one-state function), present exactly
  // where the one-state functions are.
  const auto batch = [&](const std::string& function, std::size_t outputs) -> std::string {
    if (function == "nullptr") return function;
    return "&pfgen_simulation::batch::lanes<" + function + ", " + std::to_string(truth.n) + ", " +
           std::to_string(outputs) + ">";
  };
  values["drift_batch"] = batch("&pfgen_simulation::truth::drift", truth.n);
  values["diffusion_batch"] = batch(values.at("diffusion"), truth.n * truth.q);
  values["observation_rate_batch"] = batch(values.at("observation_rate"), truth.p);
  return fill_template("cpp/simulation_plugin.cpp.tmpl", embedded_template("cpp/simulation_plugin.cpp.tmpl"),
                       values);
}

}  // namespace pfgen::codegen
