#pragma once
// What the derivation needs of an observation model: its part of every filter's equations. One
// implementation per value of the axes that change the equations (observations/<kind>/
// <kind>_derivation): samples (with either rate), a delay (of an affine rate), and for the
// undelayed continuous timing one per rate, A0 + A x's exact terms or a polynomial h's
// expectations. observation_derivation() composes them from the axes once; derive_filter and the
// exactness diagnostic call the part it gives and never ask the axes themselves.
#include <cstddef>

#include "pfgen/derivation/derivation_budget.hpp"
#include "pfgen/derivation/drift_coefficients.hpp"
#include "pfgen/derivation/exactness.hpp"
#include "pfgen/derivation/filter_equations.hpp"

namespace pfgen {

class ObservationDerivation {
 public:
  virtual ~ObservationDerivation() = default;

  // The filter variables: m and P, and after them those this observation's filters read besides.
  virtual FilterVariables variables(std::size_t n) const = 0;
  // What every filter of the model shares, built-in or user-defined: the predicted observation and
  // the observation's own data in FilterEquations (a sampled one's update, a delayed one's h).
  virtual void frame(const Model& model, FilterEquations& eq) const = 0;
  // The states the observation sees: its correction has one term per pair of them (the derivation
  // budget counts them before deriving).
  virtual std::size_t observed_states(const Model& model) const = 0;
  // The polynomials whose expectations the observation's terms take, for the derivation budget
  // (check_observation_budget): a polynomial h or sampled c; none for a linear observation.
  virtual ObservationPolynomials budget_polynomials(const Model&) const { return {}; }
  // The exactness diagnostic of a Gaussian-closure kind (the risk-sensitive and unscented kinds
  // have their own, exactness.cpp).
  virtual ExactnessReport exactness(const Model& model, FilterKind kind) const = 0;
  // A built-in kind's observation terms, after its moment terms are in `eq`: gain and correction,
  // or what stands for them.
  virtual void observation_terms(const Model& model, FilterKind kind, FilterEquations& eq) const = 0;
  // The observation's linear terms in the coefficient form (derive --coefficients); `kind` is set
  // by the caller.
  virtual ObservationCoefficients coefficients(const Model& model) const = 0;
};

// The parts (observations/<kind>/<kind>_derivation.cpp), and the model's, from its axes.
const ObservationDerivation& continuous_observation_derivation();  // continuous timing, affine rate
const ObservationDerivation& polynomial_observation_derivation();  // continuous timing, nonlinear rate
const ObservationDerivation& sampled_observation_derivation(const ObservationRate& rate);  // samples
const ObservationDerivation& delayed_observation_derivation();     // continuous timing, a delay
const ObservationDerivation& observation_derivation(const ObservationModel& observation);

}  // namespace pfgen
