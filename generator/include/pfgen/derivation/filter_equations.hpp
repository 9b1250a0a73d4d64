#pragma once
// The closed equations of one filter for one model, with continuous observations:
//   dm = m_drift dt + gain (dy - predicted_observation dt),   predicted_observation = A0 + A m
//   dP = (P_moment + P_diffusion - P_correction) dt
// For a built-in kind, P_moment = E[(x-m)f^T] + E[f(x-m)^T] (or its EKF form),
// P_diffusion = E[g g^T] (or g(m)g(m)^T, or the additive G), P_correction =
// P A^T R^-1 A P. A user filter (the model file's `filters:`) is not split into
// parts: its P drift, as given, is P_moment, the other two parts are zero and it
// has no jacobian_term. P entries are stored as the upper triangle, row by row
// (FilterVariables).
// With sampled observations (the cd-* kinds) the same fields hold the prediction between
// samples, without an observation term (gain empty, P_correction zero):
//   dm = m_drift dt, dP = P_drift dt                      (cd-optimal, cd-ekf: integrated)
//   m' = m + m_drift dt, P' = P + P_drift dt + P_euler dt^2 (cd-euler: one Euler sub-step dt)
// and `update` holds the Kalman update at each sample (observations/sampled/sampled_update.hpp).
// With delayed observations (the delay-* kinds, and user filters of such a model; docs/theory.md
// §2.6) the form is the continuous one, with the delayed filter variables (FilterVariables):
//   predicted_observation = A0 + A md, md = m(t - h), read from the filter's history;
//   delay-optimal: gain = P Phi A^T R^-1 and P_correction = P Phi A^T R^-1 A Phi P, Phi = diag(phi),
//   phi_i = xs_i(t - h) / xs_i(t) (0 where xs_i(t) = 0, and for t < h), and xs integrates
//   x_star_drift = f(xs) from xs(0) = m0 beside m and P.
// What differs between the observation models is each one's module (observations/<kind>/; its part
// of the derivation: derivation/observation_derivation.hpp); consumers reach the module of
// `observation` through their own room's interface, never by testing the kind.
#include <optional>
#include <string>
#include <vector>

#include "pfgen/algebra/polynomial.hpp"
#include "pfgen/derivation/exactness.hpp"
#include "pfgen/derivation/filter_variables.hpp"
#include "pfgen/derivation/sampled_update_parts.hpp"
#include "pfgen/kinds/filter_kinds.hpp"
#include "pfgen/model/model.hpp"
#include "pfgen/model/model_filters.hpp"

namespace pfgen {

// The state polynomials whose Gaussian expectations a Gaussian-closure kind's equations are:
// m_drift = E[drift], jacobian_term[j][k] = E[jacobian(j, k)], P_diffusion = E[diffusion_upper].
// Over the states: variable i is x_i, which has m_i's index in FilterVariables. The Jacobian is
// taken when asked, not held: every filter carries these, and at dense cubic n = 20 its n x n
// entries were most of their 15 MB, which only code generation reads.
struct ExpectationSources {
  std::vector<Polynomial> drift;                    // f, n
  std::vector<Polynomial> diffusion_upper;          // G = g g^T (or the additive G), upper triangle
  Polynomial jacobian(std::size_t j, std::size_t k) const {  // d_k f_j
    return drift[j].derivative(static_cast<std::uint32_t>(k));
  }
};

struct FilterEquations {
  std::string name;          // the kind's name ("ekf-additive") or the user filter's
  std::string description;   // one line of rich text (notation/rich_text.hpp): the kind's description or the user filter's
  std::optional<FilterKind> kind;  // empty for a user filter
  ObservationKind observation = ObservationKind::Continuous;  // the model's, which the equations are for
  FilterVariables variables;
  std::size_t p = 0;
  std::vector<Polynomial> m_drift;              // n
  std::vector<std::vector<Polynomial>> gain;    // n x p
  // What the filter predicts the observation rate to be, A0 + A m (p entries): the innovation
  // is dy - predicted_observation dt. Derived once here; printers and emitters read it.
  std::vector<Polynomial> predicted_observation;
  // The matrix standing for the Jacobian: E[d_k f_j] (optimal, additive) or
  // d_k f_j at m (EKF kinds), entry [j][k]; P_moment_ij = sum_k P_ik J_jk + J_ik P_kj.
  // Kept so that code generation can compute P_moment from it, sharing its entries.
  // Empty for a user filter.
  std::vector<std::vector<Polynomial>> jacobian_term;  // n x n
  // Set by the kinds whose m_drift, jacobian_term and P_diffusion are Gaussian expectations (not
  // the EKF kinds): what they are expectations of, so that code generation can write each as a
  // sum over shared moments E[x^a] (codegen/moment_form.hpp).
  std::optional<ExpectationSources> expectation_sources;
  std::vector<Polynomial> P_moment;             // n(n+1)/2, upper triangle
  std::vector<Polynomial> P_diffusion;          // n(n+1)/2
  std::vector<Polynomial> P_correction;         // n(n+1)/2, subtracted
  ExactnessReport exactness;
  // cd-euler only (else empty): Cov(f) = E[f f^T] - E[f] E[f]^T, upper triangle, the dt^2 term of
  // the exact covariance of x + f dt + g sqrt(dt) xi.
  std::vector<Polynomial> P_euler;
  SampledUpdate update;  // sampled observations only (update.r() == 0 otherwise)
  // Polynomial observations only (empty otherwise): dP_ij gains sum_r P_gain[u][r] (dy_r -
  // predicted_observation_r dt), u = upper_index(i, j): the covariance's own innovation term
  // sum_k P E[H_k] P (R^-1)_kr (observations/polynomial/polynomial_observation_terms.hpp).
  std::vector<std::vector<Polynomial>> P_gain;
  // The moment filters only (the closure kinds; empty otherwise): each central moment of order >= 3's
  // dt coefficient and (continuous observations) its coefficients of dy_r - predicted_observation_r dt, in
  // FilterVariables::higher_moments() order (derivation/moment_closure.hpp). Their P_gain is set for a
  // linear observation too.
  std::vector<Polynomial> higher_drift;
  std::vector<std::vector<Polynomial>> higher_gain;
  // The moment filters only: the realisability margins, each positive while the moment state can be a law's
  // (moment_closure.hpp, realisability_margins), with what each says.
  std::vector<Polynomial> realisability;
  std::vector<std::string> realisability_meaning;
  // Delayed observations only: the delay h (0 otherwise), and for the kinds with the Phi* gain the
  // drift f(xs, t) of the noise-free solution xs, n entries (empty otherwise).
  GiNaC::numeric delay = 0;
  std::vector<Polynomial> x_star_drift;
  // The risk-sensitive kind only: the model's criterion (epsilon and M), for the reports.
  std::optional<RiskCriterion> risk;
  // A user filter's auxiliary names (`define:`), in file order, or the ukf's Cholesky factor L of P
  // (derivation/unscented.hpp), entry by entry. Their symbols may appear in the
  // coefficients of every polynomial above; each value reads the filter variables as
  // variables.symbols(), the parameters, t and the names before it. Evaluators and emitters
  // compute them in this order before anything that reads them; printers list them.
  std::vector<FilterDefinition> definitions;

  std::size_t n() const { return variables.n(); }
  bool is_user_filter() const { return !kind.has_value(); }
  bool uses_x_star() const { return !x_star_drift.empty(); }
  // The dt-coefficient of dP_ij, all parts combined (i, j in either order).
  Polynomial P_drift(std::size_t i, std::size_t j) const;
};

// Derives the filter; throws std::invalid_argument if the model lacks what the
// kind needs (unsupported_reason: an additive kind without additive_diffusion).
FilterEquations derive_filter(const Model& model, FilterKind kind);

// A user filter's equations as FilterEquations (not derived: converted to polynomials
// in the filter variables). Exactness: not exact, condition "user-defined".
FilterEquations derive_user_filter(const Model& model, const UserFilter& filter);

// The built-in kind or user filter of that name; throws std::invalid_argument if the
// model offers no filter of that name (available_filter_names, model/model_filters.hpp).
FilterEquations derive_named_filter(const Model& model, const std::string& name);

}  // namespace pfgen
