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
    // A linear h's values as the continuous observation's, but for a moment filter, whose E[h] and dP's dy terms
    // read the higher moments.
    if (predicts_linearly(eq) && value.moment_names.empty()) return;
    out.add("predicted_observation", values_json(value.predicted_observation));
    if (!value.P_gain.empty()) add_P_gain_eval_json(value, out);
  }
};

}  // namespace

const ObservationCommand& polynomial_observation_command() {
  static const PolynomialCommand part;
  return part;
}

}  // namespace pfgen::cli
