#include "pfgen/codegen/backends/rust/rust_filter_code.hpp"

namespace pfgen::codegen {

std::vector<std::string> rust_filter_paths(const std::string& model_name, const std::string& filter_name) {
  return {model_name + "/" + filter_identifier(filter_name) + ".rs"};
}

GeneratedFilter rust_filter_code(const Model& model, const FilterEquations& eq, const CodegenOptions& options) {
  // Until the statement IR gives every observation module one description of its functions, the
  // backend writes each module's filter itself.
  switch (eq.observation) {
    case ObservationKind::Continuous: return rust_continuous_filter(model, eq, options);
    case ObservationKind::Sampled: return rust_sampled_filter(model, eq, options);
    case ObservationKind::Delayed: return rust_delayed_filter(model, eq, options);
    case ObservationKind::Polynomial: return rust_polynomial_filter(model, eq, options);
  }
  throw CodegenError("unknown observation kind");
}

}  // namespace pfgen::codegen
