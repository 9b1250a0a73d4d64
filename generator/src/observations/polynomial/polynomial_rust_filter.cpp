// A filter for a polynomial observation in Rust (templates/rust/polynomial_filter.rs.tmpl; a linear h
// is the continuous filter), written with the Rust backend's writer from this module's functions.
#include "pfgen/codegen/backends/rust/rust_filter_writer.hpp"
#include "pfgen/observations/polynomial/polynomial_code.hpp"

namespace pfgen::codegen {

GeneratedFilter PolynomialCode::rust_filter(const Model& model, const FilterEquations& eq,
                                            const CodegenOptions& options) const {
  if (written_linear(model)) return continuous_observation_code().rust_filter(model, eq, options);
  RustFilterWriter w(model, eq, options);
  const PolynomialFunctions f = polynomial_functions(model, eq, options, w.names, w.emitter);
  w.result.functions = f.stats();
  std::map<std::string, std::string> values = w.common_values(eq.p, eq.variables.count());
  RustFilterWriter::add_function(values, "derivatives", f.derivatives);
  RustFilterWriter::add_function(values, "gain", f.gain);
  RustFilterWriter::add_function(values, "covariance_gain", f.covariance_gain);
  RustFilterWriter::add_function(values, "observation", f.observation);
  RustFilterWriter::add_function(values, "correction", f.correction);
  values.insert({{"K", w.names.K}, {"L", w.names.L}, {"h", w.names.h}, {"c", w.names.c}});
  values.emplace("initial_body", w.body(initial_state_statements(initial_values(model, eq.variables))));
  w.write("polynomial_filter", values);
  return w.result;
}

}  // namespace pfgen::codegen
