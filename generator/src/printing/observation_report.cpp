#include "pfgen/printing/observation_report.hpp"

namespace pfgen {

const ObservationReport& observation_report(ObservationKind kind) {
  static const ObservationReport* const parts[kObservationKindCount] = {
      &continuous_observation_report(), &sampled_observation_report(), &delayed_observation_report(),
      &polynomial_observation_report()};
  return observation_part(kind, parts);
}

}  // namespace pfgen
