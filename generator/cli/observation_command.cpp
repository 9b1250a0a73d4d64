#include "observation_command.hpp"

namespace pfgen::cli {

std::string ObservationCommand::without_eigen_layer(const Model&) const { return {}; }

std::string ObservationCommand::header_note(const Model&, double) const { return {}; }

std::string ObservationCommand::reference_obstacle(const Model&) const { return {}; }

std::string ObservationCommand::after_table(const pfgen_runtime::MonteCarloResult&,
                                            const std::vector<std::string>&) const {
  return {};
}

Json values_json(const std::vector<double>& values) {
  Json a = Json::array();
  for (double x : values) a.push(Json::number(x));
  return a;
}

Json values_json(const std::vector<std::vector<double>>& values) {
  Json a = Json::array();
  for (const auto& row : values) a.push(values_json(row));
  return a;
}

void add_rate_eval_json(const EvaluatedFilter& value, Json& out) {
  out.add("m_drift", values_json(value.m_drift));
  out.add("gain", values_json(value.gain));
  out.add("P_drift", values_json(value.P_drift));
}

void add_P_gain_eval_json(const EvaluatedFilter& value, Json& out) {
  Json P_gain = Json::array();
  for (const auto& L : value.P_gain) P_gain.push(values_json(L));
  out.add("P_gain", P_gain);
}

void add_moment_eval_json(const EvaluatedFilter& value, Json& out) {
  Json names = Json::array();
  for (const auto& name : value.moment_names) names.push(Json::string(name));
  out.add("moments", names);
  out.add("moment_drift", values_json(value.moment_drift));
  // A sampled moment filter has no dy terms; its moments change at each sample instead.
  if (!value.moments_after_update.empty()) {
    out.add("P_after_update", values_json(value.P_after_update));
    out.add("moments_after_update", values_json(value.moments_after_update));
  } else
    out.add("moment_gain", values_json(value.moment_gain));
}

const ObservationCommand& observation_command(ObservationKind kind) {
  static const ObservationCommand* const parts[kObservationKindCount] = {
      &continuous_observation_command(), &sampled_observation_command(), &delayed_observation_command(),
      &polynomial_observation_command()};
  return observation_part(kind, parts);
}

}  // namespace pfgen::cli
