// A filter for continuous observations in C99 (its templates/c/filter.h.tmpl and filter.c.tmpl).
#include "pfgen/codegen/backends/c/c_filter_writer.hpp"
#include "pfgen/observations/continuous/continuous_code.hpp"
#include "pfgen/observations/continuous/heun_step.hpp"

namespace pfgen::codegen {

GeneratedFilter ContinuousCode::c_filter(const Model& model, const FilterEquations& eq,
                                         const CodegenOptions& options) const {
  CFilterWriter w(model, eq, options);
  const ContinuousFunctions f = continuous_functions(model, eq, options, w.names, w.emitter, true);
  w.result.functions = f.stats();
  std::map<std::string, std::string> values = w.common_values(eq.p, eq.variables.count());
  add_rate_function_values(values, f, w.names, eq, true);
  add_heun_step_loops(values, w.emitter,
                      {ir::name(w.prefix + "_n"), ir::name(w.prefix + "_p"), ir::name(w.prefix + "_state_size"),
                       ir::number(2)},
                      eq.n(), eq.p, eq.variables.count());
  values.emplace("initial_body", w.emitter.block(initial_state_statements(initial_values(model, eq.variables))));
  w.write("filter", values, {}, {});
  return w.result;
}

std::vector<std::string> ContinuousCode::c_templates() const {
  return {"c/filter.h.tmpl", "c/filter.c.tmpl"};
}

}  // namespace pfgen::codegen
