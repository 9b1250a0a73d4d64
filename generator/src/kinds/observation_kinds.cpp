#include "pfgen/kinds/observation_kinds.hpp"

#include <stdexcept>

namespace pfgen {

const std::vector<ObservationKindInfo>& observation_kinds() {
  static const std::vector<ObservationKindInfo> kinds = {
      {ObservationKind::Continuous, "continuous", "dy = (A0 + A x) dt + B dW2"},
      {ObservationKind::Sampled, "sampled", "y_k = C0 + C x(t_k) + Uv v_k at t_k = k T"},
      {ObservationKind::Delayed, "delayed", "dy = (A0 + A x(t - h)) dt + B dW2"},
      {ObservationKind::Polynomial, "polynomial", "dy = h(x, t) dt + B dW2"},
  };
  return kinds;
}

const ObservationKindInfo& observation_kind_info(ObservationKind kind) {
  for (const auto& info : observation_kinds())
    if (info.kind == kind) return info;
  throw std::logic_error("observation kind missing from the registry");
}

}  // namespace pfgen
