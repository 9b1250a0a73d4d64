// The delayed observation in `pfgen eval` (docs/theory.md §2.6): its filters also read what their
// history holds, md = m(t - h), and for the kinds with the Phi* gain x*(t), from which with
// x*(t - h) phi_i = x*_i(t - h) / x*_i(t), or phi itself (point_evaluator.hpp's options); their
// values are the continuous ones, then the predicted observation A0 + A md, the inputs as used and
// x*'s drift.
#include "pfgen/evaluation/observation_evaluation.hpp"
#include "pfgen/evaluation/polynomial_evaluator.hpp"

namespace pfgen {
namespace {

// The values a delayed filter reads besides m and P, exact; empty for the inputs it does not read.
struct DelayedInputs {
  std::vector<GiNaC::numeric> m_delayed, phi, x_star;
};

// The options' values, or their defaults (md = m, x* = m, x*(t - h) = x*), and phi by the filters'
// own rule (the generated step's): 1 when h = 0 (Phi* = I), else x*_i(t - h) / x*_i(t) for t >= h,
// 0 where x*_i(t) = 0, and 0 for t < h.
DelayedInputs inputs_at(const FilterEquations& eq, const EvaluationPoint& point) {
  DelayedInputs in;
  in.m_delayed = point.m_delayed.empty() ? point.m : point.m_delayed;
  if (!eq.uses_x_star()) return in;
  in.x_star = point.x_star.empty() ? point.m : point.x_star;
  if (!point.phi.empty()) {
    in.phi = point.phi;
    return in;
  }
  const std::vector<GiNaC::numeric>& earlier = point.x_star_delayed.empty() ? in.x_star : point.x_star_delayed;
  for (std::size_t i = 0; i < in.x_star.size(); ++i)
    in.phi.push_back(eq.delay.is_zero()                              ? GiNaC::numeric(1)
                     : point.t < eq.delay || in.x_star[i].is_zero() ? GiNaC::numeric(0)
                                                                    : earlier[i] / in.x_star[i]);
  return in;
}

InputValues input_values(const FilterVariables& vars, const DelayedInputs& in) {
  InputValues values;
  for (std::size_t i = 0; i < in.m_delayed.size(); ++i) values.emplace_back(vars.m_delayed(i), in.m_delayed[i]);
  for (std::size_t i = 0; i < in.phi.size(); ++i) values.emplace_back(vars.phi(i), in.phi[i]);
  for (std::size_t i = 0; i < in.x_star.size(); ++i) values.emplace_back(vars.x_star(i), in.x_star[i]);
  return values;
}

class DelayedEvaluation final : public ObservationEvaluation {
 public:
  // Only the Phi* kinds read x*; each input has n values; phi or x*(t - h), not both.
  void check_inputs(const Model& model, const FilterEquations& eq, const EvaluationPoint& point) const override {
    for (const auto& [option, values] : delayed_inputs(point)) {
      if (values->empty()) continue;
      if (option != "--m-delayed" && !eq.uses_x_star())
        throw EvaluationError(option + ": filter " + eq.name + " has no Phi* gain, so it reads no x* (delay-optimal does)");
      if (values->size() != model.n())
        throw EvaluationError(option + ": expected " + std::to_string(model.n()) + " values, found " +
                              std::to_string(values->size()));
    }
    if (!point.phi.empty() && !point.x_star_delayed.empty())
      throw EvaluationError("--phi: give --phi or --x-star-delayed (from which phi is computed), not both");
  }

  EvaluatedFilter evaluate(const Model& model, const FilterEquations& eq, const EvaluationPoint& point) const override {
    const DelayedInputs in = inputs_at(eq, point);
    const PolynomialEvaluator value(model, eq, point, input_values(eq.variables, in));
    EvaluatedFilter out;
    evaluate_m_drift(eq, value, out);
    evaluate_gain(eq, value, out);
    evaluate_P_drift(eq, value, out);
    for (std::size_t r = 0; r < eq.p; ++r)
      out.predicted_observation.push_back(
          value(eq.predicted_observation[r], "predicted_observation[" + std::to_string(r + 1) + "]"));
    out.m_delayed = rounded_values(in.m_delayed, "m_delayed");
    out.phi = rounded_values(in.phi, "phi");
    out.x_star = rounded_values(in.x_star, "x_star");
    for (std::size_t i = 0; i < eq.x_star_drift.size(); ++i)
      out.x_star_drift.push_back(value(eq.x_star_drift[i], "x_star_drift[" + std::to_string(i + 1) + "]"));
    return out;
  }
};

}  // namespace

const ObservationEvaluation& delayed_observation_evaluation() {
  static const DelayedEvaluation part;
  return part;
}

}  // namespace pfgen
