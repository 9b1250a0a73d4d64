// The continuous observation on the command line: eval's values flat.
#include "observation_command.hpp"

namespace pfgen::cli {
namespace {

class ContinuousCommand final : public ObservationCommand {
 public:
  void add_eval_json(const FilterEquations&, const EvaluatedFilter& value, Json& out) const override {
    add_rate_eval_json(value, out);
    // A moment filter's dP has a dy term for a linear h too (its P_gain reads the third moments).
    if (!value.P_gain.empty()) add_P_gain_eval_json(value, out);
  }
};

}  // namespace

const ObservationCommand& continuous_observation_command() {
  static const ContinuousCommand part;
  return part;
}

}  // namespace pfgen::cli
