#pragma once
// What the command line says of an observation model: how `pfgen eval` lays out its filters'
// values, what `pfgen codegen --eigen` writes for them, and what `pfgen simulate` says of its
// observations. Text only: how the observations are drawn and fed to the filters is the
// simulation plugin's (the runtime's). Each observation model has its part in the commands room,
// cli/observations/<kind>_command.cpp; the commands call the model's part and never ask which
// kind it is.
#include <string>
#include <vector>

#include "pfgen/derivation/filter_equations.hpp"
#include "pfgen/evaluation/point_evaluator.hpp"
#include "pfgen/printing/json_writer.hpp"
#include "pfgen_runtime/monte_carlo.hpp"

namespace pfgen::cli {

class ObservationCommand {
 public:
  virtual ~ObservationCommand() = default;

  // pfgen eval: the filter's values, after "model" and "filter" in its JSON.
  virtual void add_eval_json(const FilterEquations& eq, const EvaluatedFilter& value, Json& out) const = 0;

  // pfgen codegen --eigen: why this observation's filters have no Eigen layer, for a note (empty:
  // they have one).
  virtual std::string without_eigen_layer(const Model& model) const;

  // pfgen simulate: what the header line says of the observation after the model's name (empty
  // by default); why the particle reference cannot weigh these observations (empty: it can);
  // and what is printed after the summary table (nothing by default).
  virtual std::string header_note(const Model& model, double dt) const;
  virtual std::string reference_obstacle(const Model& model) const;
  virtual std::string after_table(const pfgen_runtime::MonteCarloResult& result,
                                  const std::vector<std::string>& state_names) const;
};

// pfgen eval's values of a filter whose observation is a rate (continuous, delayed): m_drift,
// gain and P_drift, flat.
void add_rate_eval_json(const EvaluatedFilter& value, Json& out);
// "P_gain": per observation r, dP's coefficients of dy_r - predicted_observation_r dt (n x n).
void add_P_gain_eval_json(const EvaluatedFilter& value, Json& out);
// A moment filter's "moments" (names), "moment_drift" and "moment_gain" (one row of p per moment).
void add_moment_eval_json(const EvaluatedFilter& value, Json& out);
// A vector and a matrix of values as JSON arrays.
Json values_json(const std::vector<double>& values);
Json values_json(const std::vector<std::vector<double>>& values);

// The observation models' parts (cli/observations/<kind>_command.cpp), and the model's, by kind.
const ObservationCommand& continuous_observation_command();
const ObservationCommand& sampled_observation_command();
const ObservationCommand& delayed_observation_command();
const ObservationCommand& polynomial_observation_command();
const ObservationCommand& observation_command(ObservationKind kind);

}  // namespace pfgen::cli
