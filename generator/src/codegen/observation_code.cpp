#include "pfgen/codegen/observation_code.hpp"

namespace pfgen::codegen {

void ObservationCode::check_size(const Model&, const FilterEquations&) const {}

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
