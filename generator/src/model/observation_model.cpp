#include "pfgen/model/observation_model.hpp"

#include <stdexcept>

namespace pfgen {

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
