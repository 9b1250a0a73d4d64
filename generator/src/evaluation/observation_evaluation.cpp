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

const ObservationEvaluation& observation_evaluation(ObservationKind kind) {
  static const ObservationEvaluation* const parts[kObservationKindCount] = {
      &continuous_observation_evaluation(), &sampled_observation_evaluation(), &delayed_observation_evaluation(),
      &polynomial_observation_evaluation()};
  return observation_part(kind, parts);
}

}  // namespace pfgen
