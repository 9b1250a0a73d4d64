// The sampled observation in `pfgen eval`: its filters read t, m and P only; their values are the
// prediction's (m and P drifts, cd-euler's dt^2 term) and the update's S = C P C^T + R and
// K = P C^T S^-1, formed exactly (GiNaC's rational matrix inverse) and rounded once.
#include "pfgen/evaluation/observation_evaluation.hpp"
#include "pfgen/evaluation/polynomial_evaluator.hpp"

namespace pfgen {
namespace {

void evaluate_update(const FilterEquations& eq, const PolynomialEvaluator& value, EvaluatedFilter& out) {
  const std::size_t n = eq.n();
  const SampledUpdate& u = eq.update;
  const std::size_t r = u.r();
  if (!eq.P_euler.empty()) {
    out.P_dt2.assign(n, std::vector<double>(n));
    for (std::size_t i = 0; i < n; ++i)
      for (std::size_t j = i; j < n; ++j)
        out.P_dt2[i][j] = out.P_dt2[j][i] = value(eq.P_euler[eq.variables.upper_index(i, j)], entry_name("P_dt2", i, j));
  }
  GiNaC::matrix S(static_cast<unsigned>(r), static_cast<unsigned>(r));
  GiNaC::matrix PCt(static_cast<unsigned>(n), static_cast<unsigned>(r));
  out.innovation_covariance.assign(r, std::vector<double>(r));
  for (unsigned a = 0; a < r; ++a)
    for (unsigned b = 0; b < r; ++b) {
      S(a, b) = value.exact(u.S[u.upper_index(a, b)]);
      out.innovation_covariance[a][b] = PolynomialEvaluator::rounded(S(a, b), entry_name("innovation_covariance", a, b));
    }
  for (unsigned i = 0; i < n; ++i)
    for (unsigned a = 0; a < r; ++a) PCt(i, a) = value.exact(u.PCt[i][a]);
  GiNaC::matrix S_inverse;
  try {
    S_inverse = S.inverse();
  } catch (const std::exception&) {
    throw EvaluationError("the innovation covariance C P C^T + Uv Uv^T is singular at this point");
  }
  const GiNaC::matrix K = PCt.mul(S_inverse);
  out.gain.assign(n, std::vector<double>(r));
  for (unsigned i = 0; i < n; ++i)
    for (unsigned a = 0; a < r; ++a) out.gain[i][a] = PolynomialEvaluator::rounded(K(i, a), entry_name("gain", i, a));
}

class SampledEvaluation final : public ObservationEvaluation {
 public:
  void check_inputs(const Model& model, const FilterEquations& eq, const EvaluationPoint& point) const override {
    refuse_delayed_inputs(model, eq, point);
  }

  // The prediction, then the update.
  EvaluatedFilter evaluate(const Model& model, const FilterEquations& eq, const EvaluationPoint& point) const override {
    const PolynomialEvaluator value(model, eq, point, {});
    EvaluatedFilter out;
    evaluate_m_drift(eq, value, out);
    evaluate_P_drift(eq, value, out);
    evaluate_update(eq, value, out);
    return out;
  }
};

}  // namespace

const ObservationEvaluation& sampled_observation_evaluation() {
  static const SampledEvaluation part;
  return part;
}

}  // namespace pfgen
