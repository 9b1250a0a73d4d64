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
// Products of two terms that a moment filter's derivation takes (closure3, closure4), as
// closure_derivation_work counts them: each took 0.4-0.75 us of derivation on dense cubic, linear,
// high-degree and polynomial-h models, and at most about 110 bytes held to the end (closure4 of 8
// dense cubic states: 6.2 million, 4.6 s, 583 MB; of 9: 13.6 million, 11.6 s, 1.3 GB). At the
// limit: under 10 s and about 1.1 GB.
inline constexpr double kMaxClosureProducts = 10000000;

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

// The number of terms of the central moment E[e^g], e = x - m, under a moment filter's closed law of
// order k (ClosedExpectation: every cumulant above k zero), as a polynomial in P and the carried
// moments: 1 for g = 0 and for 2 <= |g| <= k (the moment's own variable), 0 for |g| = 1, and above k
// at most one per way to split g's factors into blocks of 2..k (a block of 2 is a P, of 3 an M3, of
// 4 an M4 or, through its cumulant, a pair of P's). At most: never below the real count, equal
// unless coefficients cancel. Exact up to `stop_above`; beyond it, some number above `stop_above`.
double closed_moment_terms(const std::vector<std::uint32_t>& g, unsigned order, double stop_above = kMaxClosureProducts);

// What a moment filter's derivation (moment_closure.hpp) starts from, and the fields it names.
struct ClosureInputs {
  unsigned order = 3;                   // k: central moments up to order k carried
  std::string kind;                     // "closure3", "closure4": named in the message
  std::vector<Polynomial> drift;        // f_i
  std::vector<Polynomial> observation;  // h_r as polynomials in the states (A0 + A x's rows too); empty without
  ExMatrix noise;                       // the observation's B (R = B B^T couples rows)
  std::string diffusion_field;          // "diffusion" or "diffusion_covariance"
  std::string observation_field;        // "observation.h" or "observation.A"
};

// The work of a moment filter's derivation, counted from the polynomials it starts from as
// moment_closure_terms takes them: the products of terms of E[e^b q] for each central moment's
// equation (q a drift row, a diffusion entry or an observation row, b the moment's indices less one
// or two), of E[f] and E[h] once, of C_b = E[e^b h] - mu_b E[h] once for each b, and of the rows'
// products in the gain and the correction; and n for each equation, the bookkeeping of its
// indices. Each E[e^b q] takes, for every term m^c e^d of q(m + e), the terms of E[e^(b+d)]
// (closed_moment_terms) and, the first time, the products of the recursion that computes it. The
// equations' terms are at most these products. Counting stops once the total is above `stop_above`.
struct ClosureWork {
  double drift = 0, diffusion = 0, observation = 0;  // each part's products
  double bookkeeping = 0;     // n for each equation
  double equations = 0;       // m, P and the higher moments: C(n + k, k) - 1
  unsigned moment_order = 0;  // the highest order of E[e^g] the equations read
  double total() const { return drift + diffusion + observation + bookkeeping; }
};
ClosureWork closure_derivation_work(const Model& model, const ClosureInputs& inputs,
                                    double stop_above = kMaxClosureProducts);

// Throws ModelError naming the field with the largest share (the drift, the diffusion or the
// observation) when closure_derivation_work is above kMaxClosureProducts.
void check_closure_budget(const Model& model, const ClosureInputs& inputs);

// A moment filter's update at samples through a polynomial c (observations/sampled/closure_sampled_update.hpp):
// each of its joint moments (ascending indices over z = (x - m, d), n + r entries) is the expectation of a product
// of factors e_i and d_a, whose terms read the closed law's moments up to order k deg c. Counts the products of
// terms (the product's terms, at most those of the c_a(m + e) it multiplies, times the terms of the largest moment
// read) and throws ModelError naming observation.sampled.c above kMaxClosureProducts, or when k deg c is above
// kMaxSampledMomentOrder.
// The highest order of the closed law's moments that update may read (k deg c).
inline constexpr unsigned kMaxSampledMomentOrder = 100;
void check_closure_samples_budget(const Model& model, unsigned order, const std::string& kind,
                                  const std::vector<Polynomial>& c,
                                  const std::vector<std::vector<std::size_t>>& joint_moments);

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
