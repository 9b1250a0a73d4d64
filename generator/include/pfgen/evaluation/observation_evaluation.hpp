#pragma once
// What `pfgen eval` needs of an observation model: which inputs besides t, m and P its filters
// read, and their values at a point. Each module in observations/ implements it
// (observations/<kind>/<kind>_evaluation); evaluate_at calls the model's part and never asks which
// kind it is.
#include "pfgen/evaluation/point_evaluator.hpp"

namespace pfgen {

class ObservationEvaluation {
 public:
  virtual ~ObservationEvaluation() = default;

  // Refuses the point's inputs besides t, m and P that the filter does not read, or that are
  // malformed (EvaluationError naming the option). Called where evaluate_at checks them, after
  // --m and --P and before --set, so the first message at a bad point stays the same.
  virtual void check_inputs(const Model& model, const FilterEquations& eq, const EvaluationPoint& point) const = 0;
  // The filter's values at a checked point (polynomial_evaluator.hpp has their parts).
  virtual EvaluatedFilter evaluate(const Model& model, const FilterEquations& eq, const EvaluationPoint& point) const = 0;
};

// For the observation models whose filters read no history: EvaluationError for the first of the
// delayed filters' inputs (--m-delayed, --x-star, --x-star-delayed, --phi) the point gives.
void refuse_delayed_inputs(const Model& model, const FilterEquations& eq, const EvaluationPoint& point);
// Those inputs in that order, each with its option's name.
std::vector<std::pair<std::string, const std::vector<GiNaC::numeric>*>> delayed_inputs(const EvaluationPoint& point);

// The modules' parts (observations/<kind>/<kind>_evaluation.cpp), and the model's, composed from
// its axes: samples, a delay, then the rate as the model wrote it (eval prints A0 + A x's matrices,
// and a linear h's E[h] as its report does).
const ObservationEvaluation& continuous_observation_evaluation();
const ObservationEvaluation& sampled_observation_evaluation();
const ObservationEvaluation& delayed_observation_evaluation();
const ObservationEvaluation& polynomial_observation_evaluation();
const ObservationEvaluation& observation_evaluation(const ObservationModel& observation);

}  // namespace pfgen
