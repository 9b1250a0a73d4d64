// The polynomial observation on the command line: eval's values (the rate filters' and the
// predicted observation and dP's dy coefficients).
#include "observation_command.hpp"
#include "pfgen/observations/polynomial/polynomial_observation.hpp"

namespace pfgen::cli {
namespace {

class PolynomialCommand final : public ObservationCommand {
 public:
  void add_eval_json(const FilterEquations& eq, const EvaluatedFilter& value, Json& out) const override {
    add_rate_eval_json(value, out);
    if (predicts_linearly(eq)) return;  // a linear h's values as the continuous observation's
    out.add("predicted_observation", values_json(value.predicted_observation));
    if (value.P_gain.empty()) return;
    Json P_gain = Json::array();
    for (const auto& L : value.P_gain) P_gain.push(values_json(L));
    out.add("P_gain", P_gain);
  }
};

}  // namespace

const ObservationCommand& polynomial_observation_command() {
  static const PolynomialCommand part;
  return part;
}

}  // namespace pfgen::cli
