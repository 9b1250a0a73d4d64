// The continuous observation on the command line: eval's values flat, and simulate's runs on the
// truth's observation increments dy, which every filter steps on.
#include "observation_command.hpp"

namespace pfgen::cli {
namespace {

class ContinuousCommand final : public ObservationCommand {
 public:
  void add_eval_json(const FilterEquations&, const EvaluatedFilter& value, Json& out) const override {
    add_rate_eval_json(value, out);
  }

  pfgen_runtime::MonteCarloResult run(const pfgen_runtime::TruthScheme& scheme,
                                      const pfgen_runtime::SimulationPlugin& plugin, const Eigen::VectorXd& x0,
                                      const pfgen_runtime::MonteCarloOptions& options) const override {
    return pfgen_runtime::run_monte_carlo(scheme, plugin.observation(), x0, plugin.filters(), options);
  }
};

}  // namespace

const ObservationCommand& continuous_observation_command() {
  static const ContinuousCommand part;
  return part;
}

}  // namespace pfgen::cli
