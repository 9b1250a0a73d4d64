#pragma once
// When a filter of sampled observations is exact: the Kalman filter of the sampled linear Gaussian
// model (cd-euler: of its Euler discretisation), or why not.
#include "pfgen/derivation/exactness.hpp"

namespace pfgen {

// `nonlinear_samples`: why the samples' rate is not linear in the states, empty when it is (the
// rate's part says, sampled_derivation).
ExactnessReport sampled_exactness(const Model& model, FilterKind kind, const std::string& nonlinear_samples);

}  // namespace pfgen
