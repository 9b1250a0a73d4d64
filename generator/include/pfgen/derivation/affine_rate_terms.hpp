#pragma once
// What an affine observation rate dy = (A0 + A x) dt + B dW2 gives the filters observed through
// it, with R = B B^T: A^T R^-1, which makes the gain P A^T R^-1, and A^T R^-1 A, which makes the
// correction P A^T R^-1 A P. In the derivation room because the risk-sensitive kind's construction
// reads them as the continuous and delayed observations' terms do (observations/continuous/
// observation_terms.hpp).
#include "pfgen/model/model.hpp"

namespace pfgen {

struct ObservationTerms {
  ExMatrix At_Rinv;     // n x p
  ExMatrix At_Rinv_A;   // n x n, symmetric
};

ObservationTerms observation_terms(const ContinuousObservation& observation);

}  // namespace pfgen
