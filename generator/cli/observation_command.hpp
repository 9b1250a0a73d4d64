#pragma once
// What the command line needs of an observation model: how `pfgen eval` lays out its filters'
// values, what `pfgen codegen --eigen` writes for them, and what `pfgen simulate` says of its
// observations (the runs themselves take the plugin's one runtime Observation, whatever the model). Each module in observations/
// implements it (observations/<kind>/<kind>_command.cpp, compiled into the program with the cli:
// it meets the runtime); the commands call the model's part and never ask which kind it is.
#include <string>
#include <vector>

#include <Eigen/Dense>

#include "pfgen/derivation/filter_equations.hpp"
#include "pfgen/evaluation/point_evaluator.hpp"
#include "pfgen/printing/json_writer.hpp"
#include "pfgen_runtime/monte_carlo.hpp"
#include "pfgen_runtime/schemes.hpp"
#include "pfgen_runtime/simulation_plugin.hpp"

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
// A vector and a matrix of values as JSON arrays.
Json values_json(const std::vector<double>& values);
Json values_json(const std::vector<std::vector<double>>& values);

// The modules' parts (observations/<kind>/<kind>_command.cpp), and the model's, by kind.
const ObservationCommand& continuous_observation_command();
const ObservationCommand& sampled_observation_command();
const ObservationCommand& delayed_observation_command();
const ObservationCommand& polynomial_observation_command();
const ObservationCommand& observation_command(ObservationKind kind);

}  // namespace pfgen::cli
