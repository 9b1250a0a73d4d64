#pragma once
// The observation's contribution to the filter: A^T R^-1 (the gain is
// P A^T R^-1) and A^T R^-1 A (the correction is P A^T R^-1 A P), R = B B^T.
#include "pfgen/model/model.hpp"

namespace pfgen {

struct ObservationTerms {
  ExMatrix At_Rinv;     // n x p
  ExMatrix At_Rinv_A;   // n x n, symmetric
};

ObservationTerms observation_terms(const Model& model);

}  // namespace pfgen
