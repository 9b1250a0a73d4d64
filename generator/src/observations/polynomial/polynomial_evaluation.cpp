// The polynomial observation in `pfgen eval`: its filters read t, m and P only; their values are
// m's drift, the gain, P's drift, the predicted observation E[h] (h(m) for the extended kinds) and
// dP's coefficients of dy - E[h] dt, per observation.
#include "pfgen/evaluation/observation_evaluation.hpp"
#include "pfgen/evaluation/polynomial_evaluator.hpp"

namespace pfgen {
namespace {

class PolynomialEvaluation final : public ObservationEvaluation {
 public:
  void check_inputs(const Model& model, const FilterEquations& eq, const EvaluationPoint& point) const override {
    refuse_delayed_inputs(model, eq, point);
  }

  EvaluatedFilter evaluate(const Model& model, const FilterEquations& eq, const EvaluationPoint& point) const override {
    const PolynomialEvaluator value(model, eq, point, {});
    EvaluatedFilter out;
    evaluate_m_drift(eq, value, out);
    evaluate_gain(eq, value, out);
    evaluate_P_drift(eq, value, out);
    for (std::size_t r = 0; r < eq.p; ++r)
      out.predicted_observation.push_back(value(eq.predicted_observation[r], "predicted_observation[" + std::to_string(r + 1) + "]"));
    const std::size_t n = eq.n();
    for (std::size_t r = 0; r < eq.p && !eq.P_gain.empty(); ++r) {
      std::vector<std::vector<double>> L(n, std::vector<double>(n));
      for (std::size_t i = 0; i < n; ++i)
        for (std::size_t j = i; j < n; ++j)
          L[i][j] = L[j][i] =
              value(eq.P_gain[eq.variables.upper_index(i, j)][r], entry_name("P_gain", i, j) + " of observation " +
                                                                      std::to_string(r + 1));
      out.P_gain.push_back(std::move(L));
    }
    return out;
  }
};

}  // namespace

const ObservationEvaluation& polynomial_observation_evaluation() {
  static const PolynomialEvaluation part;
  return part;
}

}  // namespace pfgen
