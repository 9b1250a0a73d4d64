#include "pfgen/evaluation/point_evaluator.hpp"

#include <Eigen/Dense>
#include <algorithm>

#include "pfgen/evaluation/observation_evaluation.hpp"
#include "pfgen/evaluation/polynomial_evaluator.hpp"

namespace pfgen {

void check_point_shape(std::size_t n, std::size_t m_values, const std::vector<std::size_t>& P_row_values) {
  if (m_values != n)
    throw EvaluationError("--m: expected " + std::to_string(n) + " values, found " + std::to_string(m_values));
  if (P_row_values.size() != n)
    throw EvaluationError("--P: expected " + std::to_string(n) + " rows, found " + std::to_string(P_row_values.size()));
  for (std::size_t i = 0; i < n; ++i)
    if (P_row_values[i] != n)
      throw EvaluationError("--P: row " + std::to_string(i + 1) + " has " + std::to_string(P_row_values[i]) +
                            " values, expected " + std::to_string(n));
}

namespace {

void check_point(const Model& model, const FilterEquations& eq, const EvaluationPoint& point,
                 const ObservationEvaluation& observation) {
  const std::size_t n = model.n();
  std::vector<std::size_t> row_sizes;
  for (const auto& row : point.P) row_sizes.push_back(row.size());
  check_point_shape(n, point.m.size(), row_sizes);
  for (std::size_t i = 0; i < n; ++i)
    for (std::size_t j = i + 1; j < n; ++j)
      if (point.P[i][j] != point.P[j][i])
        throw EvaluationError("--P: not symmetric, row " + std::to_string(i + 1) + " column " + std::to_string(j + 1));
  // A covariance: symmetric (above) and positive semi-definite, up to rounding.
  Eigen::MatrixXd P(n, n);
  for (std::size_t i = 0; i < n; ++i)
    for (std::size_t j = 0; j < n; ++j) P(i, j) = point.P[i][j].to_double();
  const double smallest = Eigen::SelfAdjointEigenSolver<Eigen::MatrixXd>(P).eigenvalues().minCoeff();
  if (smallest < -1e-12 * std::max(1.0, P.cwiseAbs().maxCoeff()))
    throw EvaluationError("--P: not positive semi-definite (smallest eigenvalue " + std::to_string(smallest) + ")");
  observation.check_inputs(model, eq, point);
  for (const auto& [name, value] : point.moments) {
    bool known = false;
    for (std::size_t q = 0; q < eq.variables.higher_moments().size(); ++q)
      known = known || eq.variables.text_name(eq.variables.first_higher_moment() + static_cast<std::uint32_t>(q)) == name;
    if (known) continue;
    if (eq.variables.higher_moments().empty())
      throw EvaluationError("--moment: filter " + eq.name + " carries no central moments above P (the closure kinds do)");
    const std::string first = eq.variables.text_name(eq.variables.first_higher_moment());
    const std::string last = eq.variables.text_name(static_cast<std::uint32_t>(eq.variables.count() - 1));
    throw EvaluationError("--moment: filter " + eq.name + " has no central moment '" + name + "' (" +
                          (first == last ? "its one is " + first : "its moments are " + first + " to " + last) + ")");
  }
  for (const auto& [name, value] : point.parameters) {
    bool known = false;
    for (const auto& p : model.parameters) known = known || p.name == name;
    if (!known) throw EvaluationError("--set: model " + model.name + " has no parameter '" + name + "'");
  }
}

}  // namespace

EvaluatedFilter evaluate_at(const Model& model, const FilterEquations& eq, const EvaluationPoint& point) {
  const ObservationEvaluation& observation = observation_evaluation(model.observation);
  check_point(model, eq, point, observation);
  EvaluatedFilter out = observation.evaluate(model, eq, point);
  if (!eq.higher_drift.empty()) evaluate_higher_moments(eq, PolynomialEvaluator(model, eq, point, {}), out);
  return out;
}

}  // namespace pfgen
