// The delayed observation dy = (A0 + A x(t - h)) dt + B dW2 in the derivation (docs/theory.md
// §2.6): the delayed filter variables md = m(t - h), phi and xs (FilterVariables), the innovation
// dy - (A0 + A md) dt, and for the kinds with Basin, Rodriguez-Gonzalez & Martinez-Zuniga 2004's
// Phi* gain the gain P Phi A^T R^-1, the correction P Phi A^T R^-1 A Phi P and x*'s drift f(xs, t).
// The rate terms are the continuous module's (observation_terms).
#include "pfgen/derivation/derivation_budget.hpp"
#include "pfgen/derivation/observation_derivation.hpp"
#include "pfgen/observations/continuous/observation_terms.hpp"
#include "pfgen/observations/delayed/delayed_exactness.hpp"

namespace pfgen {
namespace {

class DelayedDerivation final : public ObservationDerivation {
 public:
  FilterVariables variables(std::size_t n) const override { return FilterVariables(n, true); }

  // The innovation compares dy with the prediction of x(t - h), m(t - h).
  void frame(const Model& model, FilterEquations& eq) const override {
    eq.predicted_observation = predicted_observation(*model.observation.rate().affine(), eq.variables, true);
    eq.delay = model.observation.delay();
  }

  std::size_t observed_states(const Model& model) const override {
    return pfgen::observed_states(model.observation.rate().affine()->A);
  }

  ExactnessReport exactness(const Model& model, FilterKind kind) const override {
    return delayed_exactness(model, kind);
  }

  void observation_terms(const Model& model, FilterKind kind, FilterEquations& eq) const override {
    const bool transition = uses_transition_gain(kind);
    const FilterVariables& vars = eq.variables;
    ObservationCorrection correction = observation_correction(*model.observation.rate().affine(), vars, transition);
    eq.gain = std::move(correction.gain);
    eq.P_correction = std::move(correction.P_correction);
    if (!transition) return;
    // x* solves dx*/dt = f(x*, t): the model's drift with state i read as xs_i.
    std::vector<std::uint32_t> as_x_star(vars.count());
    for (std::size_t i = 0; i < vars.n(); ++i) as_x_star[i] = vars.x_star(i);
    for (const auto& e : model.drift) eq.x_star_drift.push_back(Polynomial::from_ex(e, model.states).renumbered(as_x_star));
  }

  ObservationCoefficients coefficients(const Model& model) const override {
    ObservationCoefficients out;
    out.E = model.observation.rate().affine()->A0;
    out.E1 = model.observation.rate().affine()->A;
    return out;
  }
};

}  // namespace

const ObservationDerivation& delayed_observation_derivation() {
  static const DelayedDerivation part;
  return part;
}

}  // namespace pfgen
