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
#include "pfgen/model/model.hpp"

namespace pfgen {

struct SampledUpdate {
  GiNaC::numeric period;                          // T
  std::size_t substeps = 1;                       // prediction sub-steps per period
  // How substeps came about (substep_choice.hpp): chosen by the rule when the model leaves them
  // out, else the model's or a KIND@S name's. The rule's rho at the prior and its count
  // (ceil(T rho / 0.25), possibly beyond any count) are kept for the reports; 0 when not assessed.
  bool substeps_chosen = false;
  double prior_rate = 0;
  double advised_substeps = 0;
  std::vector<std::vector<Polynomial>> PCt;       // n x r: P C^T, linear in P
  std::vector<Polynomial> S;                      // r(r+1)/2, upper triangle row by row: C P C^T + R
  std::vector<std::vector<Polynomial>> C;         // r x n: C (constants), or E[J_c] (polynomials in m, P)
  std::vector<Polynomial> R;                      // r(r+1)/2, upper triangle: Uv Uv^T, or R_c = S - C P C^T
  // A polynomial c: C and R as above, read by the reports; `at_mean` for the extended kind's.
  bool polynomial_samples = false, at_mean = false;
  std::size_t r() const { return C.size(); }
  // Index of S_ab (or R_ab), a and b in either order, in the packed upper triangle.
  std::size_t upper_index(std::size_t a, std::size_t b) const;
};

// The update of samples through C0 + C x (the rate's affine case, `rate`, taken every `times.period`).
SampledUpdate sampled_update(const SampleTimes& times, const AffineRate& rate, const FilterVariables& vars);

// C0 + C m, one polynomial per observation row, in the filter's variables.
std::vector<Polynomial> predicted_sample(const AffineRate& rate, const FilterVariables& vars);

// The samples' c as polynomials in the states (the rate's rows; empty for C0 + C x). Kept for the
// plugin part until it moves to the axes (model.observation.rate().polynomials).
std::vector<Polynomial> sample_polynomials(const Model& model);

// For a rate that is not affine, c: the update above with E[c] (c(m)
// `at_mean`, the extended kind) as the predicted sample, which it returns in `predicted`.
SampledUpdate polynomial_sampled_update(const Model& model, const FilterVariables& vars, bool at_mean,
                                        std::vector<Polynomial>& predicted);

}  // namespace pfgen
