// The continuous observation in `pfgen eval`: its filters read t, m and P only; their values are
// m's drift, the gain (before the P drift: the order of the checks, so of the first message at a
// point where several values are not finite) and P's drift.
#include "pfgen/evaluation/observation_evaluation.hpp"
#include "pfgen/evaluation/polynomial_evaluator.hpp"

namespace pfgen {
namespace {

class ContinuousEvaluation final : public ObservationEvaluation {
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
    return out;
  }
};

}  // namespace

const ObservationEvaluation& continuous_observation_evaluation() {
  static const ContinuousEvaluation part;
  return part;
}

}  // namespace pfgen
