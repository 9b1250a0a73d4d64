#pragma once
// The risk-sensitive filter's equations by paper 002's construction (docs/theory.md §2.7): the
// log of the risk-sensitive information state sigma (the Zakai equation with the added potential
// eps^-1 L(x, m), L = (x - m)^T M (x - m)) has the quadratic form
//   log sigma = -1/2 (x - m)^T P^-1 (x - m) + rho,
// its equation is written at x = m + P u, and the terms are collected by powers of u: the u^1
// coefficients give dm, the u^2 coefficients dP, higher powers are dropped (they vanish for a
// linear drift, where this is the LEQG filter). In u the form -1/2 u^T P u needs no inverse of P,
// so every coefficient is a polynomial in m and P.
#include <vector>

#include "pfgen/algebra/polynomial.hpp"
#include "pfgen/derivation/filter_variables.hpp"
#include "pfgen/model/model.hpp"

namespace pfgen {

// Each right-hand side term's u^1 and u^2 coefficients, kept apart so that the report can show
// where each part of the filter comes from.
struct RiskSensitiveTerms {
  std::vector<Polynomial> m_drift;               // n: f(m) - P grad(div f)(m) (transport and compression)
  std::vector<std::vector<Polynomial>> gain;     // n x p: P A^T R^-1, the coefficient of dy
  std::vector<Polynomial> innovation_drift;      // n: -gain (A0 + A m), from -1/2 h^T R^-1 h
  std::vector<Polynomial> P_moment;              // upper triangle: J P + P J^T, J = df/dx at m (transport)
  std::vector<Polynomial> P_diffusion;           // upper triangle: G
  // Subtracted: P (A^T R^-1 A + Hess(div f)(m) - (2/eps) M) P (observation, compression, risk).
  std::vector<Polynomial> P_correction;
};

// Needs a continuous observation, a `risk:` section and a state-independent diffusion (the
// registry's unsupported_reason has refused other models before this is called).
RiskSensitiveTerms risk_sensitive_terms(const Model& model, const FilterVariables& vars);

}  // namespace pfgen
