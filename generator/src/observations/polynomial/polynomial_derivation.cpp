// The polynomial observation dy = h(x, t) dt + B dW2 of a nonlinear h in the derivation: the
// innovation dy - E[h] dt, the gain P E[J]^T R^-1, the correction and the covariance's own
// innovation term (polynomial_observation_terms), or for the extended kinds h(m) and J(m) without
// that term. A linear h is the affine rate's, the continuous module's (observation_derivation).
#include "pfgen/derivation/derivation_budget.hpp"
#include "pfgen/derivation/gaussian_expectation.hpp"
#include "pfgen/derivation/observation_derivation.hpp"
#include "pfgen/derivation/unscented.hpp"
#include "pfgen/model/model_error.hpp"
#include "pfgen/observations/polynomial/polynomial_observation.hpp"
#include "pfgen/observations/polynomial/polynomial_observation_terms.hpp"

namespace pfgen {
namespace {

// The ukf's observation terms (Sarkka 2007): sum_i w_i h(X_i), C = sum_i w_i (X_i - m) h(X_i)^T,
// gain C R^-1 and correction C R^-1 C^T; its P has no dy term.
PolynomialObservationTerms sigma_point_terms(const Model& model, const FilterEquations& eq) {
  const ObservationRate& rate = model.observation.rate();
  std::vector<Polynomial> predicted;
  std::vector<std::vector<Polynomial>> cross(model.n(), std::vector<Polynomial>(rate.p()));
  for (std::size_t r = 0; r < rate.p(); ++r) {
    SigmaPointMoments moments = sigma_point_moments(rate.rows()[r], model, eq.definitions);
    predicted.push_back(std::move(moments.mean));
    for (std::size_t a = 0; a < model.n(); ++a) cross[a][r] = std::move(moments.cross[a]);
  }
  return observation_terms_from_moments(std::move(predicted), cross, rate.noise());
}

class PolynomialDerivation final : public ObservationDerivation {
 public:
  FilterVariables variables(std::size_t n) const override { return FilterVariables(n); }

  // The Gaussian kinds' prediction E[h]; the extended kinds' h(m) replaces it (observation_terms).
  void frame(const Model& model, FilterEquations& eq) const override {
    GaussianExpectation E(eq.variables);
    for (const Polynomial& h : observation_polynomials(model)) eq.predicted_observation.push_back(E.of(h));
  }

  std::size_t observed_states(const Model& model) const override {
    return pfgen::observed_states(observation_polynomials(model), model.n());
  }

  ObservationPolynomials budget_polynomials(const Model& model) const override {
    return {observation_polynomials(model), "observation.h", false, model.observation.rate().noise()};
  }

  // A nonlinear h has no finite-dimensional optimal filter in general (the cubic sensor is the
  // classic case).
  ExactnessReport exactness(const Model& model, FilterKind kind) const override {
    ExactnessReport out;
    out.condition = "none";
    const std::string unknown = "for a nonlinear observation (h has degree " + std::to_string(observation_degree(model)) +
                                ") no finite-dimensional optimal filter is known (the cubic sensor $dy = x^3 dt + "
                                "...|dy = x^{3}\\,dt + \\ldots$ is the classic case)";
    out.explanation = is_extended_kalman(kind)
                          ? "approximation: the extended Kalman-Bucy filter reads $f|f$, $g|g$ and $h|h$ at $m|m$ and "
                            "linearises them there; " + unknown
                          : "approximation: " + unknown + ", so this filter is a Gaussian assumed-density approximation";
    return out;
  }

  void observation_terms(const Model& model, FilterKind kind, FilterEquations& eq) const override {
    const ObservationRate& rate = model.observation.rate();
    // The ukf sends h through its sigma points.
    PolynomialObservationTerms terms =
        uses_sigma_points(kind)
            ? sigma_point_terms(model, eq)
            : polynomial_observation_terms(observation_polynomials(model), rate.noise(), eq.variables,
                                           is_extended_kalman(kind));
    eq.predicted_observation = std::move(terms.predicted_observation);
    eq.gain = std::move(terms.gain);
    eq.P_correction = std::move(terms.P_correction);
    // Only where dP has a dy term: the extended kinds and the ukf have none.
    if (!is_extended_kalman(kind) && !uses_sigma_points(kind))
      eq.P_gain = std::move(terms.P_gain);
  }

  // The coefficient form's observation is linear: a linear h is the continuous module's part.
  ObservationCoefficients coefficients(const Model& model) const override {
    ModelError error("observation.h", "the coefficient form's observation is linear, E + E1 x; h has degree " +
                                          std::to_string(observation_degree(model)));
    error.set_file(model.source);
    throw error;
  }
};

}  // namespace

const ObservationDerivation& polynomial_observation_derivation() {
  static const PolynomialDerivation part;
  return part;
}

}  // namespace pfgen
