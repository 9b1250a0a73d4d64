// A filter for sampled observations in C++ (its templates/cpp/sampled_filter.hpp.tmpl, and with
// --eigen sampled_filter_eigen.hpp.tmpl): the prediction's derivatives (and cd-euler's dt^2 term),
// the update's polynomial parts P C^T and S, C and R, the predicted sample, and the unrolled
// Cholesky solve of the gain.
#include "pfgen/codegen/backends/c_family/file_banner.hpp"
#include "pfgen/codegen/backends/cpp/cpp_filter_parts.hpp"
#include "pfgen/codegen/template_text.hpp"
#include "pfgen/observations/sampled/cholesky_solve.hpp"
#include "pfgen/observations/sampled/sampled_code.hpp"
#include "pfgen/observations/sampled/sampled_predict.hpp"

namespace pfgen::codegen {

GeneratedFilter SampledCode::cpp_filter(const Model& model, const FilterEquations& eq,
                                        const CodegenOptions& options) const {
  const FilterVariables& vars = eq.variables;
  const std::size_t n = eq.n();
  const SampledUpdate& u = eq.update;
  const std::size_t r = u.r();
  const FunctionNames names = function_names(model);
  CppEmitter emitter(options.scalar, names.temporary_prefix);
  emitter.split_above(options.max_function_ops, names.shared);
  const SampledFunctions functions = sampled_functions(model, eq, options, names, emitter);
  const bool euler = functions.euler_square.has_value();

  GeneratedFilter result = cpp_filter_result(model, eq, options);
  result.functions = functions.stats();

  const bool templated = options.scalar == ScalarMode::Template;
  // A sampled model has no filters of its own (the validator refuses them): no user-filter line.
  std::map<std::string, std::string> values =
      cpp_template_values(model, filter_identifier(eq.name), options, n, r, vars.count(), names, emitter);
  const std::string& prefix = values.at("template_prefix");
  // cd-euler's Cov(f) dt^2 term and the prediction sub-step: the frame of each in its own partial
  // (its templates/cpp/partials/), filled here; the sub-step's body is statements (sampled_predict).
  std::string euler_function;
  if (euler)
    euler_function = fill_template("cpp/partials/euler_square.hpp.tmpl",
                                   embedded_template("cpp/partials/euler_square.hpp.tmpl"),
                                   {{"euler_ops", ops_comment(functions.euler_square->stats)},
                                    {"template_prefix", prefix},
                                    {"t", names.time},
                                    {"state", names.state},
                                    {"params", names.params},
                                    {"out", names.out},
                                    {"euler_body", functions.euler_square->body.statements}});
  const std::string predict_partial = euler ? "cpp/partials/predict_euler.hpp.tmpl" : "cpp/partials/predict_heun.hpp.tmpl";
  const ir::Block predict = predict_statements(
      euler, {ir::name("n"), ir::name("state_size"), ir::name("Scalar(2)"), "derivatives", "euler_square"});
  std::string predict_function = fill_template(predict_partial, embedded_template(predict_partial),
                                               {{"template_prefix", prefix}, {"predict_body", emitter.block(predict)}});
  predict_function.pop_back();  // its last newline: the template's line after {{predict_function}} ends it

  values.insert({
      {"banner", filter_banner(model, eq, options, result, "pfgen codegen")},
      {"substeps", std::to_string(u.substeps)},
      {"period", emitter.literal(u.period)},
      {"period_call", templated ? "<Scalar>" : ""},
      {"h", names.h},
      {"derivatives_ops", ops_comment(functions.derivatives.stats)},
      {"derivatives_body", functions.derivatives.body.statements},
      {"euler_function", euler_function},
      {"innovation_ops", ops_comment(functions.innovation.stats)},
      {"innovation_body", functions.innovation.body.statements},
      {"matrices_ops", ops_comment(functions.matrices.stats)},
      {"matrices_body", functions.matrices.body.statements},
      {"observation_ops", ops_comment(functions.observation.stats)},
      {"observation_body", functions.observation.body.statements},
      {"initial_body", emitter.block(initial_state_statements(initial_values(model, vars)))},
      {"solve_body", emitter.block(cholesky_gain_statements(r, {ir::name("n"), ir::name("p"), ir::name("Scalar(0)")}))},
      {"predict_function", predict_function},
  });
  add_sample_meanings(values, u);
  result.files.at(0).contents =
      fill_template("cpp/sampled_filter.hpp.tmpl", embedded_template("cpp/sampled_filter.hpp.tmpl"), values);
  add_eigen_layer(result, "cpp/sampled_filter_eigen.hpp.tmpl", model, eq, options, values);
  return result;
}

}  // namespace pfgen::codegen
