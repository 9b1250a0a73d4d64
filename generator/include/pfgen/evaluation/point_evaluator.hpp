#pragma once
// Evaluates a filter's equations at one point (t, m, P, parameters) for
// `pfgen eval`. The polynomials are evaluated in exact rational arithmetic
// where the inputs allow it and rounded to double once at the end, so the
// result is a reference for checking generated code.
#include <map>
#include <stdexcept>
#include <string>
#include <vector>

#include "pfgen/derivation/filter_equations.hpp"

namespace pfgen {

struct EvaluationPoint {
  GiNaC::numeric t = 0;
  std::vector<GiNaC::numeric> m;
  std::vector<std::vector<GiNaC::numeric>> P;      // full n x n, symmetric
  std::map<std::string, GiNaC::numeric> parameters;  // overrides of the model defaults
};

// For a sampled kind, m_drift and P_drift are the prediction's (no observation term) and gain is
// the update's K = P C^T (C P C^T + Uv Uv^T)^-1 at the point.
struct EvaluatedFilter {
  std::vector<double> m_drift;                 // n
  std::vector<std::vector<double>> gain;       // n x p
  std::vector<std::vector<double>> P_drift;    // n x n, symmetric
  std::vector<std::vector<double>> P_dt2;      // cd-euler only: Cov(f), n x n
  std::vector<std::vector<double>> innovation_covariance;  // sampled only: C P C^T + Uv Uv^T, r x r
};

// A problem with the point itself (wrong sizes, asymmetric P, unknown parameter).
class EvaluationError : public std::runtime_error {
 public:
  using std::runtime_error::runtime_error;
};

EvaluatedFilter evaluate_at(const Model& model, const FilterEquations& eq, const EvaluationPoint& point);

}  // namespace pfgen
