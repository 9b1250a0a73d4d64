// A filter for continuous observations in Rust (templates/rust/filter.rs.tmpl), written with the
// Rust backend's writer (codegen/backends/rust/rust_filter_writer.hpp) from this module's functions.
#include "pfgen/codegen/backends/rust/rust_filter_writer.hpp"
#include "pfgen/observations/continuous/continuous_code.hpp"
#include "pfgen/observations/continuous/heun_step.hpp"

namespace pfgen::codegen {

GeneratedFilter ContinuousCode::rust_filter(const Model& model, const FilterEquations& eq,
                                            const CodegenOptions& options) const {
  RustFilterWriter w(model, eq, options);
  const ContinuousFunctions f = continuous_functions(model, eq, options, w.names, w.emitter, true);
  w.result.functions = f.stats();
  std::map<std::string, std::string> values = w.common_values(eq.p, eq.variables.count());
  RustFilterWriter::add_function(values, "derivatives", f.derivatives);
  RustFilterWriter::add_function(values, "gain", f.gain);
  RustFilterWriter::add_function(values, "observation", f.observation);
  RustFilterWriter::add_function(values, "rates", *f.rates);
  values.insert({{"K", w.names.K}, {"h", w.names.h}, {"gain_meaning", gain_meaning(eq)}});
  values.emplace("initial_body", w.body(initial_state_statements(initial_values(model, eq.variables))));
  // The step's loops as the continuous module describes them (heun_step.hpp).
  std::map<std::string, std::string> loops;
  add_heun_step_loops(loops, w.emitter,
                      {ir::name("STATES"), ir::name("OBSERVATIONS"), ir::name("STATE_SIZE"), ir::number(2)}, eq.n(),
                      eq.p, eq.variables.count());
  for (const auto& [key, text] : loops) values.emplace(key, rust_indent(text));
  w.write("filter", values);
  return w.result;
}

}  // namespace pfgen::codegen
