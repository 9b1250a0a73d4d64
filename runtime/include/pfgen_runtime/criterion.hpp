#pragma once
// The exponential mean-square criterion of a filter (docs/theory.md, "The exponential criterion J"):
//   J = eps log E[exp(eps^-1 I)],   I = int_0^T L dt,   L = (x - m)^T M (x - m),
// estimated over Monte Carlo runs. Per run the engine integrates L over the grid (trapezoid, at
// every grid step); the fold below turns the runs' integrals into J, its standard error and the
// effective sample size, in run order, so the result does not depend on the thread count.
//
// J is computed about the mean integral: for large eps as mean I + eps log1p(mean expm1(u)),
// u = (I - mean I) / eps, which keeps J -> mean I + Var(I) / (2 eps) exact as eps -> infinity; for
// small eps, where J is carried by the few runs with the largest I, exp(I / eps) is computed as
// exp((I - max I) / eps) (log-sum-exp), which neither overflows nor loses the largest terms.
#include <cstddef>
#include <string>
#include <vector>

#include <Eigen/Core>

namespace pfgen_runtime {

// What J is asked with: eps (finite, > 0) and the weight M of L (n x n, symmetric; empty: the
// identity, L = |x - m|^2).
struct CriterionOptions {
  double epsilon = 1;
  Eigen::MatrixXd weight;
};

// J and its companions over a set of runs' integrals. Undefined numbers are NaN (no runs; the
// standard errors with fewer than 2 runs).
struct CriterionEstimate {
  std::size_t runs = 0;
  double J = 0;                   // eps log mean exp(I_r / eps), without overflow or cancellation
  double J_se = 0;                // delta method: eps sd(w) / (sqrt(N) mean(w))
  double ess = 0;                 // effective sample size (sum w)^2 / sum w^2, in [1, N]
  double mean_integral = 0;       // mean I: J's limit as eps -> infinity
  double mean_integral_se = 0;    // sd(I) / sqrt(N)
};

// The estimate from finite integrals in run order (std::invalid_argument for a non-finite one or
// eps not finite and > 0). Deterministic: one pass for the maximum, one for the sums.
CriterionEstimate estimate_criterion(const std::vector<double>& integrals, double epsilon);

// Whether `weight` is usable for n states: empty, or n x n, finite and symmetric. The message
// says what is wrong; empty when it is usable.
std::string criterion_weight_problem(const Eigen::MatrixXd& weight, std::size_t n);

}  // namespace pfgen_runtime
