// A filter for sampled observations in C99 (its templates/c/sampled_filter.h.tmpl and .c.tmpl, with
// the partials of cd-euler's dt^2 term and of the prediction sub-step).
#include "pfgen/codegen/backends/c/c_filter_writer.hpp"
#include "pfgen/codegen/template_text.hpp"
#include "pfgen/observations/sampled/cholesky_solve.hpp"
#include "pfgen/observations/sampled/sampled_code.hpp"
#include "pfgen/observations/sampled/sampled_predict.hpp"

namespace pfgen::codegen {

GeneratedFilter SampledCode::c_filter(const Model& model, const FilterEquations& eq,
                                      const CodegenOptions& options) const {
  CFilterWriter w(model, eq, options);
  const SampledFunctions f = sampled_functions(model, eq, options, w.names, w.emitter);
  const bool euler = f.euler_square.has_value();
  w.result.functions = f.stats();
  const std::size_t r = eq.update.r();
  std::map<std::string, std::string> values = w.common_values(r, eq.variables.count());
  CFilterWriter::add_function(values, "derivatives", f.derivatives);
  CFilterWriter::add_function(values, "innovation", f.innovation);
  CFilterWriter::add_function(values, "matrices", f.matrices);
  CFilterWriter::add_function(values, "observation", f.observation);
  values.insert({{"h", w.names.h}, {"substeps", std::to_string(eq.update.substeps)}});
  add_sample_meanings(values, eq.update);
  // cd-euler's Cov(f) dt^2 function and the prediction sub-step, each a partial (its templates/c/partials/);
  // the sub-step's body is statements (sampled_predict).
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
  const ir::Expr n = ir::name(w.prefix + "_n"), state_size = ir::name(w.prefix + "_state_size");
  const ir::Block predict =
      predict_statements(euler, {n, state_size, ir::number(2), w.prefix + "_derivatives", w.prefix + "_euler_square"});
  std::string predict_function =
      fill_template(predict_partial, embedded_template(predict_partial),
                    {{"prefix", w.prefix}, {"scalar", w.emitter.scalar_type()}, {"predict_body", w.emitter.block(predict)}});
  predict_function.pop_back();  // its last newline: the template's line after {{predict_function}} ends it
  w.write("sampled_filter", values,
          {{"euler_declaration", euler_declaration},
           {"predict_meaning", euler ? "cd-euler's exact moments of one Euler step." : "Heun's scheme on the prediction ODEs."}},
          {{"period", w.emitter.literal(eq.update.period)},
           {"euler_function", euler_function},
           {"initial_body", w.emitter.block(initial_state_statements(initial_values(model, eq.variables)))},
           {"solve_body", w.emitter.block(cholesky_gain_statements(
                              r, {ir::name(w.prefix + "_n"), ir::name(w.prefix + "_p"), ir::number(0)}))},
           {"predict_function", predict_function},
           {"one", w.emitter.literal(1)},
           {"zero", w.emitter.literal(0)}});
  return w.result;
}

std::vector<std::string> SampledCode::c_templates() const {
  return {"c/sampled_filter.h.tmpl", "c/sampled_filter.c.tmpl", "c/partials/euler_square.h.tmpl",
          "c/partials/euler_square.c.tmpl", "c/partials/predict_euler.c.tmpl", "c/partials/predict_heun.c.tmpl"};
}

}  // namespace pfgen::codegen
