#pragma once
// What a polynomial observation dy = h(x, t) dt + B dW2 contributes to a filter, R = B B^T and the
// innovation dnu = dy - E[h] dt (docs/theory.md, "Polynomial observations"). Under the Gaussian
// closure x ~ N(m, P), with J the Jacobian of h and H_k the Hessian of h_k, Stein's lemma gives
//   E[(x - m)(h - E h)^T] = P E[J]^T                     (once)
//   E[(x - m)(x - m)^T (h_k - E h_k)] = P E[H_k] P        (twice)
// so the assumed-density filter, in Ito form, is
//   dm = E[f] dt + K dnu,                 K = P E[J]^T R^-1
//   dP = (moments + E[g g^T] - K E[J] P) dt + sum_r L_r dnu_r,   L_r = sum_k P E[H_k] P (R^-1)_kr
// The extended filter (at the mean) reads h(m) and J(m) and has no dnu term in dP. For linear h
// = A0 + A x this is the continuous observation's filter exactly (E[J] = A, H = 0).
// The derivation room's part of the polynomial observation module (observations/polynomial/).
#include <vector>

#include "pfgen/algebra/polynomial.hpp"
#include "pfgen/derivation/filter_variables.hpp"
#include "pfgen/model/expression_matrix.hpp"

namespace pfgen {

struct PolynomialObservationTerms {
  std::vector<Polynomial> predicted_observation;  // p: E[h] (the extended filter: h(m))
  std::vector<std::vector<Polynomial>> gain;      // n x p: P E[J]^T R^-1
  std::vector<Polynomial> P_correction;           // n(n+1)/2, upper triangle, subtracted: K E[J] P
  // n(n+1)/2 x p, upper triangle: L_ij,r, the coefficient of dnu_r in dP_ij (all zero for linear h
  // and for the extended filter).
  std::vector<std::vector<Polynomial>> P_gain;
};

// `h`: p polynomials over the state variables 0..n-1 (coefficients may hold parameters and t);
// `B`: p x q with B B^T invertible. `at_mean`: the extended filter's terms.
PolynomialObservationTerms polynomial_observation_terms(const std::vector<Polynomial>& h, const ExMatrix& B,
                                                        const FilterVariables& vars, bool at_mean);

// The same from moments computed otherwise (the ukf's sigma points): the predicted observation and
// the cross covariance C = Cov(x, h), n x p; gain C R^-1, correction C R^-1 C^T, no dy term in dP.
PolynomialObservationTerms observation_terms_from_moments(std::vector<Polynomial> predicted,
                                                          const std::vector<std::vector<Polynomial>>& cross,
                                                          const ExMatrix& B);

}  // namespace pfgen
