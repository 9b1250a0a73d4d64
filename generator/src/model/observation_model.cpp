#include "pfgen/model/observation_model.hpp"

#include <stdexcept>

namespace pfgen {

ObservationKind ObservationModel::kind() const {
  // One alternative per kind, in the order of ObservationKind.
  return static_cast<ObservationKind>(form_.index());
}

std::size_t ObservationModel::p() const {
  return std::visit([](const auto& form) { return form.A.size(); }, form_);
}

const ContinuousObservation& ObservationModel::continuous() const {
  if (const auto* c = std::get_if<ContinuousObservation>(&form_)) return *c;
  throw std::logic_error("the model's observation is " + observation_kind_info(kind()).name + ", not continuous");
}

}  // namespace pfgen
