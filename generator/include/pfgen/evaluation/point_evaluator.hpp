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
#include "pfgen_support/error.hpp"

namespace pfgen {

// A filter for delayed observations (docs/theory.md §2.6) also reads what its history holds: md =
// m(t - h), and for the kinds with the Phi* gain x*(t) and x*(t - h), from which
// phi_i = x*_i(t - h) / x*_i(t) (0 where x*_i(t) = 0, and for t < h; 1 when h = 0), or phi itself. An input left
// empty takes its default: md = m, x* = m, x*(t - h) = x*(t) (so phi = 1 from t = h on).
struct EvaluationPoint {
  GiNaC::numeric t = 0;
  std::vector<GiNaC::numeric> m;
  std::vector<std::vector<GiNaC::numeric>> P;      // full n x n, symmetric
  std::map<std::string, GiNaC::numeric> parameters;  // overrides of the model defaults
  std::vector<GiNaC::numeric> m_delayed;         // --m-delayed
  std::vector<GiNaC::numeric> x_star;            // --x-star
  std::vector<GiNaC::numeric> x_star_delayed;    // --x-star-delayed
  std::vector<GiNaC::numeric> phi;               // --phi, instead of --x-star-delayed
  // A moment filter's central moments of order >= 3 by name (--moment M3_112=0.1); one not given takes its
  // value under N(m, P): 0 at order 3, P_ij P_lq + P_il P_jq + P_iq P_jl at order 4.
  std::map<std::string, GiNaC::numeric> moments;
};

// For a sampled kind, m_drift and P_drift are the prediction's (no observation term) and gain is
// the update's K = P C^T (C P C^T + Uv Uv^T)^-1 at the point.
struct EvaluatedFilter {
  std::vector<double> m_drift;                 // n
  std::vector<std::vector<double>> gain;       // n x p
  std::vector<std::vector<double>> P_drift;    // n x n, symmetric
  std::vector<std::vector<double>> P_dt2;      // cd-euler only: Cov(f), n x n
  std::vector<std::vector<double>> innovation_covariance;  // sampled only: C P C^T + Uv Uv^T, r x r
  // Delayed only: A0 + A md, what the innovation compares dy with; the inputs used (md; and phi,
  // x* for the Phi* kinds) and x*'s drift f(x*, t).
  std::vector<double> predicted_observation, m_delayed, phi, x_star, x_star_drift;
  // Polynomial observations only: per observation r, the n x n coefficients of dy_r - E[h_r] dt in dP
  // (FilterEquations::P_gain); predicted_observation then holds E[h] (or h(m)).
  std::vector<std::vector<std::vector<double>>> P_gain;
  // Moment filters only: the central moments of order >= 3 (their names, in the state's order), each one's
  // drift and coefficients of dy_r - predicted_observation_r dt; P_gain is then set for a linear h too.
  std::vector<std::string> moment_names;
  std::vector<double> moment_drift;
  std::vector<std::vector<double>> moment_gain;
  // Sampled moment filters only (cd-closure3, cd-closure4): P (n x n) and the higher moments after an update at
  // the point.
  std::vector<std::vector<double>> P_after_update;
  std::vector<double> moments_after_update;
};

// A problem with the point itself (wrong sizes, asymmetric P, unknown parameter, a delayed input
// for a filter that does not read it).
class EvaluationError : public pfgen_support::Error {
 public:
  using pfgen_support::Error::Error;
};

// The point's sizes against n states: m's values, P's rows and each row's values (EvaluationError
// naming --m or --P otherwise). evaluate_at checks them first; the API before it reads any number.
void check_point_shape(std::size_t n, std::size_t m_values, const std::vector<std::size_t>& P_row_values);

EvaluatedFilter evaluate_at(const Model& model, const FilterEquations& eq, const EvaluationPoint& point);

}  // namespace pfgen
