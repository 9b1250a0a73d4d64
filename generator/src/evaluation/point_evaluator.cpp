#include "pfgen/evaluation/point_evaluator.hpp"

#include <Eigen/Dense>
#include <algorithm>

#include <cmath>

#include "pfgen/algebra/numeric_value.hpp"

namespace pfgen {
namespace {

// The values a delayed filter reads besides m and P (docs/theory.md §2.6), exact; empty for the
// inputs the filter does not read.
struct DelayedInputs {
  std::vector<GiNaC::numeric> m_delayed, phi, x_star;
};

// The options' values, or their defaults (md = m, x* = m, x*(t - h) = x*), and phi by the filters'
// own rule (the generated step's): 1 when h = 0 (Phi* = I), else x*_i(t - h) / x*_i(t) for t >= h,
// 0 where x*_i(t) = 0, and 0 for t < h.
DelayedInputs delayed_inputs(const FilterEquations& eq, const EvaluationPoint& point) {
  DelayedInputs in;
  if (!eq.is_delayed()) return in;
  in.m_delayed = point.m_delayed.empty() ? point.m : point.m_delayed;
  if (!eq.uses_x_star()) return in;
  in.x_star = point.x_star.empty() ? point.m : point.x_star;
  if (!point.phi.empty()) {
    in.phi = point.phi;
    return in;
  }
  const std::vector<GiNaC::numeric>& earlier = point.x_star_delayed.empty() ? in.x_star : point.x_star_delayed;
  for (std::size_t i = 0; i < in.x_star.size(); ++i)
    in.phi.push_back(eq.delay.is_zero()                              ? GiNaC::numeric(1)
                     : point.t < eq.delay || in.x_star[i].is_zero() ? GiNaC::numeric(0)
                                                                    : earlier[i] / in.x_star[i]);
  return in;
}

class PolynomialEvaluator {
 public:
  PolynomialEvaluator(const Model& model, const FilterEquations& eq, const EvaluationPoint& point,
                      const DelayedInputs& delayed) {
    const FilterVariables& vars = eq.variables;
    for (const auto& p : model.parameters) {
      auto it = point.parameters.find(p.name);
      coefficient_values_[p.symbol] = it != point.parameters.end() ? it->second : p.default_value;
    }
    coefficient_values_[model.time] = point.t;
    // Every variable a polynomial may hold: a delayed input the filter does not read stays 0.
    variable_values_.resize(vars.all_count());
    for (std::size_t i = 0; i < vars.n(); ++i) {
      variable_values_[vars.m(i)] = point.m[i];
      for (std::size_t j = i; j < vars.n(); ++j) variable_values_[vars.P(i, j)] = point.P[i][j];
    }
    for (std::size_t i = 0; i < delayed.m_delayed.size(); ++i) variable_values_[vars.m_delayed(i)] = delayed.m_delayed[i];
    for (std::size_t i = 0; i < delayed.phi.size(); ++i) variable_values_[vars.phi(i)] = delayed.phi[i];
    for (std::size_t i = 0; i < delayed.x_star.size(); ++i) variable_values_[vars.x_star(i)] = delayed.x_star[i];
    define_names(eq);
  }

  // The value before rounding: exact where the inputs are.
  GiNaC::ex exact(const Polynomial& p) const {
    GiNaC::ex sum = 0;
    for (const auto& [monomial, coefficient] : p.terms()) {
      GiNaC::ex term = numeric_value(coefficient, coefficient_values_);
      for (const auto& [variable, exponent] : monomial.factors())
        term *= GiNaC::pow(variable_values_[variable], exponent);
      sum += term;
    }
    return sum;
  }

  double operator()(const Polynomial& p, const std::string& what) const { return rounded(exact(p), what); }

  static double rounded(const GiNaC::ex& exact_value, const std::string& what) {
    GiNaC::ex value = exact_value.evalf();
    if (!GiNaC::is_a<GiNaC::numeric>(value) || !GiNaC::ex_to<GiNaC::numeric>(value).is_real())
      throw EvaluationError(what + " does not evaluate to a real number at this point");
    double result = GiNaC::ex_to<GiNaC::numeric>(value).to_double();
    if (!std::isfinite(result)) throw EvaluationError(what + " is not finite at this point");
    return result;
  }

 private:
  // A user filter's definitions, in order, each from the values before it. Each value is rounded
  // to GiNaC's floating point (17 digits) as soon as it is computed: an exact value could grow
  // without bound through a chain of powers (D2 = D1^1000, D3 = D2^1000), a float cannot.
  void define_names(const FilterEquations& eq) {
    if (eq.definitions.empty()) return;
    GiNaC::exmap values = coefficient_values_;
    for (std::size_t v = 0; v < eq.variables.count(); ++v) values[eq.variables.symbols()[v]] = variable_values_[v];
    for (const auto& d : eq.definitions) {
      const std::string what = "definition '" + d.name.get_name() + "'";
      GiNaC::ex value;
      try {
        // A Cholesky entry below a zero pivot is 0 (FilterDefinition::zero_where_zero).
        if (d.zero_where_zero && numeric_value(*d.zero_where_zero, values).is_zero()) {
          coefficient_values_[d.name] = values[d.name] = GiNaC::ex(0);
          continue;
        }
        value = numeric_value(d.value, values).evalf();
      } catch (const std::exception&) {  // GiNaC's pole_error for 1/0, CLN's overflow
        throw EvaluationError(what + " cannot be computed at this point (a division by zero or an overflow)");
      }
      rounded(value, what);  // a real, finite number, or an EvaluationError naming the definition
      coefficient_values_[d.name] = values[d.name] = value;
    }
  }

  GiNaC::exmap coefficient_values_;
  std::vector<GiNaC::numeric> variable_values_;
};

void check_length(const std::string& option, const std::vector<GiNaC::numeric>& values, std::size_t n) {
  if (!values.empty() && values.size() != n)
    throw EvaluationError(option + ": expected " + std::to_string(n) + " values, found " + std::to_string(values.size()));
}

// The delayed inputs: only for a filter that reads them, each with n values, phi or x*(t - h).
void check_delayed_point(const Model& model, const FilterEquations& eq, const EvaluationPoint& point) {
  const std::vector<std::pair<std::string, const std::vector<GiNaC::numeric>*>> inputs = {
      {"--m-delayed", &point.m_delayed}, {"--x-star", &point.x_star}, {"--x-star-delayed", &point.x_star_delayed},
      {"--phi", &point.phi}};
  for (const auto& [option, values] : inputs) {
    if (values->empty()) continue;
    if (!eq.is_delayed())
      throw EvaluationError(option + ": filter " + eq.name + " is not for delayed observations (model " + model.name +
                            " has none)");
    if (option != "--m-delayed" && !eq.uses_x_star())
      throw EvaluationError(option + ": filter " + eq.name + " has no Phi* gain, so it reads no x* (delay-optimal does)");
    check_length(option, *values, model.n());
  }
  if (!point.phi.empty() && !point.x_star_delayed.empty())
    throw EvaluationError("--phi: give --phi or --x-star-delayed (from which phi is computed), not both");
}

void check_point(const Model& model, const FilterEquations& eq, const EvaluationPoint& point) {
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
  check_delayed_point(model, eq, point);
  for (const auto& [name, value] : point.parameters) {
    bool known = false;
    for (const auto& p : model.parameters) known = known || p.name == name;
    if (!known) throw EvaluationError("--set: model " + model.name + " has no parameter '" + name + "'");
  }
}

std::string at(const std::string& what, std::size_t i, std::size_t j) {
  return what + "[" + std::to_string(i + 1) + "][" + std::to_string(j + 1) + "]";
}

// The sampled kinds' update at the point: S = C P C^T + R and K = P C^T S^-1, formed exactly
// (GiNaC's rational matrix inverse) and rounded once; cd-euler's dt^2 term Cov(f).
void evaluate_sampled(const FilterEquations& eq, const PolynomialEvaluator& value, EvaluatedFilter& out) {
  const std::size_t n = eq.n();
  const SampledUpdate& u = eq.update;
  const std::size_t r = u.r();
  if (!eq.P_euler.empty()) {
    out.P_dt2.assign(n, std::vector<double>(n));
    for (std::size_t i = 0; i < n; ++i)
      for (std::size_t j = i; j < n; ++j)
        out.P_dt2[i][j] = out.P_dt2[j][i] = value(eq.P_euler[eq.variables.upper_index(i, j)], at("P_dt2", i, j));
  }
  GiNaC::matrix S(static_cast<unsigned>(r), static_cast<unsigned>(r));
  GiNaC::matrix PCt(static_cast<unsigned>(n), static_cast<unsigned>(r));
  out.innovation_covariance.assign(r, std::vector<double>(r));
  for (unsigned a = 0; a < r; ++a)
    for (unsigned b = 0; b < r; ++b) {
      S(a, b) = value.exact(u.S[u.upper_index(a, b)]);
      out.innovation_covariance[a][b] = PolynomialEvaluator::rounded(S(a, b), at("innovation_covariance", a, b));
    }
  for (unsigned i = 0; i < n; ++i)
    for (unsigned a = 0; a < r; ++a) PCt(i, a) = value.exact(u.PCt[i][a]);
  GiNaC::matrix S_inverse;
  try {
    S_inverse = S.inverse();
  } catch (const std::exception&) {
    throw EvaluationError("the innovation covariance C P C^T + Uv Uv^T is singular at this point");
  }
  const GiNaC::matrix K = PCt.mul(S_inverse);
  out.gain.assign(n, std::vector<double>(r));
  for (unsigned i = 0; i < n; ++i)
    for (unsigned a = 0; a < r; ++a) out.gain[i][a] = PolynomialEvaluator::rounded(K(i, a), at("gain", i, a));
}

}  // namespace

EvaluatedFilter evaluate_at(const Model& model, const FilterEquations& eq, const EvaluationPoint& point) {
  check_point(model, eq, point);
  const DelayedInputs delayed = delayed_inputs(eq, point);
  PolynomialEvaluator value(model, eq, point, delayed);
  const std::size_t n = eq.n();
  EvaluatedFilter out;
  for (std::size_t i = 0; i < n; ++i) out.m_drift.push_back(value(eq.m_drift[i], "m_drift[" + std::to_string(i + 1) + "]"));
  // Continuous kinds: the gain before the P drift (the order of the checks, so of the first
  // message at a point where several are not finite). Sampled kinds: the prediction, then the update.
  if (!eq.is_sampled()) {
    out.gain.assign(n, std::vector<double>(eq.p));
    for (std::size_t i = 0; i < n; ++i)
      for (std::size_t r = 0; r < eq.p; ++r)
        out.gain[i][r] = value(eq.gain[i][r], "gain[" + std::to_string(i + 1) + "][" + std::to_string(r + 1) + "]");
  }
  out.P_drift.assign(n, std::vector<double>(n));
  for (std::size_t i = 0; i < n; ++i)
    for (std::size_t j = i; j < n; ++j)
      out.P_drift[i][j] = out.P_drift[j][i] =
          value(eq.P_drift(i, j), "P_drift[" + std::to_string(i + 1) + "][" + std::to_string(j + 1) + "]");
  if (eq.is_sampled()) evaluate_sampled(eq, value, out);
  auto rounded = [](const std::vector<GiNaC::numeric>& exact, const std::string& what) {
    std::vector<double> out;
    for (std::size_t i = 0; i < exact.size(); ++i)
      out.push_back(PolynomialEvaluator::rounded(exact[i], what + "[" + std::to_string(i + 1) + "]"));
    return out;
  };
  if (eq.is_delayed())
    for (std::size_t r = 0; r < eq.p; ++r)
      out.predicted_observation.push_back(
          value(eq.predicted_observation[r], "predicted_observation[" + std::to_string(r + 1) + "]"));
  out.m_delayed = rounded(delayed.m_delayed, "m_delayed");
  out.phi = rounded(delayed.phi, "phi");
  out.x_star = rounded(delayed.x_star, "x_star");
  for (std::size_t i = 0; i < eq.x_star_drift.size(); ++i)
    out.x_star_drift.push_back(value(eq.x_star_drift[i], "x_star_drift[" + std::to_string(i + 1) + "]"));
  return out;
}

}  // namespace pfgen
