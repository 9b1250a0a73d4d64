// A filter for continuous observations in C++ (its templates/cpp/filter.hpp.tmpl, and with --eigen
// filter_eigen.hpp.tmpl): derivatives(), gain(), predicted_observation(), initial_state(), step().
#include "pfgen/codegen/backends/c_family/file_banner.hpp"
#include "pfgen/codegen/backends/cpp/cpp_filter_parts.hpp"
#include "pfgen/codegen/template_text.hpp"
#include "pfgen/observations/continuous/continuous_code.hpp"
#include "pfgen/observations/continuous/heun_step.hpp"

namespace pfgen::codegen {

GeneratedFilter ContinuousCode::cpp_filter(const Model& model, const FilterEquations& eq,
                                           const CodegenOptions& options) const {
  const FilterVariables& vars = eq.variables;
  const FunctionNames names = function_names(model);
  CppEmitter emitter(options.scalar, names.temporary_prefix);
  emitter.split_above(options.max_function_ops, names.shared);
  const ContinuousFunctions functions = continuous_functions(model, eq, options, names, emitter, true);

  GeneratedFilter result = cpp_filter_result(model, eq, options);
  result.functions = functions.stats();

  std::map<std::string, std::string> values = cpp_template_values(model, filter_identifier(eq.name), options, eq.n(),
                                                                  eq.p, vars.count(), names, emitter);
  values.insert({
      {"banner", filter_banner(model, eq, options, result, "pfgen codegen")},
      {"initial_body", emitter.block(initial_state_statements(initial_values(model, vars)))},
  });
  add_rate_function_values(values, functions, names, eq, false);
  add_heun_step_loops(values, emitter, {ir::name("n"), ir::name("p"), ir::name("state_size"), ir::name("Scalar(2)")},
                      eq.n(), eq.p, vars.count());
  result.files.at(0).contents = fill_template("cpp/filter.hpp.tmpl", embedded_template("cpp/filter.hpp.tmpl"), values);
  add_eigen_layer(result, "cpp/filter_eigen.hpp.tmpl", model, eq, options, values);
  return result;
}

}  // namespace pfgen::codegen
