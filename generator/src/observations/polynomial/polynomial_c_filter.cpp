// A filter for a polynomial observation in C99 (its templates/c/polynomial_filter.h.tmpl and .c.tmpl).
#include "pfgen/codegen/backends/c/c_filter_writer.hpp"
#include "pfgen/observations/polynomial/polynomial_code.hpp"

namespace pfgen::codegen {

GeneratedFilter PolynomialCode::c_filter(const Model& model, const FilterEquations& eq,
                                         const CodegenOptions& options) const {
  if (written_linear(model)) return continuous_observation_code().c_filter(model, eq, options);
  CFilterWriter w(model, eq, options);
  const PolynomialFunctions f = polynomial_functions(model, eq, options, w.names, w.emitter);
  w.result.functions = f.stats();
  std::map<std::string, std::string> values = w.common_values(eq.p, eq.variables.count());
  add_polynomial_function_values(values, f, w.names, true);
  values.emplace("initial_body", w.emitter.block(initial_state_statements(initial_values(model, eq.variables))));
  w.write("polynomial_filter", values, {}, {});
  return w.result;
}

std::vector<std::string> PolynomialCode::c_templates() const {
  // A linear h is written by the continuous module (polynomial_c_filter's delegation).
  std::vector<std::string> names = continuous_observation_code().c_templates();
  names.insert(names.end(), {"c/polynomial_filter.h.tmpl", "c/polynomial_filter.c.tmpl"});
  return names;
}

}  // namespace pfgen::codegen
