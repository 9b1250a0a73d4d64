#include "pfgen/printing/observation_report.hpp"

namespace pfgen {

// The one place the printers' parts are chosen from the axes.
const ObservationReport& observation_report(const ObservationModel& observation) {
  if (observation.samples()) return sampled_observation_report();
  if (observation.delay_h()) return delayed_observation_report();
  return observation.rate().affine() ? continuous_observation_report() : polynomial_observation_report();
}

const ObservationStatement& observation_statement(const ObservationModel& observation) {
  if (observation.samples()) return sampled_observation_statement();
  if (observation.delay_h()) return delayed_observation_statement();
  return observation.rate().written_affine() ? continuous_observation_statement()
                                             : polynomial_observation_statement();
}

}  // namespace pfgen
