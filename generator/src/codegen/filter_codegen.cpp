#include "pfgen/codegen/filter_codegen.hpp"

#include <cstdio>

#include "pfgen/codegen/backends/cpp/cholesky_solve.hpp"
#include "pfgen/codegen/correction_factor.hpp"
#include "pfgen/codegen/backends/cpp/cpp_names.hpp"
#include "pfgen/codegen/graph_builder.hpp"
#include "pfgen/codegen/template_text.hpp"
#include "pfgen/model/delay_grid.hpp"
#include "pfgen_support/shortest_double.hpp"

namespace pfgen::codegen {
namespace {

std::string counts_text(const OpCounts& c) {
  return std::to_string(c.total()) + " (" + std::to_string(c.adds) + " add, " + std::to_string(c.muls) + " mul, " +
         std::to_string(c.divs) + " div, " + std::to_string(c.calls) + " call)";
}

std::string ops_comment(const FunctionStats& s) {
  return "Ops: " + counts_text(s.naive) + " without CSE, " + counts_text(s.cse) + " with CSE.";
}

// The arguments of derivatives(), gain() and predicted_observation() and their temporaries,
// named clear of the model's names (cpp_names.hpp). The time argument has the model's name.
struct FunctionNames {
  std::string time, state, delayed, params, out, K, h, shared, temporary_prefix;
};

FunctionNames function_names(const Model& model) {
  CppNames names(filter_input_names(model));
  FunctionNames f;
  f.time = model.time.get_name();
  f.state = names.take("state");
  f.params = names.take("params");
  f.out = names.take("out");
  f.K = names.take("K");
  f.h = names.take("h");
  // Taken last, so that the names above are spelled as before for every model.
  f.delayed = names.take("delayed");
  f.shared = names.take("shared");  // the local array of a function written in parts (chunked_body.cpp)
  f.temporary_prefix = names.temporary_prefix();
  return f;
}

// Where each filter variable is read from: array[index], named as the equations name it. An
// undelayed filter reads its count() variables from the state; a delayed one also reads x* from
// the state (after m and P) and m(t - h), Phi* from the `delayed` argument (docs/theory.md §2.6).
struct InputLayout {
  std::vector<std::string> names, arrays;
  std::vector<std::size_t> indices;
  std::vector<std::string> array_arguments;  // the functions' array arguments, in signature order
};

InputLayout input_layout(const FilterVariables& vars, const FunctionNames& names) {
  InputLayout layout;
  layout.array_arguments = {names.state};
  const std::size_t count = vars.count(), n = vars.n();
  auto add = [&](std::uint32_t v, const std::string& array, std::size_t index) {
    layout.names.push_back(vars.text_name(v));
    layout.arrays.push_back(array);
    layout.indices.push_back(index);
  };
  for (std::size_t v = 0; v < count; ++v) add(static_cast<std::uint32_t>(v), names.state, v);
  if (!vars.delayed()) return layout;
  layout.array_arguments.push_back(names.delayed);
  for (std::size_t i = 0; i < n; ++i) add(vars.m_delayed(i), names.delayed, i);
  for (std::size_t i = 0; i < n; ++i) add(vars.phi(i), names.delayed, n + i);
  for (std::size_t i = 0; i < n; ++i) add(vars.x_star(i), names.state, count + i);
  return layout;
}

GraphBuilder graph_builder(ExpressionGraph& graph, const Model& model, const InputLayout& layout,
                           const FunctionNames& names) {
  return GraphBuilder(graph, model, layout.names, layout.arrays, layout.indices, names.params);
}

// The top of a function's body: `(void)` for each argument its outputs do not read (the
// functions share one signature, and -Wunused-parameter must stay quiet), then each input it
// reads, named once.
std::string prologue(const ExpressionGraph& graph, const GraphBuilder& builder, const std::vector<std::size_t>& roots,
                     const FunctionNames& names, const InputLayout& layout, const CppEmitter& emitter) {
  const InputUse use = builder.uses(roots);
  std::string text;
  if (!use.time) text += "  (void)" + names.time + ";\n";
  for (const std::string& array : layout.array_arguments)
    if (!use.arrays.count(array)) text += "  (void)" + array + ";\n";
  if (!use.parameters) text += "  (void)" + names.params + ";\n";
  return text + emitter.input_declarations(graph, roots, builder.declaration_order());
}

// One generated function: its statistics and its body.
struct FunctionCode {
  FunctionStats stats;
  std::string body;
};

FunctionCode function_code(const std::string& function, const std::vector<Polynomial>& outputs,
                           const std::string& target, const Model& model, const FilterEquations& eq,
                           const CodegenOptions& options, const FunctionNames& names) {
  ExpressionGraph graph;
  const InputLayout layout = input_layout(eq.variables, names);
  GraphBuilder builder = graph_builder(graph, model, layout, names);
  builder.define(eq.definitions, eq.variables.symbols());
  std::vector<std::size_t> roots;
  for (const auto& p : outputs) roots.push_back(builder.polynomial(p));
  CppEmitter emitter(options.scalar, names.temporary_prefix);
  emitter.split_above(options.max_function_ops, names.shared);
  FunctionCode code;
  code.stats = FunctionStats{function, graph.tree_counts(roots), graph.shared_counts(roots)};
  code.body = prologue(graph, builder, roots, names, layout, emitter) +
              (options.eliminate_common_subexpressions ? emitter.shared_body(graph, roots, target)
                                                       : emitter.tree_body(graph, roots, target));
  return code;
}

// derivatives() may also be built from the derivation's structure: the P
// moment terms are sum_k P_ik J_jk + J_ik P_kj, so each entry of J (E[d_k f_j]
// or its EKF stand-in) is computed once and shared by every P equation,
// instead of being expanded into each. The naive count stays that of the
// expanded equations; the emitted graph is whichever of the two forms needs
// fewer operations after sharing. A user filter has no Jacobian term (its P
// drift is given whole), so it always takes the expanded form. The structured
// form also writes the correction P A^T R^-1 A P as K (A P), K the gain, where
// correction_factor() has checked that this is the same polynomial.
FunctionCode derivatives_code(const Model& model, const FilterEquations& eq, const CodegenOptions& options,
                              const FunctionNames& names) {
  const FilterVariables& vars = eq.variables;
  const std::size_t n = eq.n();
  std::vector<Polynomial> expanded = eq.m_drift;
  for (std::size_t i = 0; i < n; ++i)
    for (std::size_t j = i; j < n; ++j) expanded.push_back(eq.P_drift(i, j));
  // A delayed filter with Phi* integrates x* beside m and P: its drift follows them in `out`.
  expanded.insert(expanded.end(), eq.x_star_drift.begin(), eq.x_star_drift.end());
  FunctionCode flat = function_code("derivatives", expanded, names.out, model, eq, options, names);
  if (!options.eliminate_common_subexpressions || eq.jacobian_term.empty()) return flat;

  ExpressionGraph graph;
  const InputLayout layout = input_layout(vars, names);
  GraphBuilder builder = graph_builder(graph, model, layout, names);
  builder.define(eq.definitions, eq.variables.symbols());
  std::vector<std::size_t> roots;
  for (const auto& p : eq.m_drift) roots.push_back(builder.polynomial(p));
  std::vector<std::vector<std::size_t>> J(n, std::vector<std::size_t>(n));
  for (std::size_t j = 0; j < n; ++j)
    for (std::size_t k = 0; k < n; ++k)
      if (!eq.jacobian_term[j][k].is_zero()) J[j][k] = builder.polynomial(eq.jacobian_term[j][k]);
  // The correction's factors: K (n x p) and H = A P (p x n), each entry built once.
  const auto H = correction_factor(eq);
  std::vector<std::vector<std::size_t>> K_node, H_node;
  if (H) {
    K_node.assign(n, std::vector<std::size_t>(eq.p));
    H_node.assign(eq.p, std::vector<std::size_t>(n));
    for (std::size_t i = 0; i < n; ++i)
      for (std::size_t r = 0; r < eq.p; ++r)
        if (!eq.gain[i][r].is_zero()) K_node[i][r] = builder.polynomial(eq.gain[i][r]);
    for (std::size_t r = 0; r < eq.p; ++r)
      for (std::size_t j = 0; j < n; ++j)
        if (!(*H)[r][j].is_zero()) H_node[r][j] = builder.polynomial((*H)[r][j]);
  }
  for (std::size_t i = 0; i < n; ++i)
    for (std::size_t j = i; j < n; ++j) {
      const std::size_t u = vars.upper_index(i, j);
      std::vector<std::size_t> terms;
      for (std::size_t k = 0; k < n; ++k) {
        if (!eq.jacobian_term[j][k].is_zero()) terms.push_back(graph.mul(builder.variable(vars.P(i, k)), J[j][k]));
        if (!eq.jacobian_term[i][k].is_zero()) terms.push_back(graph.mul(J[i][k], builder.variable(vars.P(k, j))));
      }
      if (!eq.P_diffusion[u].is_zero()) terms.push_back(builder.polynomial(eq.P_diffusion[u]));
      std::size_t sum = terms.empty() ? graph.constant(0) : terms[0];
      for (std::size_t k = 1; k < terms.size(); ++k) sum = graph.add(sum, terms[k]);
      if (eq.P_correction[u].is_zero()) {
      } else if (H) {
        std::vector<std::size_t> products;
        for (std::size_t r = 0; r < eq.p; ++r)
          if (!eq.gain[i][r].is_zero() && !(*H)[r][j].is_zero()) products.push_back(graph.mul(K_node[i][r], H_node[r][j]));
        std::size_t correction = products[0];  // not empty: the correction is not zero
        for (std::size_t k = 1; k < products.size(); ++k) correction = graph.add(correction, products[k]);
        sum = graph.sub(sum, correction);
      } else {
        sum = graph.sub(sum, builder.polynomial(eq.P_correction[u]));
      }
      roots.push_back(sum);
    }
  for (const auto& p : eq.x_star_drift) roots.push_back(builder.polynomial(p));
  OpCounts structured = graph.shared_counts(roots);
  if (structured.total() >= flat.stats.cse.total()) return flat;
  FunctionCode code;
  code.stats = FunctionStats{"derivatives", flat.stats.naive, structured};
  CppEmitter emitter(options.scalar, names.temporary_prefix);
  emitter.split_above(options.max_function_ops, names.shared);
  code.body = prologue(graph, builder, roots, names, layout, emitter) + emitter.shared_body(graph, roots, names.out);
  return code;
}

// m0 and P0; with `x_star`, x*(0) = m0 after them (a delayed filter's noise-free solution).
std::string initial_body(const Model& model, const FilterVariables& vars, const CppEmitter& emitter,
                         bool x_star = false) {
  std::vector<GiNaC::numeric> values(vars.count() + (x_star ? vars.n() : 0), 0);
  if (model.initial) {
    for (std::size_t i = 0; i < vars.n(); ++i) {
      values[vars.m(i)] = model.initial->m0[i];
      for (std::size_t j = i; j < vars.n(); ++j) values[vars.P(i, j)] = model.initial->P0[i][j];
      if (x_star) values[vars.count() + i] = model.initial->m0[i];
    }
  }
  std::string body;
  for (std::size_t v = 0; v < values.size(); ++v)
    body += "  state[" + std::to_string(v) + "] = " + emitter.literal(values[v]) + ";\n";
  return body;
}

std::string eigen_banner(const Model& model, const FilterEquations& eq, const CodegenOptions& options) {
  return "// Generated by pfgen " PFGEN_VERSION " from model `" + model.name + "`, filter `" + eq.name +
         "`: Eigen wrappers. Do not edit: regenerate with `pfgen codegen --eigen`.\n// Scalar: " +
         scalar_mode_name(options.scalar) + ".";
}

// The banner of a filter header: where it came from, whether its equations are the model's own,
// the scalar, CSE, and the operation counts; `extra` lines (ending in a newline) after the first.
std::string ops_banner(const Model& model, const FilterEquations& eq, const CodegenOptions& options,
                       const GeneratedFilter& result, const std::string& extra = "") {
  return "// Generated by pfgen " PFGEN_VERSION " from model `" + model.name + "`, filter `" + eq.name +
         "`. Do not edit: regenerate with `pfgen codegen`.\n" + extra +
         (eq.is_user_filter() ? "// The filter's equations are given in the model file (`filters:`), not derived by pfgen.\n"
                              : "") +
         "// Scalar: " + scalar_mode_name(options.scalar) + ". Common-subexpression elimination: " +
         (options.eliminate_common_subexpressions ? "on" : "off") + ".\n" +
         "// Ops before CSE: " + counts_text(result.naive_total()) + ".\n" +
         "// Ops after CSE:  " + counts_text(result.cse_total()) + ".";
}

// The members of Params<Scalar>: each parameter with its model-file default.
std::string params_members(const Model& model, const CppEmitter& emitter) {
  std::string params;
  for (const auto& p : model.parameters) params += "  Scalar " + p.name + " = " + emitter.literal(p.default_value) + ";\n";
  return params;
}

// derivatives(), gain() and predicted_observation() of a filter with continuous (or delayed)
// observations, and the names they were written with.
struct ContinuousFunctions {
  FunctionNames names;
  FunctionCode derivatives, gain, observation;
};

ContinuousFunctions continuous_functions(const Model& model, const FilterEquations& eq, const CodegenOptions& options) {
  std::vector<Polynomial> gain_outputs;
  for (const auto& row : eq.gain) gain_outputs.insert(gain_outputs.end(), row.begin(), row.end());
  ContinuousFunctions f;
  f.names = function_names(model);
  f.derivatives = derivatives_code(model, eq, options, f.names);
  f.gain = function_code("gain", gain_outputs, f.names.K, model, eq, options, f.names);
  f.observation =
      function_code("predicted_observation", eq.predicted_observation, f.names.h, model, eq, options, f.names);
  return f;
}

// A filter for sampled observations (templates/cpp/sampled_filter.hpp.tmpl): the prediction's
// derivatives (and cd-euler's dt^2 term), the update's polynomial parts P C^T and S, C and R, the
// predicted sample, and the unrolled Cholesky solve of the gain.
// The placeholders every filter template has (filter.hpp, sampled_filter.hpp, delayed_filter.hpp):
// the namespace, the dimensions, the scalar, the parameters and the names of the functions'
// arguments. Each kind adds its own to these.
std::map<std::string, std::string> common_template_values(const Model& model, const std::string& identifier,
                                                          const CodegenOptions& options, std::size_t n,
                                                          std::size_t p, std::size_t state_size,
                                                          const FunctionNames& names, const CppEmitter& emitter) {
  const bool templated = options.scalar == ScalarMode::Template;
  return {
      {"namespace", options.name_space + "::" + model.name + "::" + identifier},
      {"n", std::to_string(n)},
      {"p", std::to_string(p)},
      {"state_size", std::to_string(state_size)},
      {"scalar_alias", templated ? "" : "\nusing Scalar = " + scalar_mode_name(options.scalar) + ";\n"},
      {"template_prefix", templated ? "template <class Scalar>\n" : ""},
      {"params_members", params_members(model, emitter)},
      {"t", names.time},
      {"state", names.state},
      {"params", names.params},
      {"out", names.out},
  };
}

GeneratedFilter generate_sampled_code(const Model& model, const FilterEquations& eq, const CodegenOptions& options) {
  const FilterVariables& vars = eq.variables;
  const std::size_t n = eq.n();
  const SampledUpdate& u = eq.update;
  const std::size_t r = u.r();
  if (r > kMaxSampledOutputs)
    throw CodegenError("filter '" + eq.name + "' of model " + model.name + " samples " + std::to_string(r) +
                       " outputs; its generated update writes the Cholesky solve out for every output (O(r^3) "
                       "code: 1.2 MB of C++ at r = 64, 27 MB at r = 200, which a compiler takes minutes over), so "
                       "code generation takes at most " + std::to_string(kMaxSampledOutputs) +
                       " outputs; derive and eval take any");
  const FunctionNames names = function_names(model);
  FunctionCode derivatives = derivatives_code(model, eq, options, names);
  const bool euler = !eq.P_euler.empty();
  FunctionCode square;
  if (euler) square = function_code("euler_square", eq.P_euler, names.out, model, eq, options, names);
  std::vector<Polynomial> innovation;
  for (const auto& row : u.PCt) innovation.insert(innovation.end(), row.begin(), row.end());
  innovation.insert(innovation.end(), u.S.begin(), u.S.end());
  FunctionCode innovation_code = function_code("innovation_terms", innovation, names.out, model, eq, options, names);
  std::vector<Polynomial> matrices;
  for (const auto& row : u.C) matrices.insert(matrices.end(), row.begin(), row.end());
  matrices.insert(matrices.end(), u.R.begin(), u.R.end());
  FunctionCode matrices_code = function_code("observation_matrices", matrices, names.out, model, eq, options, names);
  FunctionCode observation =
      function_code("predicted_observation", eq.predicted_observation, names.h, model, eq, options, names);

  const std::string identifier = filter_identifier(eq.name);
  GeneratedFilter result;
  result.name = eq.name;
  const FilterHeaderPaths paths = filter_header_paths(model.name, eq.name);
  result.relative_path = paths.header;
  result.functions = {derivatives.stats};
  if (euler) result.functions.push_back(square.stats);
  result.functions.push_back(innovation_code.stats);
  result.functions.push_back(matrices_code.stats);
  result.functions.push_back(observation.stats);

  CppEmitter emitter(options.scalar);
  const bool templated = options.scalar == ScalarMode::Template;
  // A sampled model has no filters of its own (the validator refuses them): no user-filter line.
  std::map<std::string, std::string> values =
      common_template_values(model, identifier, options, n, r, vars.count(), names, emitter);
  const std::string& prefix = values.at("template_prefix");
  // cd-euler's Cov(f) dt^2 term and the prediction sub-step: the C++ of each in its own partial
  // (templates/cpp/partials/), filled here.
  std::string euler_function;
  if (euler)
    euler_function = fill_template("cpp/partials/euler_square.hpp.tmpl",
                                   embedded_template("cpp/partials/euler_square.hpp.tmpl"),
                                   {{"euler_ops", ops_comment(square.stats)},
                                    {"template_prefix", prefix},
                                    {"t", names.time},
                                    {"state", names.state},
                                    {"params", names.params},
                                    {"out", names.out},
                                    {"euler_body", square.body}});
  const std::string predict_partial = euler ? "cpp/partials/predict_euler.hpp.tmpl" : "cpp/partials/predict_heun.hpp.tmpl";
  std::string predict_function =
      fill_template(predict_partial, embedded_template(predict_partial), {{"template_prefix", prefix}});
  predict_function.pop_back();  // its last newline: the template's line after {{predict_function}} ends it

  values.insert({
      {"banner", ops_banner(model, eq, options, result)},
      {"substeps", std::to_string(u.substeps)},
      {"period", emitter.literal(u.period)},
      {"period_call", templated ? "<Scalar>" : ""},
      {"h", names.h},
      {"derivatives_ops", ops_comment(derivatives.stats)},
      {"derivatives_body", derivatives.body},
      {"euler_function", euler_function},
      {"innovation_ops", ops_comment(innovation_code.stats)},
      {"innovation_body", innovation_code.body},
      {"matrices_ops", ops_comment(matrices_code.stats)},
      {"matrices_body", matrices_code.body},
      {"observation_ops", ops_comment(observation.stats)},
      {"observation_body", observation.body},
      {"initial_body", initial_body(model, vars, emitter)},
      {"solve_body", cholesky_gain_body(r)},
      {"predict_function", predict_function},
  });
  result.contents =
      fill_template("cpp/sampled_filter.hpp.tmpl", embedded_template("cpp/sampled_filter.hpp.tmpl"), values);
  if (options.eigen_wrapper) {
    std::map<std::string, std::string> eigen_values = {
        {"banner", eigen_banner(model, eq, options)},
        {"namespace", values.at("namespace")},
        {"kind_header", identifier + ".hpp"},
        {"template_prefix", prefix},
    };
    result.eigen_relative_path = paths.eigen_header;
    result.eigen_contents = fill_template("cpp/sampled_filter_eigen.hpp.tmpl",
                                          embedded_template("cpp/sampled_filter_eigen.hpp.tmpl"), eigen_values);
  }
  return result;
}

// A filter for delayed observations (templates/cpp/delayed_filter.hpp.tmpl; docs/theory.md §2.6):
// the functions read m(t - h) and Phi* from a second array, x* follows m and P in the state, and
// the step keeps the history on the fixed grid the filter is generated for.
GeneratedFilter generate_delayed_code(const Model& model, const FilterEquations& eq, const CodegenOptions& options) {
  // No Eigen wrapper (options.eigen_wrapper is ignored): the state carries x* and the filter keeps
  // a history, so the header's Filter is the interface.
  if (!options.grid_step)
    throw CodegenError("filter '" + eq.name + "': a filter for delayed observations steps on a fixed grid: give --dt "
                       "(or simulation: dt in the model file)");
  const DelaySteps steps = delay_steps(eq.delay, *options.grid_step);
  if (!steps.problem.empty()) throw CodegenError("filter '" + eq.name + "': " + steps.problem);
  const FilterVariables& vars = eq.variables;
  const std::size_t n = eq.n();
  const bool x_star = eq.uses_x_star();
  const ContinuousFunctions functions = continuous_functions(model, eq, options);
  const FunctionNames& names = functions.names;

  const std::string identifier = filter_identifier(eq.name);
  GeneratedFilter result;
  result.name = eq.name;
  const FilterHeaderPaths paths = filter_header_paths(model.name, eq.name);
  result.relative_path = paths.header;
  result.functions = {functions.derivatives.stats, functions.gain.stats, functions.observation.stats};

  CppEmitter emitter(options.scalar);
  const bool templated = options.scalar == ScalarMode::Template;
  const std::string h = pfgen_support::shortest_double(eq.delay.to_double());
  const std::string dt = pfgen_support::shortest_double(*options.grid_step);
  const std::string extra = "// Delayed observations: h = " + h + " = " + std::to_string(steps.steps) +
                            " steps of dt = " + dt + "; the caller supplies dy over each step of this dt.\n";
  // h and dt as literals of the scalar type (float code has no double in it).
  auto real_literal = [&](double value) { return emitter.literal(GiNaC::numeric(value)); };
  std::string gain_meaning = "P A^T (B B^T)^-1";
  if (eq.is_user_filter()) gain_meaning = "as given in the model file";
  else if (x_star) gain_meaning = "P Phi*^T A^T (B B^T)^-1, Phi* = diag(phi)";
  std::map<std::string, std::string> values =
      common_template_values(model, identifier, options, n, eq.p, vars.count() + (x_star ? n : 0), names, emitter);
  values.insert({
      {"banner", ops_banner(model, eq, options, result, extra)},
      {"scalar_call", templated ? "<Scalar>" : ""},
      {"delay", real_literal(eq.delay.to_double())},
      {"dt", real_literal(*options.grid_step)},
      {"delay_steps", std::to_string(steps.steps)},
      {"uses_x_star", x_star ? "true" : "false"},
      {"history_what", x_star ? " and x*" : ""},
      {"prehistory_x_star", x_star ? " and x*(s) = m0" : ""},
      {"state_x_star",
       x_star ? "\n// then x* (n entries), the noise-free solution dx*/dt = f(x*, t) from x*(0) = m0." : ""},
      {"out_x_star", x_star ? ", x* drift f(x*, t)" : ""},
      {"initial_x_star", x_star ? ", and x*(0) = m0" : ""},
      {"delayed", names.delayed},
      {"K", names.K},
      {"h", names.h},
      {"derivatives_ops", ops_comment(functions.derivatives.stats)},
      {"derivatives_body", functions.derivatives.body},
      {"gain_meaning", gain_meaning},
      {"gain_ops", ops_comment(functions.gain.stats)},
      {"gain_body", functions.gain.body},
      {"observation_ops", ops_comment(functions.observation.stats)},
      {"observation_body", functions.observation.body},
      {"initial_body", initial_body(model, vars, emitter, x_star)},
  });
  result.contents =
      fill_template("cpp/delayed_filter.hpp.tmpl", embedded_template("cpp/delayed_filter.hpp.tmpl"), values);
  return result;
}

}  // namespace

FilterHeaderPaths filter_header_paths(const std::string& model_name, const std::string& filter_name) {
  const std::string stem = model_name + "/" + filter_identifier(filter_name);
  return {stem + ".hpp", stem + "_eigen.hpp"};
}

OpCounts GeneratedFilter::naive_total() const {
  OpCounts total;
  for (const auto& f : functions) total += f.naive;
  return total;
}

OpCounts GeneratedFilter::cse_total() const {
  OpCounts total;
  for (const auto& f : functions) total += f.cse;
  return total;
}

double codegen_terms(const FilterEquations& eq) {
  double terms = 0;
  auto add = [&terms](const std::vector<Polynomial>& polynomials) {
    for (const Polynomial& p : polynomials) terms += static_cast<double>(p.terms().size());
  };
  add(eq.m_drift);
  for (const auto& row : eq.gain) add(row);
  add(eq.predicted_observation);
  for (const auto& row : eq.jacobian_term) add(row);
  add(eq.P_moment);
  add(eq.P_diffusion);
  add(eq.P_correction);
  add(eq.P_euler);
  add(eq.x_star_drift);
  return terms;
}

GeneratedFilter generate_filter_code(const Model& model, const FilterEquations& eq, const CodegenOptions& options) {
  if (const double terms = codegen_terms(eq); terms > kMaxCodegenTerms) {
    char text[400];
    std::snprintf(text, sizeof text,
                  "filter '%s' of model %s has %.0f terms in its equations; code generation holds at most %.0f "
                  "(about 1.1 kB each while it builds the code: this would need about %.1f GB); derive and eval "
                  "handle it, and a model with fewer states or a lower degree generates",
                  eq.name.c_str(), model.name.c_str(), terms, kMaxCodegenTerms, terms * 1.1e3 / 1e9);
    throw CodegenError(text);
  }
  if (eq.is_sampled()) return generate_sampled_code(model, eq, options);
  if (eq.is_delayed()) return generate_delayed_code(model, eq, options);
  const FilterVariables& vars = eq.variables;
  const std::size_t n = eq.n();
  const ContinuousFunctions functions = continuous_functions(model, eq, options);
  const FunctionNames& names = functions.names;

  const std::string identifier = filter_identifier(eq.name);
  GeneratedFilter result;
  result.name = eq.name;
  const FilterHeaderPaths paths = filter_header_paths(model.name, eq.name);
  result.relative_path = paths.header;
  result.functions = {functions.derivatives.stats, functions.gain.stats, functions.observation.stats};

  CppEmitter emitter(options.scalar);
  std::map<std::string, std::string> values =
      common_template_values(model, identifier, options, n, eq.p, vars.count(), names, emitter);
  values.insert({
      {"banner", ops_banner(model, eq, options, result)},
      {"K", names.K},
      {"h", names.h},
      {"derivatives_ops", ops_comment(functions.derivatives.stats)},
      {"derivatives_body", functions.derivatives.body},
      {"gain_meaning", eq.is_user_filter() ? "as given in the model file" : "P A^T (B B^T)^-1"},
      {"gain_ops", ops_comment(functions.gain.stats)},
      {"gain_body", functions.gain.body},
      {"observation_ops", ops_comment(functions.observation.stats)},
      {"observation_body", functions.observation.body},
      {"initial_body", initial_body(model, vars, emitter)},
  });
  result.contents = fill_template("cpp/filter.hpp.tmpl", embedded_template("cpp/filter.hpp.tmpl"), values);
  if (options.eigen_wrapper) {
    const std::string kind_header = identifier + ".hpp";
    std::map<std::string, std::string> eigen_values = {
        {"banner", eigen_banner(model, eq, options)},
        {"namespace", values.at("namespace")},
        {"kind_header", kind_header},
        {"template_prefix", values.at("template_prefix")},
    };
    result.eigen_relative_path = paths.eigen_header;
    result.eigen_contents =
        fill_template("cpp/filter_eigen.hpp.tmpl", embedded_template("cpp/filter_eigen.hpp.tmpl"), eigen_values);
  }
  return result;
}

}  // namespace pfgen::codegen
