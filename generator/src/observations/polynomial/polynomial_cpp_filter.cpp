// A filter for a polynomial observation in C++ (its templates/cpp/polynomial_filter.hpp.tmpl, and
// with --eigen polynomial_filter_eigen.hpp.tmpl): derivatives(), gain(), covariance_gain(),
// predicted_observation(), stratonovich_correction(), initial_state(), step().
#include "pfgen/codegen/backends/c_family/file_banner.hpp"
#include "pfgen/codegen/backends/cpp/cpp_filter_parts.hpp"
#include "pfgen/codegen/template_text.hpp"
#include "pfgen/observations/polynomial/polynomial_code.hpp"

namespace pfgen::codegen {

GeneratedFilter PolynomialCode::cpp_filter(const Model& model, const FilterEquations& eq,
                                           const CodegenOptions& options) const {
  if (written_linear(model)) return continuous_observation_code().cpp_filter(model, eq, options);
  const FunctionNames names = function_names(model);
  CppEmitter emitter(options.scalar, names.temporary_prefix);
  emitter.split_above(options.max_function_ops, names.shared);
  const PolynomialFunctions functions = polynomial_functions(model, eq, options, names, emitter);

  GeneratedFilter result = cpp_filter_result(model, eq, options);
  result.functions = functions.stats();
  std::map<std::string, std::string> values = cpp_template_values(model, filter_identifier(eq.name), options, eq.n(),
                                                                  eq.p, eq.variables.count(), names, emitter);
  values.insert({
      {"banner", filter_banner(model, eq, options, result, "pfgen codegen")},
      {"initial_body", emitter.block(initial_state_statements(initial_values(model, eq.variables)))},
  });
  add_polynomial_function_values(values, functions, names, false);
  const std::string name = "cpp/polynomial_filter.hpp.tmpl";
  result.files.at(0).contents = fill_template(name, embedded_template(name), values);
  add_eigen_layer(result, "cpp/polynomial_filter_eigen.hpp.tmpl", model, eq, options, values);
  return result;
}

}  // namespace pfgen::codegen
