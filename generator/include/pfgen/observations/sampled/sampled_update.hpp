#pragma once
// What a sampled observation y_k = C0 + C x(t_k) + Uv v_k contributes to a filter: the Kalman
// update at each sample (docs/theory.md, "Continuous-discrete filters"), with R = Uv Uv^T:
//   S = C P C^T + R,  K = P C^T S^-1,  m <- m + K (y - C0 - C m),
//   P <- (I - K C) P (I - K C)^T + K R K^T   (Joseph form).
// K is rational in P, not polynomial, so the derivation keeps its polynomial parts (P C^T and
// S) and the consumers form K: `pfgen eval` exactly, generated code by an unrolled Cholesky solve.
//
// Samples y_k = c(x(t_k)) + Uv v_k through a polynomial c (docs/theory.md §2.5) get the Gaussian
// (moment-matching) update with c's exact moments under x ~ N(m, P): predicted sample E[c],
// Cov(x, c) = P E[J_c]^T (Stein), S = Cov(c) + R, K = Cov(x, c) S^-1, m <- m + K (y - E[c]),
// P <- P - K S K^T. It is written in the linear update's form, with C = E[J_c] and R replaced by
// R_c = S - C P C^T (the Schur complement of the joint covariance of x and c, positive
// semi-definite): then S = C P C^T + R_c, P C^T = Cov(x, c), and the Joseph form
// (I - K C) P (I - K C)^T + K R_c K^T equals P - K S K^T, so every consumer of the linear update
// serves it unchanged. The extended kind (at_mean) reads c(m), J_c(m) and R_c = R.
#include <cstddef>
#include <vector>

#include "pfgen/algebra/polynomial.hpp"
#include "pfgen/derivation/filter_variables.hpp"
#include "pfgen/derivation/sampled_update_parts.hpp"
#include "pfgen/model/model.hpp"

namespace pfgen {

// The update of samples through C0 + C x (the rate's affine case, `rate`, taken every `times.period`).
SampledUpdate sampled_update(const SampleTimes& times, const AffineRate& rate, const FilterVariables& vars);

// C0 + C m, one polynomial per observation row, in the filter's variables.
std::vector<Polynomial> predicted_sample(const AffineRate& rate, const FilterVariables& vars);

// For a rate that is not affine, c: the update above with E[c] (c(m)
// `at_mean`, the extended kind) as the predicted sample, which it returns in `predicted`.
SampledUpdate polynomial_sampled_update(const Model& model, const FilterVariables& vars, bool at_mean,
                                        std::vector<Polynomial>& predicted);

}  // namespace pfgen
