#pragma once
// The observation models pfgen knows, as plain names: the kind registry says which of them each
// filter kind supports, and the model room's ObservationModel (model/observation_model.hpp)
// derives one from its axes (timing, delay, rate; ObservationModel::kind()). What each name
// means for the rooms above is its module in observations/ (DESIGN.md, "A new observation model").
#include <cstddef>
#include <string>
#include <vector>

namespace pfgen {

enum class ObservationKind {
  Continuous,  // dy = (A0 + A x) dt + B dW2
  Sampled,     // y_k = C0 + C x(t_k) + Uv v_k at t_k = k T, v_k ~ N(0, I)
  Delayed,     // dy = (A0 + A x(t - h)) dt + B dW2, h >= 0 (h = 0 only through the C++ API)
  Polynomial,  // dy = h(x, t) dt + B dW2, h polynomial in the states, written as rows
};

struct ObservationKindInfo {
  ObservationKind kind;
  std::string name;         // as printed in messages: "continuous"
  std::string description;  // one line, the observation equation
};

// Every observation model, in a fixed order.
const std::vector<ObservationKindInfo>& observation_kinds();
const ObservationKindInfo& observation_kind_info(ObservationKind kind);

// The number of observation models: every table indexed by ObservationKind has this many rows.
inline constexpr std::size_t kObservationKindCount = 4;

// A room's part of the observation model `kind`, from that room's table of the modules' parts, one
// per kind in ObservationKind's order (a table of another length does not compile). Each room that
// needs what differs between observation models declares an interface and keeps such a table
// (derivation/observation_derivation.cpp, printing/observation_report.cpp, ...), and calls the part
// instead of branching on the kind.
template <class Part>
const Part& observation_part(ObservationKind kind, const Part* const (&parts)[kObservationKindCount]) {
  return *parts[static_cast<std::size_t>(kind)];
}

}  // namespace pfgen
