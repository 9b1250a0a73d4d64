#pragma once
// What a continuous observation dy = (A0 + A x) dt + B dW2 contributes to a filter, R = B B^T:
// the gain P A^T R^-1, the correction P A^T R^-1 A P subtracted from the P drift (from
// derivation/affine_rate_terms.hpp's A^T R^-1 and A^T R^-1 A), and the predicted observation rate
// A0 + A m. Each observation kind has such a part of its own.
#include <vector>

#include "pfgen/algebra/polynomial.hpp"
#include "pfgen/derivation/affine_rate_terms.hpp"
#include "pfgen/derivation/filter_variables.hpp"
#include "pfgen/model/model.hpp"

namespace pfgen {

// A0 + A m, one polynomial per observation row, in the filter's variables; with `delayed`,
// A0 + A md, md = m(t - h) (FilterVariables::m_delayed).
std::vector<Polynomial> predicted_observation(const ContinuousObservation& observation, const FilterVariables& vars,
                                              bool delayed = false);

// The gain (n x p) and the correction (upper triangle) of a derived filter.
struct ObservationCorrection {
  std::vector<std::vector<Polynomial>> gain;
  std::vector<Polynomial> P_correction;
};
// With `transition`, paper 004's gain P Phi A^T R^-1 and correction P Phi A^T R^-1 A Phi P,
// Phi = diag(phi_1..phi_n) (FilterVariables::phi; a delayed filter's variables).
ObservationCorrection observation_correction(const ContinuousObservation& observation, const FilterVariables& vars,
                                             bool transition = false);

}  // namespace pfgen
