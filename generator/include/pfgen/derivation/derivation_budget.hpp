#pragma once
// Bounds on the work of a derivation, checked before the expectations are expanded.
//
// The per-state degree limit does not bound the work: E[x^80 y^80] alone has 45961 terms, and the
// memoised recursion holds every E[x^a y^b] on its way, 2.8 million terms that took 16 s and
// 800 MB; x^160 y^160 exhausted 3 GB. The covariance equations grow as n^2 times the terms of the
// Jacobian and of the observation term. Both are counted exactly or bounded from above, from the
// polynomials the derivation starts from, and a model beyond a limit is refused with one line
// naming the field (docs/guide/model-file.md, limits).
#include <cstddef>
#include <string>
#include <vector>

#include "pfgen/algebra/polynomial.hpp"
#include "pfgen/model/model.hpp"

namespace pfgen {

inline constexpr double kMaxExpectationTerms = 250000;  // terms of all E[x^a] the recursion holds
inline constexpr double kMaxEquationTerms = 2000000;    // terms of the m and P equations
// Products of two terms that a polynomial observation's correction or a sampled c's update take
// (each a product of coefficients, about 1 us and 40 bytes: about 5 s and 150 MB at the limit).
inline constexpr double kMaxObservationProducts = 4000000;

// The number of terms of E[x^alpha] for x ~ N(m, P), as a polynomial in m and P: one per way to
// pair some of alpha's factors (P_ij, P_ii for a pair within one state) and leave the rest as m's.
// Exact up to `stop_above`; beyond it, some number above `stop_above`.
double gaussian_moment_terms(const Monomial& alpha, double stop_above = kMaxExpectationTerms);

// The polynomials a filter kind starts from, with where each came from in the model file.
struct DerivationInputs {
  bool gaussian = true;  // expectations under N(m, P), else evaluated at m (extended filters)
  std::vector<Polynomial> drift;                   // f_i
  std::vector<std::vector<Polynomial>> jacobian;   // d f_i / d x_k
  std::vector<Polynomial> diffusion_upper;         // G_ij, i <= j
  std::string diffusion_field;                     // "diffusion", "additive_diffusion_covariance", ...
  std::size_t observed_states = 0;                 // states with a nonzero column in the observation
};

// The states whose column of an observation matrix (A, or a sampled observation's C) is not zero:
// an observation module's DerivationInputs::observed_states.
std::size_t observed_states(const ExMatrix& observation_matrix);
// The same for an observation through polynomials in the states 0..n-1 (a polynomial h or c): the
// states any of them reads.
std::size_t observed_states(const std::vector<Polynomial>& observation, std::size_t n);

// Throws ModelError (file, field, row) when the derivation would go beyond either limit.
void check_derivation_budget(const Model& model, const DerivationInputs& inputs);

// An observation through polynomials in the states, whose expectations the derivation takes: a
// polynomial h (dy = h dt + B dW2) or a sampled c (y_k = c(x(t_k)) + Uv v_k). Empty for a linear one.
struct ObservationPolynomials {
  std::vector<Polynomial> rows;  // h_1..h_p or c_1..c_r
  std::string field;             // "observation.h", "observation.sampled.c"
  bool sampled = false;          // c: every kind's update takes E[c_a c_b] (S = Cov(c)) and E[J_c]
  ExMatrix noise;                // h's B: the gain's R^-1 = (B B^T)^-1 couples some rows; empty for c
};

// The same limits for what the observation adds, checked before any of it is computed (a filter's
// frame takes E[h] first): the Gaussian expectations of the rows, of their derivatives (the gain
// P E[J]^T) and second derivatives (dP's dy term P E[H] P) or of the products c_a c_b, and the
// terms of the products that make the correction (K E[J] P) or S's C P C^T. `gaussian`: the
// kind's observation terms are expectations (the extended kinds read h at m). Throws ModelError
// naming `observation.field`.
void check_observation_budget(const Model& model, const ObservationPolynomials& observation, bool gaussian);

}  // namespace pfgen
