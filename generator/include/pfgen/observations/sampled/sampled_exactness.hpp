#pragma once
// When a filter of sampled observations is exact: the Kalman filter of the sampled linear Gaussian
// model (cd-euler: of its Euler discretisation), or why not.
#include "pfgen/derivation/exactness.hpp"

namespace pfgen {

ExactnessReport sampled_exactness(const Model& model, FilterKind kind);

}  // namespace pfgen
