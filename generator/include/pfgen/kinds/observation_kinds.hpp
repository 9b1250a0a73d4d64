#pragma once
// The observation models pfgen knows, as plain names: the kind registry says which of them each
// filter kind supports, and the model room's ObservationModel (model/observation_model.hpp)
// holds one of them. A new observation model is one row here and one alternative there.
#include <string>
#include <vector>

namespace pfgen {

enum class ObservationKind {
  Continuous,  // dy = (A0 + A x) dt + B dW2
  Sampled,     // y_k = C0 + C x(t_k) + Uv v_k at t_k = k T, v_k ~ N(0, I)
  Delayed,     // dy = (A0 + A x(t - h)) dt + B dW2, h >= 0 (h = 0 only through the C++ API)
};

struct ObservationKindInfo {
  ObservationKind kind;
  std::string name;         // as printed in messages: "continuous"
  std::string description;  // one line, the observation equation
};

// Every observation model, in a fixed order.
const std::vector<ObservationKindInfo>& observation_kinds();
const ObservationKindInfo& observation_kind_info(ObservationKind kind);

}  // namespace pfgen
