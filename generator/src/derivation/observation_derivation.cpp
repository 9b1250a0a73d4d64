#include "pfgen/derivation/observation_derivation.hpp"

namespace pfgen {

const ObservationDerivation& observation_derivation(ObservationKind kind) {
  static const ObservationDerivation* const parts[kObservationKindCount] = {
      &continuous_observation_derivation(), &sampled_observation_derivation(), &delayed_observation_derivation(),
      &polynomial_observation_derivation()};
  return observation_part(kind, parts);
}

}  // namespace pfgen
