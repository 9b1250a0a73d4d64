// The sampled observation in `pfgen eval`: its filters read t, m and P only; their values are the
// prediction's (m and P drifts, cd-euler's dt^2 term) and the update's S = C P C^T + R and
// K = P C^T S^-1, formed exactly (GiNaC's rational matrix inverse) and rounded once.
#include <map>

#include "pfgen/evaluation/observation_evaluation.hpp"
#include "pfgen/evaluation/polynomial_evaluator.hpp"
#include "pfgen/observations/sampled/sampled_moment_update.hpp"

namespace pfgen {
namespace {

// A moment filter's higher moments after the update (sampled_moment_update.hpp), exactly, then rounded once: A = I - K C
// applied to the prior's moments, or with samples through a polynomial c Abar = [A, -K] to z's (closure_sampled_update).
void evaluate_moment_update(const FilterEquations& eq, const PolynomialEvaluator& value, const EvaluationPoint& point,
                            const GiNaC::matrix& K, EvaluatedFilter& out) {
  const FilterVariables& vars = eq.variables;
  const SampledUpdate& u = eq.update;
  const std::size_t n = eq.n(), r = u.r(), columns = u.closed_law ? n + r : n;
  auto num = [](const GiNaC::ex& e) { return GiNaC::ex_to<GiNaC::numeric>(e); };
  // C (r x n) and R (r x r) at the point, each entry evaluated once.
  NumericMatrix C(r, std::vector<GiNaC::numeric>(n)), R(r, std::vector<GiNaC::numeric>(r));
  for (unsigned b = 0; b < r; ++b) {
    for (unsigned j = 0; j < n; ++j) C[b][j] = num(value.exact(u.C[b][j], entry_name("C", b, j)));
    for (unsigned c = 0; c < r; ++c) R[b][c] = num(value.exact(u.R[u.upper_index(b, c)], entry_name("R", b, c)));
  }
  NumericMatrix A(n, std::vector<GiNaC::numeric>(columns)), Q(n, std::vector<GiNaC::numeric>(n, 0));
  for (unsigned i = 0; i < n; ++i) {
    for (unsigned j = 0; j < n; ++j) {
      GiNaC::numeric a = i == j ? 1 : 0;
      for (unsigned b = 0; b < r; ++b) a -= num(K(i, b)) * C[b][j];
      A[i][j] = a;
      for (unsigned b = 0; b < r; ++b)
        for (unsigned c = 0; c < r; ++c) Q[i][j] += num(K(i, b)) * R[b][c] * num(K(j, c));
    }
    for (unsigned b = 0; b < columns - n; ++b) A[i][n + b] = -num(K(i, b));
  }
  std::map<std::vector<std::size_t>, GiNaC::numeric> joint;
  for (std::size_t q = 0; q < u.joint.size(); ++q)
    joint.emplace(u.joint_indices[q], num(value.exact(u.joint[q], "the update's joint moment " + std::to_string(q + 1))));
  auto z = [&](const std::vector<std::size_t>& t) -> GiNaC::numeric {
    if (t.back() >= n) return joint.at(t);
    if (t.size() == 2) return point.P[t[0]][t[1]];
    return central_moment_value(vars, point, vars.higher_moment(t));
  };
  const MomentsAfterUpdate after = updated_moments(vars, A, z, Q);
  out.P_after_update.assign(n, std::vector<double>(n));
  for (std::size_t i = 0; i < n; ++i)
    for (std::size_t j = 0; j < n; ++j)
      out.P_after_update[i][j] = PolynomialEvaluator::rounded(after.P[i][j], entry_name("P_after_update", i, j));
  for (std::size_t q = 0; q < after.higher.size(); ++q)
    out.moments_after_update.push_back(PolynomialEvaluator::rounded(
        after.higher[q], vars.text_name(vars.first_higher_moment() + static_cast<std::uint32_t>(q)) + " after the update"));
}

void evaluate_update(const FilterEquations& eq, const PolynomialEvaluator& value, const EvaluationPoint& point,
                     EvaluatedFilter& out) {
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
      S(a, b) = value.exact(u.S[u.upper_index(a, b)], entry_name("innovation_covariance", a, b));
      out.innovation_covariance[a][b] = PolynomialEvaluator::rounded(S(a, b), entry_name("innovation_covariance", a, b));
    }
  for (unsigned i = 0; i < n; ++i)
    for (unsigned a = 0; a < r; ++a) PCt(i, a) = value.exact(u.PCt[i][a], entry_name("PCt", i, a));
  // The update needs S positive definite (the generated update() takes its Cholesky factor and returns false
  // otherwise): with P positive semi-definite it is, but a moment filter's S reads the moments given.
  for (unsigned k = 1; k <= r; ++k) {
    GiNaC::matrix leading(k, k);
    for (unsigned a = 0; a < k; ++a)
      for (unsigned b = 0; b < k; ++b) leading(a, b) = S(a, b);
    const GiNaC::ex minor = leading.determinant();
    if (!GiNaC::is_a<GiNaC::numeric>(minor) || !GiNaC::ex_to<GiNaC::numeric>(minor).is_positive())
      throw EvaluationError("the innovation covariance S is not positive definite at the point that --m, --P and --moment give (its leading " +
                            std::to_string(k) + " x " + std::to_string(k) +
                            " minor is not positive): the update is undefined there, and the generated update() "
                            "returns false");
  }
  const GiNaC::matrix S_inverse = S.inverse();
  const GiNaC::matrix K = PCt.mul(S_inverse);
  out.gain.assign(n, std::vector<double>(r));
  for (unsigned i = 0; i < n; ++i)
    for (unsigned a = 0; a < r; ++a) out.gain[i][a] = PolynomialEvaluator::rounded(K(i, a), entry_name("gain", i, a));
  if (!eq.variables.higher_moments().empty()) evaluate_moment_update(eq, value, point, K, out);
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
    evaluate_update(eq, value, point, out);
    return out;
  }
};

}  // namespace

const ObservationEvaluation& sampled_observation_evaluation() {
  static const SampledEvaluation part;
  return part;
}

}  // namespace pfgen
