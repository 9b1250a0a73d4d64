#include "pfgen/observations/polynomial/polynomial_observation.hpp"

namespace pfgen {

std::vector<Polynomial> observation_polynomials(const Model& model) {
  return model.observation.rate().polynomials(model.states);
}

unsigned observation_degree(const Model& model) { return model.observation.rate().degree(model.states); }

bool predicts_linearly(const FilterEquations& eq) {
  for (const Polynomial& y : eq.predicted_observation)
    if (y.degree() > 1) return false;
  return true;
}

}  // namespace pfgen
