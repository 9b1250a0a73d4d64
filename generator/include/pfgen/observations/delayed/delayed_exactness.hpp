#pragma once
// When a filter of delayed observations is exact: only with h = 0, as its undelayed counterpart;
// with h > 0 the report names the approximations (docs/theory.md §2.6).
#include "pfgen/derivation/exactness.hpp"

namespace pfgen {

ExactnessReport delayed_exactness(const Model& model, FilterKind kind);

}  // namespace pfgen
