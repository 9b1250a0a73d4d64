#include "pfgen/evaluation/polynomial_evaluator.hpp"

#include <cmath>

#include "pfgen/algebra/numeric_value.hpp"
#include "pfgen/derivation/closed_expectation.hpp"

namespace pfgen {

GiNaC::numeric central_moment_value(const FilterVariables& vars, const EvaluationPoint& point, std::uint32_t variable) {
  if (auto it = point.moments.find(vars.text_name(variable)); it != point.moments.end()) return it->second;
  return gaussian_central_moment(vars.higher_moments().at(variable - vars.first_higher_moment()), point.P);
}

PolynomialEvaluator::PolynomialEvaluator(const Model& model, const FilterEquations& eq, const EvaluationPoint& point,
                                         const InputValues& inputs) {
  const FilterVariables& vars = eq.variables;
  for (const auto& p : model.parameters) {
    auto it = point.parameters.find(p.name);
    coefficient_values_[p.symbol] = it != point.parameters.end() ? it->second : p.default_value;
  }
  coefficient_values_[model.time] = point.t;
  // Every variable a polynomial may hold: an input the filter does not read stays 0.
  variable_values_.resize(vars.all_count());
  for (std::size_t i = 0; i < vars.n(); ++i) {
    variable_values_[vars.m(i)] = point.m[i];
    for (std::size_t j = i; j < vars.n(); ++j) variable_values_[vars.P(i, j)] = point.P[i][j];
  }
  for (std::size_t q = 0; q < vars.higher_moments().size(); ++q) {
    const std::uint32_t v = vars.first_higher_moment() + static_cast<std::uint32_t>(q);
    variable_values_[v] = central_moment_value(vars, point, v);
  }
  for (const auto& [variable, value] : inputs) variable_values_[variable] = value;
  define_names(eq);
}

GiNaC::ex PolynomialEvaluator::exact(const Polynomial& p) const {
  GiNaC::ex sum = 0;
  for (const auto& [monomial, coefficient] : p.terms()) {
    GiNaC::ex term = numeric_value(coefficient, coefficient_values_);
    for (const auto& [variable, exponent] : monomial.factors()) term *= GiNaC::pow(variable_values_[variable], exponent);
    sum += term;
  }
  return sum;
}

GiNaC::ex PolynomialEvaluator::exact(const Polynomial& p, const std::string& what) const {
  GiNaC::ex value;
  try {
    value = exact(p);
    if (!GiNaC::is_a<GiNaC::numeric>(value)) value = value.evalf();  // sqrt(2) and the like stay symbolic till then
  } catch (const std::exception&) {  // GiNaC's pole_error for 1/0 or tgamma(-1), CLN's overflow
    throw EvaluationError(what + " cannot be computed at this point (a pole of a function, a division by zero or "
                                 "an overflow)");
  }
  if (!GiNaC::is_a<GiNaC::numeric>(value))
    throw EvaluationError(what + " does not evaluate to a real number at this point");
  return value;
}

double PolynomialEvaluator::operator()(const Polynomial& p, const std::string& what) const {
  return rounded(exact(p, what), what);
}

double PolynomialEvaluator::rounded(const GiNaC::ex& exact_value, const std::string& what) {
  GiNaC::ex value = exact_value.evalf();
  if (!GiNaC::is_a<GiNaC::numeric>(value) || !GiNaC::ex_to<GiNaC::numeric>(value).is_real())
    throw EvaluationError(what + " does not evaluate to a real number at this point");
  double result = GiNaC::ex_to<GiNaC::numeric>(value).to_double();
  if (!std::isfinite(result)) throw EvaluationError(what + " is not finite at this point");
  return result;
}

// A user filter's definitions, in order, each from the values before it. Each value is rounded
// to GiNaC's floating point (17 digits) as soon as it is computed: an exact value could grow
// without bound through a chain of powers (D2 = D1^1000, D3 = D2^1000), a float cannot.
void PolynomialEvaluator::define_names(const FilterEquations& eq) {
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

std::string entry_name(const std::string& what, std::size_t i, std::size_t j) {
  return what + "[" + std::to_string(i + 1) + "][" + std::to_string(j + 1) + "]";
}

std::vector<double> rounded_values(const std::vector<GiNaC::numeric>& exact, const std::string& what) {
  std::vector<double> out;
  for (std::size_t i = 0; i < exact.size(); ++i)
    out.push_back(PolynomialEvaluator::rounded(exact[i], what + "[" + std::to_string(i + 1) + "]"));
  return out;
}

void evaluate_higher_moments(const FilterEquations& eq, const PolynomialEvaluator& value, EvaluatedFilter& out) {
  const FilterVariables& vars = eq.variables;
  const std::size_t n = eq.n();
  // E[h], which a polynomial h's moment filter reads its higher moments in; the observation's part fills it for a
  // polynomial h only.
  if (out.predicted_observation.empty())
    for (std::size_t r = 0; r < eq.p; ++r)
      out.predicted_observation.push_back(
          value(eq.predicted_observation[r], "predicted_observation[" + std::to_string(r + 1) + "]"));
  if (out.P_gain.empty())
    for (std::size_t r = 0; r < eq.p && !eq.P_gain.empty(); ++r) {
      std::vector<std::vector<double>> L(n, std::vector<double>(n));
      for (std::size_t i = 0; i < n; ++i)
        for (std::size_t j = i; j < n; ++j)
          L[i][j] = L[j][i] = value(eq.P_gain[vars.upper_index(i, j)][r],
                                    entry_name("P_gain", i, j) + " of observation " + std::to_string(r + 1));
      out.P_gain.push_back(std::move(L));
    }
  for (std::size_t q = 0; q < eq.higher_drift.size(); ++q) {
    const std::string name = vars.text_name(vars.first_higher_moment() + static_cast<std::uint32_t>(q));
    out.moment_names.push_back(name);
    out.moment_drift.push_back(value(eq.higher_drift[q], "the drift of " + name));
    std::vector<double> gain;
    for (std::size_t r = 0; r < eq.p && !eq.higher_gain.empty(); ++r)
      gain.push_back(value(eq.higher_gain[q][r], "the gain of " + name + " for observation " + std::to_string(r + 1)));
    out.moment_gain.push_back(std::move(gain));
  }
}

void evaluate_m_drift(const FilterEquations& eq, const PolynomialEvaluator& value, EvaluatedFilter& out) {
  for (std::size_t i = 0; i < eq.n(); ++i)
    out.m_drift.push_back(value(eq.m_drift[i], "m_drift[" + std::to_string(i + 1) + "]"));
}

void evaluate_gain(const FilterEquations& eq, const PolynomialEvaluator& value, EvaluatedFilter& out) {
  const std::size_t n = eq.n();
  out.gain.assign(n, std::vector<double>(eq.p));
  for (std::size_t i = 0; i < n; ++i)
    for (std::size_t r = 0; r < eq.p; ++r)
      out.gain[i][r] = value(eq.gain[i][r], "gain[" + std::to_string(i + 1) + "][" + std::to_string(r + 1) + "]");
}

void evaluate_P_drift(const FilterEquations& eq, const PolynomialEvaluator& value, EvaluatedFilter& out) {
  const std::size_t n = eq.n();
  out.P_drift.assign(n, std::vector<double>(n));
  for (std::size_t i = 0; i < n; ++i)
    for (std::size_t j = i; j < n; ++j)
      out.P_drift[i][j] = out.P_drift[j][i] =
          value(eq.P_drift(i, j), "P_drift[" + std::to_string(i + 1) + "][" + std::to_string(j + 1) + "]");
}

}  // namespace pfgen
