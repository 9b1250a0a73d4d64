#pragma once
// The one table of pfgen's built-in filter kinds. Every list of kind names is read from it: the
// model validator's (user filter names, simulation.filters), the command line's help texts and
// checks, the default filters of derive/latex/codegen/simulate, and the tests;
// tests/test_kind_registry.cpp fails if any list, or the table of docs/guide/filter-kinds.md, disagrees with it.
// The two axes say how a kind's equations are formed (derivation/filter_equations.cpp reads
// them); adding a kind is a row here, and DESIGN.md's recipe says what else changes.
#include <optional>
#include <string>
#include <vector>

#include "pfgen/kinds/observation_kinds.hpp"

namespace pfgen {

enum class FilterKind { Optimal, Ekf, Additive, EkfAdditive, CdOptimal, CdEkf, CdEuler, DelayOptimal, DelayUncorrected, DelayEkf,
                        RiskSensitive, Ukf, Closure3, Closure4, CdClosure3, CdClosure4 };

// How a kind takes the expectations of f, of its Jacobian and of g g^T.
enum class ExpectationRule {
  Gaussian,  // E[.] over x ~ N(m, P), expanded exactly: the Gaussian closure
  AtMean,    // evaluated at x = m: the extended Kalman-Bucy filter
  SigmaPoints,  // a weighted sum over the 2n+1 sigma points m, m +- sqrt(c) L_j (L L^T = P): the unscented
                // Kalman-Bucy filter (derivation/unscented.hpp, docs/theory.md §2.8)
  CumulantNeglect,  // the moment filter of order k (closure_order): m and the central moments of orders 2..k
                    // carried, every cumulant of order > k set to zero (derivation/moment_closure.hpp, §2.10)
};

// Which diffusion a kind puts into its P equation.
enum class DiffusionSource {
  Model,     // the model's g (or G = g g^T), which may depend on the states
  Additive,  // the model's constant additive_diffusion, which the model file must give
};

// How a sampled-observation kind moves m and P between samples (continuous kinds: Ode).
enum class Prediction {
  Ode,       // the closed moment ODEs dm = E[f] dt, dP = (...) dt, integrated over the sub-steps
  EulerMap,  // the exact moments of one Euler step x + f dt + g sqrt(dt) xi: adds Cov(f) dt^2
};

// How a delayed-observation kind forms its gain (other kinds: Undelayed). The innovation of every
// delayed kind is dy - (A0 + A m(t - h)) dt (docs/theory.md §2.6).
enum class DelayGain {
  // P A^T R^-1, as if the observation were not delayed (Basin, Rodriguez-Gonzalez & Martinez-Zuniga
  // 2004, eqs 19-20)
  Undelayed,
  // P Phi*^T A^T R^-1, Phi* = diag(x*(t - h) / x*(t)) from the noise-free x* (the same, eq 6)
  Transition,
};

// What a kind's estimate is optimal for (docs/theory.md §2.7).
enum class Criterion {
  MeanSquare,     // E|x - m|^2: m approximates the conditional mean
  RiskSensitive,  // J = eps log E exp(eps^-1 int (x - m)^T M (x - m) dt): the model's `risk:` section; m is the
                  // centre of the risk-sensitive information state, expanded to second order about it
};

struct FilterKindInfo {
  FilterKind kind;
  std::string name;         // the --filter name, and (with '-' as '_') the generated code's
  std::string description;  // one line of rich text (notation/rich_text.hpp): $plain|latex$ math spans
  ExpectationRule expectation;
  DiffusionSource diffusion;
  std::vector<ObservationKind> observations;  // the observation models it is derived for
  Prediction prediction = Prediction::Ode;
  DelayGain delay_gain = DelayGain::Undelayed;
  Criterion criterion = Criterion::MeanSquare;
  // Whether derive/latex/codegen/simulate include the kind when no filter is named. The ukf is a
  // comparator one asks for (`--filter ukf`): adding it to every default would change every
  // default output and the checked-in generated/ code.
  bool in_defaults = true;
  // The highest order of central moment the filter carries: 2 (m and P) but for the moment filters.
  unsigned closure_order = 2;
};

// Every built-in kind, in the canonical order in which commands list and default to them.
const std::vector<FilterKindInfo>& filter_kinds();
const FilterKindInfo& filter_kind_info(FilterKind kind);
std::optional<FilterKind> parse_filter_kind(const std::string& name);
std::vector<std::string> filter_kind_names();  // canonical order

// What a model must offer for a kind, as plain facts (the model room supplies them).
struct FilterKindNeeds {
  bool has_additive_diffusion = false;
  ObservationKind observation = ObservationKind::Continuous;
  bool has_risk_criterion = false;         // the model file's `risk:` section
  bool state_independent_diffusion = false;  // g (or G) free of the states
  unsigned drift_degree = 0;               // the highest total degree of a drift entry in the states
  unsigned drift_degree_row = 0;           // 1-based row of the first entry of that degree
  bool prior_positive_definite = true;     // initial.P0 (when given) positive definite
};
// The risk-sensitive kind is derived for drifts of degree <= 3 (the second- and third-degree systems
// of Alcorta-Garcia et al. 2011; the construction's dropped terms grow with the degree).
inline constexpr unsigned kRiskSensitiveMaxDegree = 3;
// Why the kind cannot be derived for such a model ("needs additive_diffusion or ..."), or
// nothing when it can.
std::optional<std::string> unsupported_reason(const FilterKindInfo& kind, const FilterKindNeeds& model);

// Convenience readings of the table.
inline const std::string& filter_kind_name(FilterKind kind) { return filter_kind_info(kind).name; }
inline const std::string& filter_kind_description(FilterKind kind) { return filter_kind_info(kind).description; }
inline bool uses_additive_diffusion(FilterKind kind) {
  return filter_kind_info(kind).diffusion == DiffusionSource::Additive;
}
inline bool is_extended_kalman(FilterKind kind) { return filter_kind_info(kind).expectation == ExpectationRule::AtMean; }
inline bool uses_sigma_points(FilterKind kind) { return filter_kind_info(kind).expectation == ExpectationRule::SigmaPoints; }
inline bool uses_euler_map(FilterKind kind) { return filter_kind_info(kind).prediction == Prediction::EulerMap; }
inline bool uses_transition_gain(FilterKind kind) { return filter_kind_info(kind).delay_gain == DelayGain::Transition; }
inline bool uses_cumulant_closure(FilterKind kind) {
  return filter_kind_info(kind).expectation == ExpectationRule::CumulantNeglect;
}
inline bool is_risk_sensitive(FilterKind kind) { return filter_kind_info(kind).criterion == Criterion::RiskSensitive; }

}  // namespace pfgen
