// The continuous observation dy = (A0 + A x) dt + B dW2 in the derivation, the undelayed
// continuous timing with an affine rate (written so, or a linear h): the innovation
// dy - (A0 + A m) dt, the gain P A^T R^-1 and the correction P A^T R^-1 A P (observation_terms).
#include "pfgen/derivation/derivation_budget.hpp"
#include "pfgen/derivation/observation_derivation.hpp"
#include "pfgen/observations/continuous/continuous_exactness.hpp"
#include "pfgen/observations/continuous/observation_terms.hpp"

namespace pfgen {
namespace {

// The model's rate, written A0 + A x for the observation this module is for.
const AffineRate& rate_of(const Model& model) { return *model.observation.rate().affine(); }

class ContinuousDerivation final : public ObservationDerivation {
 public:
  FilterVariables variables(std::size_t n) const override { return FilterVariables(n); }

  void frame(const Model& model, FilterEquations& eq) const override {
    eq.predicted_observation = predicted_observation(rate_of(model), eq.variables);
  }

  std::size_t observed_states(const Model& model) const override {
    return pfgen::observed_states(rate_of(model).A);
  }

  ExactnessReport exactness(const Model& model, FilterKind kind) const override {
    return continuous_exactness(model, kind);
  }

  void observation_terms(const Model& model, FilterKind, FilterEquations& eq) const override {
    ObservationCorrection correction = observation_correction(rate_of(model), eq.variables);
    eq.gain = std::move(correction.gain);
    eq.P_correction = std::move(correction.P_correction);
  }

  ObservationCoefficients coefficients(const Model& model) const override {
    ObservationCoefficients out;
    out.E = rate_of(model).A0;
    out.E1 = rate_of(model).A;
    return out;
  }
};

}  // namespace

const ObservationDerivation& continuous_observation_derivation() {
  static const ContinuousDerivation part;
  return part;
}

}  // namespace pfgen
