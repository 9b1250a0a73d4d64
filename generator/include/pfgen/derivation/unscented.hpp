#pragma once
// The unscented Kalman-Bucy filter's moment terms (Sarkka 2007; docs/theory.md §2.8): the
// expectations of f, (x - m) f^T and g g^T under N(m, P) replaced by weighted sums over the 2n + 1
// sigma points
//   X_0 = m,   X_j = m + sqrt(c) L_j,   X_{n+j} = m - sqrt(c) L_j   (j = 1..n),
// L the lower Cholesky factor of P (L L^T = P), L_j its j-th column, c = n + kappa with kappa = 3 - n
// for n <= 3 (c = 3, the Gauss-Hermite choice) and kappa = 0 above (c = n, so w_0 is never negative);
// weights w_0 = kappa / c, w_i = 1 / (2c).
//   m_drift     = sum_i w_i f(X_i)
//   P_moment    = sum_i w_i (X_i - m) f(X_i)^T + its transpose
//   P_diffusion = sum_i w_i G(X_i),   G = g g^T (the mean weights: beta plays no role, see §2.8)
// The entries of L are symbols (the lower triangle, n(n+1)/2 of them) defined from P by the
// Cholesky recursion; the terms are polynomials in m whose coefficients hold them. The odd powers
// of sqrt(c) cancel between X_j and X_{n+j}, so the coefficients are rational in c.
#include <vector>

#include <ginac/ginac.h>

#include "pfgen/algebra/polynomial.hpp"
#include "pfgen/derivation/filter_variables.hpp"
#include "pfgen/model/model.hpp"

namespace pfgen {

// The scale c = n + kappa and the weights of the centre point and of each of the 2n others.
struct SigmaPointWeights {
  GiNaC::numeric c, w0, w;
};
SigmaPointWeights sigma_point_weights(std::size_t n);

struct UnscentedTerms {
  // L's entries, column by column (L11, L21, ..., Ln1, L22, ...), each defined from P and the
  // entries before it: L_jj = sqrt(P_jj - sum_{k<j} L_jk^2), L_ij = (P_ij - sum_{k<j} L_ik L_jk) / L_jj,
  // the radicand taken as max(0, .) = (d + |d|) / 2 so that a singular P's zero pivot stays 0.
  std::vector<FilterDefinition> cholesky;
  std::vector<Polynomial> m_drift;      // n
  std::vector<Polynomial> P_moment;     // n(n+1)/2, upper triangle
  std::vector<Polynomial> P_diffusion;  // n(n+1)/2, upper triangle
};

// The terms for the model's drift and diffusion (G, so that a model with only
// diffusion_covariance is served as well as one with g: sum w_i g g^T = sum w_i G). L's symbols are
// named L21 (L2_1 from n = 10, as P's indices), with '_' after the L while a state, parameter or
// the time of the model already has one of those names.
UnscentedTerms unscented_terms(const Model& model, const FilterVariables& vars);

// For an observation module whose observation is a function h of the state: the sigma points'
// sum_i w_i h(X_i) and sum_i w_i (X_i - m) h(X_i) (n entries), with L the Cholesky entries that
// unscented_terms defined (`cholesky`, in its order). Polynomials in m, their coefficients holding L.
struct SigmaPointMoments {
  Polynomial mean;
  std::vector<Polynomial> cross;
};
SigmaPointMoments sigma_point_moments(const GiNaC::ex& h, const Model& model,
                                      const std::vector<FilterDefinition>& cholesky);

}  // namespace pfgen
