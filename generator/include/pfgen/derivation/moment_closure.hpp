#pragma once
// The moment filter of order k (the closure kinds; docs/theory.md §2.10): m and the central moments
// mu_a = E[(x-m)^a], 2 <= |a| <= k, of the conditional law, whose Kushner-Stratonovich equations are
// closed by setting every cumulant of order > k to zero (ClosedExpectation). In Ito form, with
// e = x - m, dnu = dy - E[h] dt, C_b = E[e^b h] - mu_b E[h] (1 x p) and K_i = C_(e_i) R^-1:
//   dm = E[f] dt + K dnu
//   dmu_a = ( sum_i a_i (E[e^(a-e_i) f_i] - mu_(a-e_i) E[f_i])
//           + 1/2 sum_ij a_i (a_j - [i = j]) (E[e^(a-e_i-e_j) G_ij] + mu_(a-e_i-e_j) K_i R K_j^T)
//           - sum_i a_i C_(a-e_i) R^-1 C_(e_i)^T ) dt
//         + (C_a - sum_i a_i mu_(a-e_i) C_(e_i)) R^-1 dnu
// (Ito's formula for E[phi(x, m)] with the moving centre m). At k = 2 these are the Gaussian
// closure's equations, the optimal kind's, term for term.
#include <vector>

#include "pfgen/algebra/polynomial.hpp"
#include "pfgen/derivation/filter_variables.hpp"
#include "pfgen/model/model.hpp"

namespace pfgen {

struct MomentClosureTerms {
  std::vector<Polynomial> m_drift;  // E[f], n
  // dP's dt coefficient in the optimal kind's three parts, upper triangle: the f terms, the G terms, and the
  // observation's terms (subtracted).
  std::vector<Polynomial> P_moment, P_diffusion, P_correction;
  // The higher moments' dt coefficients, in FilterVariables::higher_moments() order.
  std::vector<Polynomial> higher_drift;
  // With an observation (else empty): E[h] (p), the gain K (n x p), and the dnu coefficients of P (upper
  // triangle x p) and of each higher moment.
  std::vector<Polynomial> predicted_observation;
  std::vector<std::vector<Polynomial>> gain, P_gain, higher_gain;
};

// The terms for a model's drift f, diffusion G (n x n, the states') and, when `h` is not empty, its
// observation rows h with noise B (p x r, R = B B^T).
MomentClosureTerms moment_closure_terms(const Model& model, const FilterVariables& vars, const std::vector<Polynomial>& h,
                                        const ExMatrix& B);

// Margins that are all positive while the moment state can belong to a law, one pair of words per margin: per
// state i the variance P_ii; P's leading principal minors of sizes 2..min(n, 4) (Sylvester: P positive definite;
// the runtime checks P's least eigenvalue at any n); and per state Pearson's bound mu4 P_ii - P_ii^3 - M3_iii^2
// (kurtosis above 1 + skewness^2; zero only for a law on two points) with mu4 the closed law's: M4_iiii at order 4,
// 3 P_ii^2 at order 3. These are necessary conditions on P and each marginal; the joint moment matrix may lose
// positive definiteness first (docs/theory.md §2.10).
struct RealisabilityMargins {
  std::vector<Polynomial> margins;
  std::vector<std::string> meaning;  // "variance of x1", "Pearson's bound of x1"
};
RealisabilityMargins realisability_margins(const FilterVariables& vars, const std::vector<std::string>& state_names);

}  // namespace pfgen
