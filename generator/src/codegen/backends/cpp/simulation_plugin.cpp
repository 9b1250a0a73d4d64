#include "pfgen/codegen/backends/cpp/simulation_plugin.hpp"

#include <map>
#include <optional>
#include <set>

#include "pfgen/codegen/backends/cpp/cpp_emitter.hpp"
#include "pfgen/codegen/filter_codegen.hpp"
#include "pfgen/codegen/graph_builder.hpp"
#include "pfgen/codegen/template_text.hpp"
#include "pfgen/codegen/backends/cpp/truth_codegen.hpp"
#include "pfgen/model/delay_grid.hpp"
#include "pfgen_support/shortest_double.hpp"

namespace pfgen::codegen {
namespace {

// Filters live in pfgen_simulation::filters::<model>::<name>, apart from pfgen_simulation::truth and
// pfgen_simulation::entry, so that no filter name can collide with them.
const char* const kFilterNamespace = "pfgen_simulation::filters";

std::string c_string(const std::string& text) {
  std::string out = "\"";
  for (char c : text) {
    if (c == '"' || c == '\\') out += '\\';
    out += c;
  }
  return out + "\"";
}

// A generated header's text as part of one translation unit: `#pragma once` there would draw
// "#pragma once in main file" from the compiler, and each filter appears only once anyway.
std::string without_pragma_once(std::string text) {
  const std::string pragma = "#pragma once\n";
  const std::size_t at = text.find(pragma);
  if (at != std::string::npos) text.erase(at, pragma.size());
  return text;
}

std::string filter_namespace(const Model& model, const std::string& name) {
  return std::string("::") + kFilterNamespace + "::" + model.name + "::" + name;
}

// The ABI's step and initial_state have no parameters argument: the model's defaults.
std::string filter_wrappers(const Model& model, const std::vector<std::string>& names) {
  std::string out;
  if (model.observation.is_sampled()) {
    for (const auto& name : names) {
      const std::string alias = "  namespace F = " + filter_namespace(model, name) + ";\n";
      out += "void " + name + "_initial_state(double* state) {\n" + alias + "  F::initial_state(state);\n}\n";
      out += "void " + name + "_predict(double* state, double t, double dt) {\n" + alias +
             "  F::predict(state, t, dt, F::Params<double>{});\n}\n";
      out += "int " + name + "_update(double* state, double t, const double* y) {\n" + alias +
             "  return F::update(state, t, y, F::Params<double>{}) ? 1 : 0;\n}\n\n";
    }
    return out;
  }
  if (model.observation.is_delayed()) {
    // The ABI's flat state is [F's state (m, P, x*), F's history]; the grid index k of the step
    // from t: the loader accepts only the grid t_k = k F::dt (fixed_dt).
    for (const auto& name : names) {
      const std::string alias = "  namespace F = " + filter_namespace(model, name) + ";\n";
      out += "void " + name + "_initial_state(double* state) {\n" + alias +
             "  F::initial_state(state);\n  F::initial_history(state, state + F::state_size);\n}\n";
      out += "void " + name + "_step(double* state, double t, double dt, const double* dy) {\n" + alias +
             "  (void)dt;  // F::dt(), the table's fixed_dt\n"
             "  F::step(state, state + F::state_size, static_cast<std::size_t>(std::llround(t / F::dt())), dy,\n"
             "          F::Params<double>{});\n}\n\n";
    }
    return out;
  }
  for (const auto& name : names) {
    const std::string alias = "  namespace F = " + filter_namespace(model, name) + ";\n";
    out += "void " + name + "_initial_state(double* state) {\n" + alias + "  F::initial_state(state);\n}\n";
    out += "void " + name + "_step(double* state, double t, double dt, const double* dy) {\n" + alias +
           "  F::step(state, t, dt, dy, F::Params<double>{});\n}\n\n";
  }
  return out;
}

// names: C++ identifiers (filter_identifier); labels: the filters' own names, for the runtime.
std::string filter_table(const Model& model, const std::vector<std::string>& names,
                         const std::vector<std::string>& labels) {
  if (names.empty()) return "";
  const std::string count = std::to_string(names.size());
  std::string out = "  static const std::array<pfgen_plugin_filter, " + count + "> filters = [] {\n" +
                    "    std::array<pfgen_plugin_filter, " + count + "> list{};\n";
  for (std::size_t k = 0; k < names.size(); ++k) {
    const std::string item = "    list[" + std::to_string(k) + "].";
    const std::string ns = "F" + std::to_string(k);
    out += "    namespace " + ns + " = " + filter_namespace(model, names[k]) + ";\n";
    out += item + "name = " + c_string(labels[k]) + ";\n";
    out += item + "n = " + ns + "::n;\n";
    out += item + "p = " + ns + "::p;\n";
    if (model.observation.is_delayed()) {
      // The ABI's state_size is m and P; x* and the history follow as extra state.
      const std::string mP = ns + "::n + " + ns + "::n * (" + ns + "::n + 1) / 2";
      out += item + "state_size = " + mP + ";\n";
      out += item + "extra_state_size = " + ns + "::state_size + " + ns + "::history_size - (" + mP + ");\n";
      out += item + "fixed_dt = " + ns + "::dt();\n";
    } else {
      out += item + "state_size = " + ns + "::state_size;\n";
    }
    out += item + "initial_state = &pfgen_simulation::entry::" + names[k] + "_initial_state;\n";
    out += item + "step = &pfgen_simulation::entry::" + names[k] + "_step;\n";
  }
  return out + "    return list;\n  }();\n";
}

// The sampled filters' table: substeps from each filter's own header (the model's, or NAME@S's).
std::string sampled_filter_table(const Model& model, const std::vector<std::string>& names,
                                 const std::vector<std::string>& labels) {
  if (names.empty()) return "";
  const std::string count = std::to_string(names.size());
  std::string out = "  static const std::array<pfgen_plugin_sampled_filter, " + count + "> sampled_filters = [] {\n" +
                    "    std::array<pfgen_plugin_sampled_filter, " + count + "> list{};\n";
  for (std::size_t k = 0; k < names.size(); ++k) {
    const std::string item = "    list[" + std::to_string(k) + "].";
    const std::string ns = "F" + std::to_string(k);
    out += "    namespace " + ns + " = " + filter_namespace(model, names[k]) + ";\n";
    out += item + "name = " + c_string(labels[k]) + ";\n";
    out += item + "n = " + ns + "::n;\n";
    out += item + "p = " + ns + "::p;\n";
    out += item + "state_size = " + ns + "::state_size;\n";
    out += item + "substeps = " + ns + "::substeps;\n";
    out += item + "initial_state = &pfgen_simulation::entry::" + names[k] + "_initial_state;\n";
    out += item + "predict = &pfgen_simulation::entry::" + names[k] + "_predict;\n";
    out += item + "update = &pfgen_simulation::entry::" + names[k] + "_update;\n";
  }
  return out + "    return list;\n  }();\n";
}

std::string flag(bool value) { return value ? "1" : "0"; }

std::string truth_function(bool present, const std::string& name) {
  return present ? "&pfgen_simulation::truth::" + name : "nullptr";
}

}  // namespace

const std::string& plugin_abi_header() { return embedded_template("pfgen_runtime/plugin_abi.h"); }

std::string generate_simulation_plugin(const Model& model, const std::vector<FilterEquations>& filters,
                                       std::optional<double> grid_step) {
  CodegenOptions options;
  options.scalar = ScalarMode::Double;
  options.name_space = kFilterNamespace;
  // The delay on the grid: the truth reads x(t - h) D steps back, the filters keep D steps.
  std::size_t delay_steps_value = 0;
  const bool delayed = model.observation.is_delayed();
  if (delayed) {
    if (!grid_step) throw CodegenError("a model with delayed observations needs the grid step dt for its plugin");
    const DelaySteps steps = delay_steps(model.observation.delay(), *grid_step);
    if (!steps.problem.empty()) throw CodegenError("observation.delay: " + steps.problem);
    delay_steps_value = steps.steps;
    options.grid_step = grid_step;
  }

  std::vector<std::string> names, labels;
  std::set<std::string> seen;
  std::string filter_sources;
  for (const auto& eq : filters) {
    const std::string name = filter_identifier(eq.name);
    if (!seen.insert(name).second) throw CodegenError("the filter `" + eq.name + "` is given twice for one plugin");
    names.push_back(name);
    labels.push_back(eq.name);
    GeneratedFilter generated = generate_filter_code(model, eq, options);
    filter_sources += without_pragma_once(std::move(generated.files.at(0).contents)) + "\n";
  }

  const TruthCode truth = generate_truth_code(model);
  const bool has_g = !truth.diffusion_is_zero && !truth.diffusion_is_covariance;
  const bool sampled = truth.sampled;
  const std::string period =
      sampled ? CppEmitter(ScalarMode::Double).literal(model.observation.sampled().period) : std::string("0.0");
  const std::map<std::string, std::string> values = {
      {"banner", "// Generated by pfgen " PFGEN_VERSION " from model `" + model.name +
                     "`: a simulation plugin (truth, observation, filters). Do not edit: `pfgen simulate` rebuilds it."},
      {"abi_header", plugin_abi_header()},
      {"filter_sources", filter_sources},
      {"truth_definitions", truth.definitions},
      {"filter_wrappers", filter_wrappers(model, names)},
      {"filter_table", sampled ? sampled_filter_table(model, names, labels) : filter_table(model, names, labels)},
      {"model_name", c_string(model.name)},
      {"pfgen_version", c_string(PFGEN_VERSION)},
      {"n", std::to_string(truth.n)},
      {"q", std::to_string(truth.q)},
      {"p", std::to_string(truth.p)},
      {"r", std::to_string(truth.r)},
      {"diffusion_is_zero", flag(truth.diffusion_is_zero)},
      {"diffusion_is_covariance", flag(truth.diffusion_is_covariance)},
      {"observation_is_constant", flag(truth.observation_is_constant)},
      {"truth_initial_state", truth_function(truth.has_initial_state, "initial_state")},
      {"diffusion", truth_function(has_g, "diffusion")},
      {"diffusion_jacobian", truth_function(has_g, "diffusion_jacobian")},
      {"diffusion_covariance", truth_function(truth.diffusion_is_covariance, "diffusion_covariance")},
      {"filter_count", sampled ? "0" : std::to_string(names.size())},
      {"filters", sampled || names.empty() ? "nullptr" : "filters.data()"},
      {"observation", sampled ? "nullptr" : "&pfgen_simulation::truth::observation"},
      {"observation_is_sampled", flag(sampled)},
      {"period", period},
      {"sampled_observation", sampled ? "&pfgen_simulation::truth::sampled_observation" : "nullptr"},
      {"sampled_filter_count", sampled ? std::to_string(names.size()) : "0"},
      {"sampled_filters", !sampled || names.empty() ? "nullptr" : "sampled_filters.data()"},
      {"delay", CppEmitter(ScalarMode::Double).literal(model.observation.delay())},
      {"delay_dt", delayed ? pfgen_support::shortest_double(*grid_step) : std::string("0.0")},
      {"delay_steps", std::to_string(delay_steps_value)},
  };
  return fill_template("cpp/simulation_plugin.cpp.tmpl", embedded_template("cpp/simulation_plugin.cpp.tmpl"),
                       values);
}

}  // namespace pfgen::codegen
