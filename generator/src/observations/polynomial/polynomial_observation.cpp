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
  if (observation_degree(model) > 1) return std::nullopt;
  const std::size_t n = model.n();
  ContinuousObservation out;
  out.B = model.observation.polynomial().B;
  for (const Polynomial& h : observation_polynomials(model)) {
    GiNaC::ex constant = 0;
    ExVector row(n, GiNaC::ex(0));
    for (const auto& [monomial, coefficient] : h.terms()) {
      if (monomial.is_one())
        constant = coefficient;
      else
        row[monomial.factors().front().first] = coefficient;
    }
    out.A0.push_back(constant);
    out.A.push_back(row);
  }
  return out;
}

}  // namespace pfgen
