// Sampled observations y_k = c(x(t_k)) + Uv v_k in the derivation: no observation term between
// samples (the equations are the prediction), for cd-euler the dt^2 term of its Euler moment map,
// the prediction's sub-steps per period (substep_choice), and at each sample the update of the
// rate: the Kalman update's polynomial parts for C0 + C x (sampled_update), or the moment-matching
// update of a polynomial c (polynomial_sampled_update; a moment filter's closure_sampled_update). One class per rate, chosen once
// (sampled_observation_derivation).
#include "pfgen/derivation/derivation_budget.hpp"
#include "pfgen/derivation/gaussian_expectation.hpp"
#include "pfgen/derivation/observation_derivation.hpp"
#include "pfgen/model/model_error.hpp"
#include "pfgen/observations/sampled/closure_sampled_update.hpp"
#include "pfgen/observations/sampled/sampled_exactness.hpp"
#include "pfgen/observations/sampled/sampled_update.hpp"
#include "pfgen/observations/sampled/substep_choice.hpp"

namespace pfgen {
namespace {

// Cov(f)_ij = E[f_i f_j] - E[f_i] E[f_j] under x ~ N(m, P), upper triangle: the dt^2 term of the
// covariance of one Euler step x + f(x) dt + g(x) sqrt(dt) xi (docs/theory.md). The cross term
// E[(x - m + f dt - E[f] dt) g sqrt(dt) xi] vanishes because xi is independent of x with mean 0.
std::vector<Polynomial> euler_square_term(const Model& model, const FilterVariables& vars) {
  std::vector<Polynomial> f;
  for (const auto& e : model.drift) f.push_back(Polynomial::from_ex(e, model.states));
  GaussianExpectation E(vars);
  std::vector<Polynomial> Ef;
  for (const auto& fi : f) Ef.push_back(E.of(fi));
  std::vector<Polynomial> out;
  for (std::size_t i = 0; i < f.size(); ++i)
    for (std::size_t j = i; j < f.size(); ++j) out.push_back(E.of(f[i] * f[j]) - Ef[i] * Ef[j]);
  return out;
}

// What samples mean whatever their rate: no observation term between samples, the prediction's
// Euler term and sub-steps. The update is the rate's part (the two classes below).
class SampledTiming : public ObservationDerivation {
 public:
  FilterVariables variables(std::size_t n) const override { return FilterVariables(n); }

  ExactnessReport exactness(const Model& model, FilterKind kind) const override {
    return sampled_exactness(model, kind, nonlinear_samples());
  }

  // Between samples there is no observation term; the update is eq.update (frame).
  void observation_terms(const Model& model, FilterKind kind, FilterEquations& eq) const override {
    eq.P_correction.assign(eq.P_moment.size(), Polynomial());
    update_terms(model, kind, eq);
    if (uses_euler_map(kind)) eq.P_euler = euler_square_term(model, eq.variables);
    set_prediction_substeps(model, eq);
  }

 protected:
  // What a built-in kind changes in the update frame() made.
  virtual void update_terms(const Model&, FilterKind, FilterEquations&) const {}
  // Why the rate keeps the samples from being exact, empty when it does not.
  virtual std::string nonlinear_samples() const { return {}; }
};

// Samples through C0 + C x (a c of degree <= 1 is written so when the model is built).
class AffineSamples final : public SampledTiming {
 public:
  void frame(const Model& model, FilterEquations& eq) const override {
    const AffineRate& rate = *model.observation.rate().affine();
    eq.predicted_observation = predicted_sample(rate, eq.variables);
    eq.update = sampled_update(*model.observation.samples(), rate, eq.variables);
  }

  std::size_t observed_states(const Model& model) const override {
    return pfgen::observed_states(model.observation.rate().affine()->A);
  }

  // A sampled observation has no rate: its sample equation's C0 and C stand in the coefficient form.
  ObservationCoefficients coefficients(const Model& model) const override {
    ObservationCoefficients out;
    out.E = model.observation.rate().affine()->A0;
    out.E1 = model.observation.rate().affine()->A;
    return out;
  }
};

// Samples through polynomials c of degree >= 2: the update takes their expectations.
class PolynomialSamples final : public SampledTiming {
 public:
  void frame(const Model& model, FilterEquations& eq) const override {
    eq.update = polynomial_sampled_update(model, eq.variables, false, eq.predicted_observation);
  }

  std::size_t observed_states(const Model& model) const override {
    return pfgen::observed_states(model.observation.rate().polynomials(model.states), model.n());
  }

  ObservationPolynomials budget_polynomials(const Model& model) const override {
    return {model.observation.rate().polynomials(model.states), "observation.sampled.c", true, {}};
  }

  ObservationCoefficients coefficients(const Model& model) const override {
    ModelError error("observation.sampled.c", "the coefficient form's observation is linear, E + E1 x; c is not");
    error.set_file(model.source);
    throw error;
  }

 protected:
  // A polynomial c of degree >= 2: x given the samples is not Gaussian even for a linear system.
  std::string nonlinear_samples() const override { return "the samples' c is not linear in the states"; }
  // The extended kind's update reads c(m) and J_c(m), a moment filter's the moments of its closed law (frame gave
  // the Gaussian law's).
  void update_terms(const Model& model, FilterKind kind, FilterEquations& eq) const override {
    if (is_extended_kalman(kind)) eq.update = polynomial_sampled_update(model, eq.variables, true, eq.predicted_observation);
    if (uses_cumulant_closure(kind)) eq.update = closure_sampled_update(model, eq.variables, filter_kind_name(kind), eq.predicted_observation);
  }
};

}  // namespace

const ObservationDerivation& sampled_observation_derivation(const ObservationRate& rate) {
  static const AffineSamples affine;
  static const PolynomialSamples polynomial;
  if (rate.affine()) return affine;
  return polynomial;
}

}  // namespace pfgen
