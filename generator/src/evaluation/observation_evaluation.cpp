#include "pfgen/evaluation/observation_evaluation.hpp"

namespace pfgen {

std::vector<std::pair<std::string, const std::vector<GiNaC::numeric>*>> delayed_inputs(const EvaluationPoint& point) {
  return {{"--m-delayed", &point.m_delayed},
          {"--x-star", &point.x_star},
          {"--x-star-delayed", &point.x_star_delayed},
          {"--phi", &point.phi}};
}

void refuse_delayed_inputs(const Model& model, const FilterEquations& eq, const EvaluationPoint& point) {
  for (const auto& [option, values] : delayed_inputs(point))
    if (!values->empty())
      throw EvaluationError(option + ": filter " + eq.name + " is not for delayed observations (model " + model.name +
                            " has none)");
}

// The one place eval's part is chosen from the axes.
const ObservationEvaluation& observation_evaluation(const ObservationModel& observation) {
  if (observation.samples()) return sampled_observation_evaluation();
  if (observation.delay_h()) return delayed_observation_evaluation();
  return observation.rate().written_affine() ? continuous_observation_evaluation()
                                             : polynomial_observation_evaluation();
}

}  // namespace pfgen
