// The continuous observation on the command line: eval's values flat.
#include "observation_command.hpp"

namespace pfgen::cli {
namespace {

class ContinuousCommand final : public ObservationCommand {
 public:
  void add_eval_json(const FilterEquations&, const EvaluatedFilter& value, Json& out) const override {
    add_rate_eval_json(value, out);
  }
};

}  // namespace

const ObservationCommand& continuous_observation_command() {
  static const ContinuousCommand part;
  return part;
}

}  // namespace pfgen::cli
