// The sampled observation y_k = C0 + C x(t_k) + Uv v_k in the derivation: no observation term
// between samples (the equations are the prediction), the Kalman update's polynomial parts at each
// sample (sampled_update), for cd-euler the dt^2 term of its Euler moment map, and the prediction's
// sub-steps per period (substep_choice).
#include "pfgen/derivation/derivation_budget.hpp"
#include "pfgen/derivation/gaussian_expectation.hpp"
#include "pfgen/derivation/observation_derivation.hpp"
#include "pfgen/model/model_error.hpp"
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

// The samples' rate: C0 + C x when affine (the model room writes a c of degree <= 1 so), else the
// rows c, whose update takes their expectations.
class SampledDerivation final : public ObservationDerivation {
 public:
  FilterVariables variables(std::size_t n) const override { return FilterVariables(n); }

  void frame(const Model& model, FilterEquations& eq) const override {
    const std::optional<AffineRate>& affine = model.observation.rate().affine();
    if (!affine) {
      eq.update = polynomial_sampled_update(model, eq.variables, false, eq.predicted_observation);
      return;
    }
    eq.predicted_observation = predicted_sample(*affine, eq.variables);
    eq.update = sampled_update(*model.observation.samples(), *affine, eq.variables);
  }

  std::size_t observed_states(const Model& model) const override {
    const ObservationRate& rate = model.observation.rate();
    return rate.affine() ? pfgen::observed_states(rate.affine()->A)
                         : pfgen::observed_states(rate.polynomials(model.states), model.n());
  }

  ObservationPolynomials budget_polynomials(const Model& model) const override {
    if (model.observation.rate().affine()) return {};
    return {model.observation.rate().polynomials(model.states), "observation.sampled.c", true, {}};
  }

  ExactnessReport exactness(const Model& model, FilterKind kind) const override {
    return sampled_exactness(model, kind);
  }

  // Between samples there is no observation term; the update is eq.update (frame).
  void observation_terms(const Model& model, FilterKind kind, FilterEquations& eq) const override {
    eq.P_correction.assign(eq.P_moment.size(), Polynomial());
    // The extended kind's update of a polynomial c reads c(m) and J_c(m) (frame gave E[c]'s).
    if (!model.observation.rate().affine() && is_extended_kalman(kind))
      eq.update = polynomial_sampled_update(model, eq.variables, true, eq.predicted_observation);
    if (uses_euler_map(kind)) eq.P_euler = euler_square_term(model, eq.variables);
    set_prediction_substeps(model, eq);
  }

  // A sampled observation has no rate: its sample equation's C0 and C stand in the coefficient form.
  ObservationCoefficients coefficients(const Model& model) const override {
    const std::optional<AffineRate>& affine = model.observation.rate().affine();
    if (!affine) {
      ModelError error("observation.sampled.c", "the coefficient form's observation is linear, E + E1 x; c is not");
      error.set_file(model.source);
      throw error;
    }
    ObservationCoefficients out;
    out.E = affine->A0;
    out.E1 = affine->A;
    return out;
  }
};

}  // namespace

const ObservationDerivation& sampled_observation_derivation() {
  static const SampledDerivation part;
  return part;
}

}  // namespace pfgen
