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

}  // namespace pfgen::codegen
