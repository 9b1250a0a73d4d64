#include "pfgen/codegen/backends/c/c_filter_code.hpp"

#include <regex>

#include "pfgen/codegen/backends/c/c_emitter.hpp"
#include "pfgen/codegen/backends/c_family/cholesky_solve.hpp"
#include "pfgen/codegen/backends/c_family/file_banner.hpp"
#include "pfgen/codegen/template_text.hpp"
#include "pfgen_support/shortest_double.hpp"

namespace pfgen::codegen {
namespace {

std::string params_members(const Model& model, const CEmitter& emitter) {
  if (model.parameters.empty()) return "  char unused;  // C has no empty record\n";
  std::string text;
  for (const auto& p : model.parameters) text += "  " + emitter.scalar_type() + " " + p.name + ";\n";
  return text;
}

std::string params_defaults(const Model& model, const CEmitter& emitter) {
  if (model.parameters.empty()) return "  (void)params;\n";
  std::string text;
  for (const auto& p : model.parameters) text += "  params->" + p.name + " = " + emitter.literal(p.default_value) + ";\n";
  return text;
}

std::string initial_body(const std::vector<GiNaC::numeric>& values, const CEmitter& emitter) {
  std::string body;
  for (std::size_t v = 0; v < values.size(); ++v)
    body += "  state[" + std::to_string(v) + "] = " + emitter.literal(values[v]) + ";\n";
  return body;
}

// What a C filter's .h and .c share: the writer of both files.
struct CFilterWriter {
  const Model& model;
  const FilterEquations& eq;
  const CodegenOptions& options;
  FunctionNames names;
  std::string prefix;
  CEmitter emitter;
  GeneratedFilter result;

  CFilterWriter(const Model& m, const FilterEquations& e, const CodegenOptions& o)
      : model(m),
        eq(e),
        options(o),
        names(function_names(m)),
        prefix(c_symbol_prefix(o.name_space, m.name, e.name)),
        emitter(o.scalar, names.temporary_prefix, prefix, prefix + "_params") {
    emitter.split_above(options.max_function_ops, names.shared);
    result.name = eq.name;
    for (const std::string& path : c_filter_paths(model.name, eq.name)) result.files.push_back({path, ""});
  }

  // The placeholders of every C filter template and partial.
  std::map<std::string, std::string> common_values(std::size_t p, std::size_t state_size, const std::string& extra = "") {
    const std::string header = result.files.at(0).relative_path;
    return {
        {"banner", filter_banner(model, eq, options, result, "pfgen codegen --language c", extra)},
        {"guard", prefix + "_h"},
        {"header", header.substr(header.find_last_of('/') + 1)},
        {"prefix", prefix},
        {"scalar", emitter.scalar_type()},
        {"n", std::to_string(eq.n())},
        {"p", std::to_string(p)},
        {"state_size", std::to_string(state_size)},
        {"params_members", params_members(model, emitter)},
        {"params_defaults", params_defaults(model, emitter)},
        {"t", names.time},
        {"state", names.state},
        {"params", names.params},
        {"out", names.out},
        {"two", emitter.literal(2)},
    };
  }

  // A function's ops comment, helpers (a split body's parts) and body, under `key`_ops etc.
  static void add_function(std::map<std::string, std::string>& values, const std::string& key,
                           const FunctionCode& code) {
    values[key + "_ops"] = ops_comment(code.stats);
    values[key + "_helpers"] = code.body.helpers;
    values[key + "_body"] = code.body.statements;
  }

  // Fills the .h and .c templates: `values` holds what both need; header_only and source_only
  // what one of them has alone (every value must meet its placeholder).
  void write(const std::string& kind, std::map<std::string, std::string> values,
             const std::map<std::string, std::string>& header_only, const std::map<std::string, std::string>& source_only) {
    std::map<std::string, std::string> header_values = values, source_values = values;
    header_values.insert(header_only.begin(), header_only.end());
    source_values.insert(source_only.begin(), source_only.end());
    const std::string h = "c/" + kind + ".h.tmpl", c = "c/" + kind + ".c.tmpl";
    result.files.at(0).contents = fill_template(h, embedded_template(h), keep_used(h, header_values));
    result.files.at(1).contents = fill_template(c, embedded_template(c), keep_used(c, source_values));
  }

  // The values whose placeholders the template (with its partials) has: the .h and .c share one
  // map, each using part of it.
  static std::map<std::string, std::string> keep_used(const std::string& name, const std::map<std::string, std::string>& values) {
    std::map<std::string, std::string> used;
    const std::string text = expanded_template(name);
    for (const auto& [key, value] : values)
      if (text.find("{{" + key + "}}") != std::string::npos) used.emplace(key, value);
    return used;
  }
};

GeneratedFilter continuous_code(const Model& model, const FilterEquations& eq, const CodegenOptions& options) {
  CFilterWriter w(model, eq, options);
  const ContinuousFunctions f = continuous_functions(model, eq, options, w.names, w.emitter);
  w.result.functions = {f.derivatives.stats, f.gain.stats, f.observation.stats};
  std::map<std::string, std::string> values = w.common_values(eq.p, eq.variables.count());
  CFilterWriter::add_function(values, "derivatives", f.derivatives);
  CFilterWriter::add_function(values, "gain", f.gain);
  CFilterWriter::add_function(values, "observation", f.observation);
  values.insert({{"K", w.names.K},
                 {"h", w.names.h},
                 {"gain_meaning", gain_meaning(eq)},
                 {"initial_body", initial_body(initial_values(model, eq.variables), w.emitter)}});
  w.write("filter", values, {}, {});
  return w.result;
}

GeneratedFilter sampled_code(const Model& model, const FilterEquations& eq, const CodegenOptions& options) {
  CFilterWriter w(model, eq, options);
  const SampledFunctions f = sampled_functions(model, eq, options, w.names, w.emitter);
  const bool euler = f.euler_square.has_value();
  w.result.functions = {f.derivatives.stats};
  if (euler) w.result.functions.push_back(f.euler_square->stats);
  w.result.functions.push_back(f.innovation.stats);
  w.result.functions.push_back(f.matrices.stats);
  w.result.functions.push_back(f.observation.stats);
  const std::size_t r = eq.update.r();
  std::map<std::string, std::string> values = w.common_values(r, eq.variables.count());
  CFilterWriter::add_function(values, "derivatives", f.derivatives);
  CFilterWriter::add_function(values, "innovation", f.innovation);
  CFilterWriter::add_function(values, "matrices", f.matrices);
  CFilterWriter::add_function(values, "observation", f.observation);
  values.insert({{"h", w.names.h}, {"substeps", std::to_string(eq.update.substeps)}});
  // cd-euler's Cov(f) dt^2 function and the prediction sub-step, each a partial (templates/c/partials/).
  std::string euler_function, euler_declaration;
  if (euler) {
    std::map<std::string, std::string> euler_values = {{"prefix", w.prefix}, {"scalar", w.emitter.scalar_type()},
                                                       {"t", w.names.time},  {"state", w.names.state},
                                                       {"params", w.names.params}, {"out", w.names.out}};
    euler_declaration = fill_template("c/partials/euler_square.h.tmpl", embedded_template("c/partials/euler_square.h.tmpl"),
                                      euler_values);
    CFilterWriter::add_function(euler_values, "euler", *f.euler_square);
    euler_function = fill_template("c/partials/euler_square.c.tmpl", embedded_template("c/partials/euler_square.c.tmpl"),
                                   euler_values);
  }
  const std::string predict_partial = euler ? "c/partials/predict_euler.c.tmpl" : "c/partials/predict_heun.c.tmpl";
  std::string predict_function = fill_template(
      predict_partial, embedded_template(predict_partial),
      CFilterWriter::keep_used(predict_partial, {{"prefix", w.prefix}, {"scalar", w.emitter.scalar_type()}, {"two", w.emitter.literal(2)}}));
  predict_function.pop_back();  // its last newline: the template's line after {{predict_function}} ends it
  w.write("sampled_filter", values,
          {{"euler_declaration", euler_declaration},
           {"predict_meaning", euler ? "cd-euler's exact moments of one Euler step." : "Heun's scheme on the prediction ODEs."}},
          {{"period", w.emitter.literal(eq.update.period)},
           {"euler_function", euler_function},
           {"initial_body", initial_body(initial_values(model, eq.variables), w.emitter)},
           {"solve_body", cholesky_gain_body(r, w.emitter,
                                             {"size_t", w.prefix + "_n", w.prefix + "_p", w.emitter.literal(0), "0", "1"})},
           {"predict_function", predict_function},
           {"one", w.emitter.literal(1)},
           {"zero", w.emitter.literal(0)}});
  return w.result;
}

// The parts of a delayed filter's .c that depend on its delay in steps and on x*, written for the
// values it has (so that no branch is always true or always false, which -Wextra reports).
struct DelayedParts {
  std::string initial_history, delayed_inputs, history_store;
};

DelayedParts delayed_parts(const std::string& P, const std::string& scalar, std::size_t delay_steps, bool x_star,
                           const CEmitter& emitter) {
  DelayedParts parts;
  const std::string n = P + "_n", width = P + "_history_width", x_star_offset = "(" + P + "_state_size - " + n + ")";
  const std::string zero = emitter.literal(0), one = emitter.literal(1);
  if (delay_steps == 0) {
    parts.initial_history = "  (void)state;\n  (void)history;\n";
    parts.delayed_inputs = "  (void)history;\n  (void)start;\n  (void)k;\n  (void)offset;\n"
                           "  for (size_t i = 0; i < " + n + "; ++i) delayed[i] = now[i];\n";
    if (x_star) parts.delayed_inputs += "  for (size_t i = 0; i < " + n + "; ++i) delayed[" + n + " + i] = " + one + ";\n";
    parts.history_store = "  (void)history;\n";
    return parts;
  }
  const std::string entry = "i < " + n + " ? state[i] : state[" + P + "_state_size - " + n + " + (i - " + n + ")]";
  parts.initial_history = "  for (size_t slot = 0; slot < " + P + "_delay_steps; ++slot)\n"
                          "    for (size_t i = 0; i < " + width + "; ++i)\n"
                          "      history[slot * " + width + " + i] = " + entry + ";\n";
  std::string& d = parts.delayed_inputs;
  d = "  const " + scalar + "* m_past = history + ((k + offset) % " + P + "_delay_steps) * " + width + ";\n";
  if (x_star) d += "  const " + scalar + "* x_star_past = m_past + " + n + ";\n";
  if (delay_steps == 1) {
    d += "  if (offset == 1) {\n    m_past = start;\n";
    if (x_star) d += "    x_star_past = start + " + x_star_offset + ";\n";
    d += "  }\n";
  } else {
    d += "  (void)start;\n";
  }
  d += "  for (size_t i = 0; i < " + n + "; ++i) delayed[i] = m_past[i];\n";
  if (x_star) {
    d += "  {\n    const " + scalar + "* x_star_now = now + " + x_star_offset + ";\n"
         "    for (size_t i = 0; i < " + n + "; ++i) {\n"
         "      if (k < " + P + "_delay_steps || x_star_now[i] == " + zero + ")\n"
         "        delayed[" + n + " + i] = " + zero + ";\n"
         "      else\n"
         "        delayed[" + n + " + i] = x_star_past[i] / x_star_now[i];\n    }\n  }\n";
  } else {
    d += "  (void)now;\n";
  }
  parts.history_store = "  {\n    " + scalar + "* slot = history + (k % " + P + "_delay_steps) * " + width + ";\n"
                        "    for (size_t i = 0; i < " + width + "; ++i) slot[i] = " + entry + ";\n  }\n";
  return parts;
}

GeneratedFilter delayed_code(const Model& model, const FilterEquations& eq, const CodegenOptions& options) {
  const DelaySteps steps = filter_delay_steps(eq, options);
  CFilterWriter w(model, eq, options);
  const std::size_t n = eq.n();
  const bool x_star = eq.uses_x_star();
  const ContinuousFunctions f = continuous_functions(model, eq, options, w.names, w.emitter);
  w.result.functions = {f.derivatives.stats, f.gain.stats, f.observation.stats};
  const std::string extra = "// Delayed observations: h = " + pfgen_support::shortest_double(eq.delay.to_double()) +
                            " = " + std::to_string(steps.steps) + " steps of dt = " +
                            pfgen_support::shortest_double(*options.grid_step) +
                            "; the caller supplies dy over each step of this dt.\n";
  std::map<std::string, std::string> values = w.common_values(eq.p, eq.variables.count() + (x_star ? n : 0), extra);
  CFilterWriter::add_function(values, "derivatives", f.derivatives);
  CFilterWriter::add_function(values, "gain", f.gain);
  CFilterWriter::add_function(values, "observation", f.observation);
  const std::size_t width = x_star ? 2 * n : n, history = steps.steps * width;
  const DelayedParts parts = delayed_parts(w.prefix, w.emitter.scalar_type(), steps.steps, x_star, w.emitter);
  values.insert({{"delayed", w.names.delayed},
                 {"K", w.names.K},
                 {"h", w.names.h},
                 {"gain_meaning", gain_meaning(eq)},
                 {"history_what", x_star ? " and x*" : ""},
                 {"prehistory_x_star", x_star ? " and x*(s) = m0" : ""},
                 {"out_x_star", x_star ? ", x* drift f(x*, t)" : ""},
                 {"initial_x_star", x_star ? ", and x*(0) = m0" : ""}});
  w.write("delayed_filter", values,
          {{"state_x_star",
            x_star ? "\n// then x* (n entries), the noise-free solution dx*/dt = f(x*, t) from x*(0) = m0." : ""},
           {"delay_steps", std::to_string(steps.steps)},
           {"uses_x_star", x_star ? "1" : "0"},
           {"history_width", std::to_string(width)},
           {"history_size", std::to_string(history)},
           {"history_array_size", std::to_string(history > 0 ? history : 1)},  // C has no empty array
           {"delayed_size", std::to_string(x_star ? 2 * n : n)}},
          {{"delay", w.emitter.literal(GiNaC::numeric(eq.delay.to_double()))},
           {"dt", w.emitter.literal(GiNaC::numeric(*options.grid_step))},
           {"initial_body", initial_body(initial_values(model, eq.variables, x_star), w.emitter)},
           {"initial_history_body", parts.initial_history},
           {"delayed_inputs_body", parts.delayed_inputs},
           {"history_store", parts.history_store}});
  return w.result;
}

}  // namespace

std::vector<std::string> c_filter_paths(const std::string& model_name, const std::string& filter_name) {
  const std::string stem = model_name + "/" + filter_identifier(filter_name);
  return {stem + ".h", stem + ".c"};
}

std::string c_symbol_prefix(const std::string& name_space, const std::string& model_name, const std::string& filter_name) {
  return std::regex_replace(name_space, std::regex("::"), "_") + "_" + model_name + "_" + filter_identifier(filter_name);
}

GeneratedFilter c_filter_code(const Model& model, const FilterEquations& eq, const CodegenOptions& options) {
  if (eq.is_sampled()) return sampled_code(model, eq, options);
  if (eq.is_delayed()) return delayed_code(model, eq, options);
  return continuous_code(model, eq, options);
}

}  // namespace pfgen::codegen
