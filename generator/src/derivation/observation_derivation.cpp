#include "pfgen/derivation/observation_derivation.hpp"

namespace pfgen {

// The one place the axes choose the derivation's part: the timing, then the delay, then the rate
// (samples choose theirs in the sampled module). A linear h (rows of degree <= 1, whose affine
// case the rate found when the model was built) takes A0 + A x's part, so its filters are the
// continuous observation's field for field.
const ObservationDerivation& observation_derivation(const ObservationModel& observation) {
  if (observation.samples()) return sampled_observation_derivation(observation.rate());
  if (observation.delay_h()) return delayed_observation_derivation();
  return observation.rate().affine() ? continuous_observation_derivation() : polynomial_observation_derivation();
}

}  // namespace pfgen
