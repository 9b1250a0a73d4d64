#pragma once
// A filter's polynomials at one point, for `pfgen eval` (point_evaluator.hpp): exact where the
// inputs are, rounded to double once. What every filter's evaluation is made of, whatever its
// observation; each observation module's part (observation_evaluation.hpp) puts them together.
#include <cstdint>
#include <string>
#include <utility>
#include <vector>

#include "pfgen/evaluation/point_evaluator.hpp"

namespace pfgen {

// Values of the filter variables after m and P that a filter reads (a delayed filter's md, phi,
// x*), each by its variable number.
using InputValues = std::vector<std::pair<std::uint32_t, GiNaC::numeric>>;

class PolynomialEvaluator {
 public:
  // The parameters (the point's, else the model's defaults), t, m and P, the given inputs (every
  // other variable 0), and the filter's definitions computed from them in order.
  PolynomialEvaluator(const Model& model, const FilterEquations& eq, const EvaluationPoint& point,
                      const InputValues& inputs);

  // The value before rounding: exact where the inputs are.
  GiNaC::ex exact(const Polynomial& p) const;
  // The same, with an EvaluationError naming `what` where it cannot be computed (a pole, an overflow).
  GiNaC::ex exact(const Polynomial& p, const std::string& what) const;
  // Rounded; EvaluationError naming `what` when it is not a real, finite number.
  double operator()(const Polynomial& p, const std::string& what) const;
  static double rounded(const GiNaC::ex& exact_value, const std::string& what);

 private:
  void define_names(const FilterEquations& eq);

  GiNaC::exmap coefficient_values_;
  std::vector<GiNaC::numeric> variable_values_;
};

// "what[i][j]", 1-based, as the messages name a matrix entry.
std::string entry_name(const std::string& what, std::size_t i, std::size_t j);
// Each value rounded, "what[i]" naming it in a message.
std::vector<double> rounded_values(const std::vector<GiNaC::numeric>& exact, const std::string& what);

// The parts every filter's values have: m's drift, the gain (n x p), and P's drift (full, symmetric).
// A moment filter's central moment of order >= 3 at the point: as given (--moment), else its value under N(m, P).
GiNaC::numeric central_moment_value(const FilterVariables& vars, const EvaluationPoint& point, std::uint32_t variable);
// A moment filter's values beyond m and P: each higher moment's drift and gain, and the predicted observation and
// P_gain when the observation's part left them out (a linear h's).
void evaluate_higher_moments(const FilterEquations& eq, const PolynomialEvaluator& value, EvaluatedFilter& out);
void evaluate_m_drift(const FilterEquations& eq, const PolynomialEvaluator& value, EvaluatedFilter& out);
void evaluate_gain(const FilterEquations& eq, const PolynomialEvaluator& value, EvaluatedFilter& out);
void evaluate_P_drift(const FilterEquations& eq, const PolynomialEvaluator& value, EvaluatedFilter& out);

}  // namespace pfgen
