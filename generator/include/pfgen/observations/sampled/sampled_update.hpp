#pragma once
// What a sampled observation y_k = C0 + C x(t_k) + Uv v_k contributes to a filter: the Kalman
// update at each sample (docs/theory.md, "Continuous-discrete filters"), with R = Uv Uv^T:
//   S = C P C^T + R,  K = P C^T S^-1,  m <- m + K (y - C0 - C m),
//   P <- (I - K C) P (I - K C)^T + K R K^T   (Joseph form).
// K is rational in P, not polynomial, so the derivation keeps its polynomial parts (P C^T and
// S) and the consumers form K: `pfgen eval` exactly, generated code by an unrolled Cholesky solve.
#include <cstddef>
#include <vector>

#include "pfgen/algebra/polynomial.hpp"
#include "pfgen/derivation/filter_variables.hpp"
#include "pfgen/model/model.hpp"

namespace pfgen {

struct SampledUpdate {
  GiNaC::numeric period;                          // T
  std::size_t substeps = 1;                       // prediction sub-steps per period
  std::vector<std::vector<Polynomial>> PCt;       // n x r: P C^T, linear in P
  std::vector<Polynomial> S;                      // r(r+1)/2, upper triangle row by row: C P C^T + R
  std::vector<std::vector<Polynomial>> C;         // r x n, constants in the filter variables
  std::vector<Polynomial> R;                      // r(r+1)/2, upper triangle: Uv Uv^T
  std::size_t r() const { return C.size(); }
  // Index of S_ab (or R_ab), a and b in either order, in the packed upper triangle.
  std::size_t upper_index(std::size_t a, std::size_t b) const;
};

SampledUpdate sampled_update(const SampledObservation& observation, const FilterVariables& vars);

// C0 + C m, one polynomial per observation row, in the filter's variables.
std::vector<Polynomial> predicted_sample(const SampledObservation& observation, const FilterVariables& vars);

}  // namespace pfgen
