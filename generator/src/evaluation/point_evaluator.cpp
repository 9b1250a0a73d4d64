#include "pfgen/evaluation/point_evaluator.hpp"

#include <Eigen/Dense>
#include <algorithm>

#include <cmath>

namespace pfgen {
namespace {

class PolynomialEvaluator {
 public:
  PolynomialEvaluator(const Model& model, const FilterVariables& vars, const EvaluationPoint& point) {
    for (const auto& p : model.parameters) {
      auto it = point.parameters.find(p.name);
      coefficient_values_[p.symbol] = it != point.parameters.end() ? it->second : p.default_value;
    }
    coefficient_values_[model.time] = point.t;
    variable_values_.resize(vars.count());
    for (std::size_t i = 0; i < vars.n(); ++i) {
      variable_values_[vars.m(i)] = point.m[i];
      for (std::size_t j = i; j < vars.n(); ++j) variable_values_[vars.P(i, j)] = point.P[i][j];
    }
  }

  double operator()(const Polynomial& p, const std::string& what) const {
    GiNaC::ex sum = 0;
    for (const auto& [monomial, coefficient] : p.terms()) {
      GiNaC::ex term = coefficient.subs(coefficient_values_);
      for (const auto& [variable, exponent] : monomial.factors())
        term *= GiNaC::pow(variable_values_[variable], exponent);
      sum += term;
    }
    GiNaC::ex value = sum.evalf();
    if (!GiNaC::is_a<GiNaC::numeric>(value) || !GiNaC::ex_to<GiNaC::numeric>(value).is_real())
      throw EvaluationError(what + " does not evaluate to a real number at this point");
    double result = GiNaC::ex_to<GiNaC::numeric>(value).to_double();
    if (!std::isfinite(result)) throw EvaluationError(what + " is not finite at this point");
    return result;
  }

 private:
  GiNaC::exmap coefficient_values_;
  std::vector<GiNaC::numeric> variable_values_;
};

void check_point(const Model& model, const EvaluationPoint& point) {
  const std::size_t n = model.n();
  if (point.m.size() != n)
    throw EvaluationError("--m: expected " + std::to_string(n) + " values, found " + std::to_string(point.m.size()));
  if (point.P.size() != n)
    throw EvaluationError("--P: expected " + std::to_string(n) + " rows, found " + std::to_string(point.P.size()));
  for (std::size_t i = 0; i < n; ++i) {
    if (point.P[i].size() != n)
      throw EvaluationError("--P: row " + std::to_string(i + 1) + " has " + std::to_string(point.P[i].size()) +
                            " values, expected " + std::to_string(n));
  }
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
  for (const auto& [name, value] : point.parameters) {
    bool known = false;
    for (const auto& p : model.parameters) known = known || p.name == name;
    if (!known) throw EvaluationError("--set: model " + model.name + " has no parameter '" + name + "'");
  }
}

}  // namespace

EvaluatedFilter evaluate_at(const Model& model, const FilterEquations& eq, const EvaluationPoint& point) {
  check_point(model, point);
  const FilterVariables& vars = eq.variables;
  PolynomialEvaluator value(model, vars, point);
  const std::size_t n = eq.n();
  EvaluatedFilter out;
  for (std::size_t i = 0; i < n; ++i) out.m_drift.push_back(value(eq.m_drift[i], "m_drift[" + std::to_string(i + 1) + "]"));
  out.gain.assign(n, std::vector<double>(eq.p));
  for (std::size_t i = 0; i < n; ++i)
    for (std::size_t r = 0; r < eq.p; ++r)
      out.gain[i][r] = value(eq.gain[i][r], "gain[" + std::to_string(i + 1) + "][" + std::to_string(r + 1) + "]");
  out.P_drift.assign(n, std::vector<double>(n));
  for (std::size_t i = 0; i < n; ++i)
    for (std::size_t j = i; j < n; ++j)
      out.P_drift[i][j] = out.P_drift[j][i] =
          value(eq.P_drift(i, j), "P_drift[" + std::to_string(i + 1) + "][" + std::to_string(j + 1) + "]");
  return out;
}

}  // namespace pfgen
