// A filter for delayed observations in C++ (its templates/cpp/delayed_filter.hpp.tmpl; docs/theory.md
// §2.6): the functions read m(t - h) and Phi* from a second array, x* follows m and P in the state,
// and the step keeps the history on the fixed grid the filter is generated for.
#include "pfgen/codegen/backends/c_family/file_banner.hpp"
#include "pfgen/codegen/backends/cpp/cpp_backend.hpp"
#include "pfgen/codegen/backends/cpp/cpp_filter_parts.hpp"
#include "pfgen/codegen/template_text.hpp"
#include "pfgen/observations/continuous/continuous_code.hpp"
#include "pfgen/observations/delayed/delayed_code.hpp"

namespace pfgen::codegen {

GeneratedFilter DelayedCode::cpp_filter(const Model& model, const FilterEquations& eq,
                                        const CodegenOptions& options) const {
  // No Eigen wrapper (options.eigen_wrapper is ignored): the state carries x* and the filter keeps
  // a history, so the header's Filter is the interface.
  const DelaySteps steps = filter_delay_steps(eq, options);
  const FilterVariables& vars = eq.variables;
  const std::size_t n = eq.n();
  const bool x_star = eq.uses_x_star();
  const FunctionNames names = function_names(model);
  CppEmitter emitter(options.scalar, names.temporary_prefix);
  emitter.split_above(options.max_function_ops, names.shared);
  const ContinuousFunctions functions = continuous_functions(model, eq, options, names, emitter);

  GeneratedFilter result;
  result.name = eq.name;
  result.files.push_back({cpp_filter_paths(model.name, eq.name, false).at(0), ""});
  result.functions = functions.stats();

  const bool templated = options.scalar == ScalarMode::Template;
  const std::string extra = delay_banner_line(eq, steps, *options.grid_step);
  // h and dt as literals of the scalar type (float code has no double in it).
  auto real_literal = [&](double value) { return emitter.literal(GiNaC::numeric(value)); };
  std::map<std::string, std::string> values = cpp_template_values(
      model, filter_identifier(eq.name), options, n, eq.p, vars.count() + (x_star ? n : 0), names, emitter);
  values.insert({
      {"banner", filter_banner(model, eq, options, result, "pfgen codegen", extra)},
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
      {"initial_body", emitter.block(initial_state_statements(initial_values(model, vars, x_star)))},
  });
  add_rate_function_values(values, functions, names, eq, false);
  result.files.at(0).contents =
      fill_template("cpp/delayed_filter.hpp.tmpl", embedded_template("cpp/delayed_filter.hpp.tmpl"), values);
  return result;
}

}  // namespace pfgen::codegen
