#include "pfgen/codegen/observation_code.hpp"

#include <stdexcept>

namespace pfgen::codegen {

void ObservationCode::check_size(const Model&, const FilterEquations&) const {}

FilterFile ObservationCode::filter_file(const Model&, const FilterEquations&, const CodegenOptions&,
                                        const FunctionNames&, const StatementEmitter&) const {
  throw std::logic_error("an observation module without layouts() describes no filter file");
}

std::vector<std::string> ObservationCode::layouts() const { return {}; }

GeneratedFilter ObservationCode::cpp_filter(const Model&, const FilterEquations&, const CodegenOptions&) const {
  throw std::logic_error("an observation module with layouts() is written by the backends' writers");
}

GeneratedFilter ObservationCode::c_filter(const Model& model, const FilterEquations& eq,
                                          const CodegenOptions& options) const {
  return cpp_filter(model, eq, options);
}

GeneratedFilter ObservationCode::rust_filter(const Model& model, const FilterEquations& eq,
                                             const CodegenOptions& options) const {
  return cpp_filter(model, eq, options);
}

std::vector<std::string> ObservationCode::c_templates() const { return {}; }

void ObservationCode::plugin_options(const Model&, std::optional<double>, CodegenOptions&) const {}

const ObservationCode& observation_code(ObservationKind kind) {
  static const ObservationCode* const parts[kObservationKindCount] = {
      &continuous_observation_code(), &sampled_observation_code(), &delayed_observation_code(),
      &polynomial_observation_code()};
  return observation_part(kind, parts);
}

const ObservationCode& observation_code(const ObservationModel& observation) {
  if (observation.samples()) return sampled_observation_code();
  if (observation.delay_h()) return delayed_observation_code();
  return observation.rate().affine() ? continuous_observation_code() : polynomial_observation_code();
}

}  // namespace pfgen::codegen
