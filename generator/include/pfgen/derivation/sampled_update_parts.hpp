#pragma once
// The Kalman update at each sample as FilterEquations holds it (a sampled observation's filters;
// what it means and how it is derived: observations/sampled/sampled_update.hpp). A type of the
// derivation room's, so that FilterEquations names it without including an observation module.
#include <cstddef>
#include <utility>
#include <vector>

#include "pfgen/algebra/polynomial.hpp"

namespace pfgen {

struct SampledUpdate {
  GiNaC::numeric period;                          // T
  std::size_t substeps = 1;                       // prediction sub-steps per period
  // How substeps came about (observations/sampled/substep_choice.hpp): chosen by the rule when the model leaves them
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
  // A moment filter's samples through a polynomial c (observations/sampled/closure_sampled_update.hpp): C = E[J_c]
  // and R = Uv Uv^T under the closed law, and z = (x - m, c - E[c] - C (x - m))'s joint central moments that are not
  // the filter's own, `joint[q]` the one with ascending indices `joint_indices[q]` (0-based over z's n + r entries),
  // from which P and the higher moments are updated. Empty otherwise.
  bool closed_law = false;
  std::vector<std::vector<std::size_t>> joint_indices;
  std::vector<Polynomial> joint;
  std::size_t r() const { return C.size(); }
  // Index of S_ab (or R_ab), a and b in either order, in the packed upper triangle.
  std::size_t upper_index(std::size_t a, std::size_t b) const {
    if (a > b) std::swap(a, b);
    return a * r() - a * (a - 1) / 2 + (b - a);
  }
};

}  // namespace pfgen
