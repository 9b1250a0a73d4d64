#include "pfgen/model/observation_model.hpp"

#include <stdexcept>

#include "pfgen/algebra/polynomial.hpp"

namespace pfgen {

std::optional<AffineRows> affine_rows(const ExVector& rows, const std::vector<GiNaC::symbol>& states) {
  std::vector<Polynomial> polynomials;
  for (const GiNaC::ex& row : rows) {
    polynomials.push_back(Polynomial::from_ex(row, states));
    if (polynomials.back().degree() > 1) return std::nullopt;
  }
  AffineRows out{ExVector(rows.size(), GiNaC::ex(0)), ExMatrix(rows.size(), ExVector(states.size(), GiNaC::ex(0)))};
  for (std::size_t r = 0; r < polynomials.size(); ++r)
    for (const auto& [monomial, coefficient] : polynomials[r].terms()) {
      if (monomial.is_one())
        out.constant[r] = coefficient;
      else
        out.linear[r][monomial.factors().front().first] = coefficient;
    }
  return out;
}

ObservationKind ObservationModel::kind() const {
  // One alternative per kind, in the order of ObservationKind.
  return static_cast<ObservationKind>(form_.index());
}

std::size_t ObservationModel::p() const {
  if (const auto* s = std::get_if<SampledObservation>(&form_)) return s->C.size();
  if (const auto* h = std::get_if<PolynomialObservation>(&form_)) return h->h.size();
  return rate().A.size();
}

const ContinuousObservation& ObservationModel::continuous() const {
  if (const auto* c = std::get_if<ContinuousObservation>(&form_)) return *c;
  throw std::logic_error("the model's observation is " + observation_kind_info(kind()).name + ", not continuous");
}

const SampledObservation& ObservationModel::sampled() const {
  if (const auto* s = std::get_if<SampledObservation>(&form_)) return *s;
  throw std::logic_error("the model's observation is " + observation_kind_info(kind()).name + ", not sampled");
}

const DelayedObservation& ObservationModel::delayed() const {
  if (const auto* d = std::get_if<DelayedObservation>(&form_)) return *d;
  throw std::logic_error("the model's observation is " + observation_kind_info(kind()).name + ", not delayed");
}

const PolynomialObservation& ObservationModel::polynomial() const {
  if (const auto* h = std::get_if<PolynomialObservation>(&form_)) return *h;
  throw std::logic_error("the model's observation is " + observation_kind_info(kind()).name + ", not polynomial");
}

const ContinuousObservation& ObservationModel::rate() const {
  if (const auto* c = std::get_if<ContinuousObservation>(&form_)) return *c;
  if (const auto* d = std::get_if<DelayedObservation>(&form_)) return d->rate;
  throw std::logic_error("the model's observation is " + observation_kind_info(kind()).name + ": it has no A0, A, B");
}

GiNaC::numeric ObservationModel::delay() const {
  if (const auto* d = std::get_if<DelayedObservation>(&form_)) return d->delay;
  return 0;
}

}  // namespace pfgen
