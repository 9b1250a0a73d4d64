// The sampled observation on the command line: eval's values as the prediction and the update, as
// derive shows them.
#include "observation_command.hpp"

namespace pfgen::cli {
namespace {

class SampledCommand final : public ObservationCommand {
 public:
  void add_eval_json(const FilterEquations&, const EvaluatedFilter& value, Json& out) const override {
    Json prediction = Json::object();
    prediction.add("m_drift", values_json(value.m_drift));
    prediction.add("P_drift", values_json(value.P_drift));
    if (!value.P_dt2.empty()) prediction.add("P_dt2", values_json(value.P_dt2));
    Json update = Json::object();
    update.add("innovation_covariance", values_json(value.innovation_covariance));
    update.add("gain", values_json(value.gain));
    out.add("prediction", prediction);
    out.add("update", update);
  }
};

}  // namespace

const ObservationCommand& sampled_observation_command() {
  static const SampledCommand part;
  return part;
}

}  // namespace pfgen::cli
