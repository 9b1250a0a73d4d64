// The polynomial observation dy = h(x, t) dt + B dW2 in the derivation: the innovation
// dy - E[h] dt, the gain P E[J]^T R^-1, the correction and the covariance's own innovation term
// (polynomial_observation_terms), or for the extended kinds h(m) and J(m) without that term.
#include "pfgen/derivation/gaussian_expectation.hpp"
#include "pfgen/derivation/observation_derivation.hpp"
#include "pfgen/model/model_error.hpp"
#include "pfgen/observations/continuous/continuous_exactness.hpp"
#include "pfgen/observations/polynomial/polynomial_observation.hpp"
#include "pfgen/observations/polynomial/polynomial_observation_terms.hpp"

namespace pfgen {
namespace {

class PolynomialDerivation final : public ObservationDerivation {
 public:
  FilterVariables variables(std::size_t n) const override { return FilterVariables(n); }

  // The Gaussian kinds' prediction E[h]; the extended kinds' h(m) replaces it (observation_terms).
  void frame(const Model& model, FilterEquations& eq) const override {
    GaussianExpectation E(eq.variables);
    for (const Polynomial& h : observation_polynomials(model)) eq.predicted_observation.push_back(E.of(h));
  }

  std::size_t observed_states(const Model& model) const override {
    std::vector<bool> read(model.n(), false);
    for (const Polynomial& h : observation_polynomials(model))
      for (const auto& [monomial, coefficient] : h.terms())
        for (const auto& [variable, exponent] : monomial.factors()) read[variable] = true;
    return static_cast<std::size_t>(std::count(read.begin(), read.end(), true));
  }

  // A linear h is the continuous observation, with its exactness conditions; a nonlinear one has
  // no finite-dimensional optimal filter in general (the cubic sensor is the classic case).
  ExactnessReport exactness(const Model& model, FilterKind kind) const override {
    if (std::optional<ContinuousObservation> linear = linear_form(model)) {
      Model written_linear = model;
      written_linear.observation = *linear;
      return continuous_exactness(written_linear, kind);
    }
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
    PolynomialObservationTerms terms = polynomial_observation_terms(
        observation_polynomials(model), model.observation.polynomial().B, eq.variables, is_extended_kalman(kind));
    eq.predicted_observation = std::move(terms.predicted_observation);
    eq.gain = std::move(terms.gain);
    eq.P_correction = std::move(terms.P_correction);
    // Only where dP has a dy term: a linear h's filters are the continuous observation's, field
    // for field, and the extended kinds have none.
    if (!is_extended_kalman(kind) && observation_degree(model) > 1) eq.P_gain = std::move(terms.P_gain);
  }

  ObservationCoefficients coefficients(const Model& model) const override {
    const std::optional<ContinuousObservation> linear = linear_form(model);
    if (!linear) {
      ModelError error("observation.h", "the coefficient form's observation is linear, E + E1 x; h has degree " +
                                            std::to_string(observation_degree(model)));
      error.set_file(model.source);
      throw error;
    }
    ObservationCoefficients out;
    out.E = linear->A0;
    out.E1 = linear->A;
    return out;
  }
};

}  // namespace

const ObservationDerivation& polynomial_observation_derivation() {
  static const PolynomialDerivation part;
  return part;
}

}  // namespace pfgen
