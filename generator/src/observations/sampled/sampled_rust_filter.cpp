// A filter for sampled observations in Rust (templates/rust/sampled_filter.rs.tmpl, with the
// partials of cd-euler's dt^2 term and of the prediction sub-step).
#include "pfgen/codegen/backends/rust/rust_filter_writer.hpp"
#include "pfgen/codegen/template_text.hpp"
#include "pfgen/observations/sampled/cholesky_solve.hpp"
#include "pfgen/observations/sampled/sampled_code.hpp"
#include "pfgen/observations/sampled/sampled_predict.hpp"

namespace pfgen::codegen {
namespace {

std::string filled_partial(const std::string& name, const std::map<std::string, std::string>& values) {
  return fill_template(name, embedded_template(name), values_in_template(name, values));
}

}  // namespace

GeneratedFilter SampledCode::rust_filter(const Model& model, const FilterEquations& eq,
                                              const CodegenOptions& options) const {
  RustFilterWriter w(model, eq, options);
  const SampledFunctions f = sampled_functions(model, eq, options, w.names, w.emitter);
  const bool euler = f.euler_square.has_value();
  w.result.functions = f.stats();
  const std::size_t r = eq.update.r();
  std::map<std::string, std::string> values = w.common_values(r, eq.variables.count());
  RustFilterWriter::add_function(values, "derivatives", f.derivatives);
  RustFilterWriter::add_function(values, "innovation", f.innovation);
  RustFilterWriter::add_function(values, "matrices", f.matrices);
  RustFilterWriter::add_function(values, "observation", f.observation);
  values.insert({{"h", w.names.h}, {"substeps", std::to_string(eq.update.substeps)}});
  add_sample_meanings(values, eq.update);
  std::string euler_function;
  if (euler) {
    std::map<std::string, std::string> euler_values = values;
    RustFilterWriter::add_function(euler_values, "euler", *f.euler_square);
    euler_function = filled_partial("rust/partials/euler_square.rs.tmpl", euler_values);
  }
  const std::string predict = euler ? "rust/partials/predict_euler.rs.tmpl" : "rust/partials/predict_heun.rs.tmpl";
  values["predict_body"] = w.body(predict_statements(
      euler, {ir::name("STATES"), ir::name("STATE_SIZE"), ir::number(2), "derivatives", "euler_square"}));
  values.insert({{"period", w.emitter.literal_text(eq.update.period)},
                 {"euler_function", euler_function},
                 {"predict_function", filled_partial(predict, values)},
                 {"initial_body", w.body(initial_state_statements(initial_values(model, eq.variables)))},
                 {"solve_body", w.body(cholesky_gain_statements(
                                    r, {ir::name("STATES"), ir::name("OBSERVATIONS"), ir::number(0)}))},
                 {"one", w.emitter.literal_text(1)}});
  w.write("sampled_filter", values);
  return w.result;
}

}  // namespace pfgen::codegen
