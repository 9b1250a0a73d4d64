// The delayed observation on the command line: eval's values with the predicted observation, the
// delayed inputs as used and x*'s drift; codegen's note that --eigen writes no wrappers; simulate's
// header note on h in grid steps, the particle reference skipped, and the signed errors at the
// report times after the table.
#include <cmath>

#include "observation_command.hpp"
#include "pfgen_runtime/summary_table.hpp"
#include "pfgen_support/shortest_double.hpp"

namespace pfgen::cli {
namespace {

class DelayedCommand final : public ObservationCommand {
 public:
  void add_eval_json(const FilterEquations& eq, const EvaluatedFilter& value, Json& out) const override {
    add_rate_eval_json(value, out);
    // A0 + A m(t-h), the delayed inputs as used (after the defaults and phi's rule), x*'s own drift.
    out.add("predicted_observation", values_json(value.predicted_observation));
    Json inputs = Json::object();
    inputs.add("m_delayed", values_json(value.m_delayed));
    if (eq.uses_x_star()) {
      inputs.add("x_star", values_json(value.x_star));
      inputs.add("phi", values_json(value.phi));
    }
    out.add("delayed_inputs", inputs);
    if (eq.uses_x_star()) out.add("x_star_drift", values_json(value.x_star_drift));
  }

  // A delayed filter's state carries x* and it keeps a history: the plain header's Filter is its
  // interface.
  std::string without_eigen_layer(const Model& model) const override {
    return "no Eigen wrappers for the filters of delayed observations (model " + model.name +
           "); their headers have a Filter type instead";
  }

  // Every filter and the truth's dy read x or m h = D dt back.
  std::string header_note(const Model& model, double dt) const override {
    const double h = model.observation.delay().to_double();
    const long long steps = std::llround(h / dt);
    return ", observation delay h = " + pfgen_support::shortest_chars(h) + " = " + std::to_string(steps) +
           (steps == 1 ? " step" : " steps") + " of dt = " + pfgen_support::shortest_chars(dt);
  }

  std::string reference_obstacle(const Model&) const override {
    return "the observations are delayed, and the reference weighs undelayed ones only";
  }

  // The printed estimates of Basin, Rodriguez-Gonzalez & Martinez-Zuniga 2004 are compared through
  // mean m = x - mean e: the signed errors at the report times with standard errors.
  std::string after_table(const pfgen_runtime::MonteCarloResult& result,
                          const std::vector<std::string>& state_names) const override {
    return pfgen_runtime::format_report_errors(result, state_names);
  }
};

}  // namespace

const ObservationCommand& delayed_observation_command() {
  static const DelayedCommand part;
  return part;
}

}  // namespace pfgen::cli
