#include "pfgen/observations/polynomial/polynomial_observation.hpp"

#include <algorithm>

namespace pfgen {

std::vector<Polynomial> observation_polynomials(const Model& model) {
  std::vector<Polynomial> out;
  for (const GiNaC::ex& h : model.observation.polynomial().h) out.push_back(Polynomial::from_ex(h, model.states));
  return out;
}

unsigned observation_degree(const Model& model) {
  unsigned degree = 0;
  for (const Polynomial& h : observation_polynomials(model)) degree = std::max(degree, h.degree());
  return degree;
}

bool predicts_linearly(const FilterEquations& eq) {
  for (const Polynomial& y : eq.predicted_observation)
    if (y.degree() > 1) return false;
  return true;
}

std::optional<ContinuousObservation> linear_form(const Model& model) {
  std::optional<AffineRows> linear = affine_rows(model.observation.polynomial().h, model.states);
  if (!linear) return std::nullopt;
  return ContinuousObservation{std::move(linear->constant), std::move(linear->linear), model.observation.polynomial().B};
}

}  // namespace pfgen
