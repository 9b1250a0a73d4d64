#pragma once
// Maximum likelihood over a record: one filter's log-likelihood as a function of some of the
// model's parameters, maximised by NLopt's L-BFGS within bounds (gradients by central
// differences), with standard errors from the observed information (the negative Hessian, by
// central differences) and Wald intervals; optionally profile-likelihood intervals.
#include <cstddef>
#include <functional>
#include <string>
#include <vector>

namespace pfgen::cli {

// The log-likelihood at the values of the estimated parameters; NaN where the filter fails, with
// the reason in `why`.
using LogLikelihood = std::function<double(const std::vector<double>& theta, std::string& why)>;

struct FitProblem {
  std::vector<std::string> names;
  std::vector<double> start;       // inside the bounds
  std::vector<double> lower, upper;  // -inf / +inf where unbounded
  std::size_t starts = 1;            // the first at `start`, the others drawn uniformly in the bounds
  unsigned long long seed = 1;
  bool profile = false;              // profile-likelihood intervals too
  std::size_t max_evaluations = 2000;  // of the log-likelihood, per start
  // The filter stops where its moments leave the realisable set (a moment filter): the likelihood
  // has holes, so the profile's stepping out also probes between its steps for them.
  bool filter_can_stop = false;
};

struct FittedParameter {
  std::string name;
  double estimate = 0;
  double std_error = 0;          // NaN when the observed information is not positive definite
  double wald_low = 0, wald_high = 0;
  double profile_low = 0, profile_high = 0;  // NaN unless asked; the bound where the interval reaches it
  bool profile_low_is_bound = false, profile_high_is_bound = false;
  // The profile interval's end is the last value where the filter runs: just beyond it the
  // log-likelihood cannot be evaluated (a moment filter leaves its realisable set, say).
  bool profile_low_is_edge = false, profile_high_is_edge = false;
  bool at_bound = false;
};

struct FitResult {
  bool converged = false;
  std::string stop_reason;  // the optimiser's, in words
  std::vector<FittedParameter> parameters;
  double log_likelihood = 0;
  std::size_t evaluations = 0;  // of the log-likelihood, all starts
  std::size_t best_start = 0;   // 0-based
  std::string information_note;  // why there are no standard errors, if there are none
  // A step of the differences from the estimate meets a value where the filter fails: the
  // estimate lies at the edge of where the log-likelihood exists (information_note says where).
  bool at_edge = false;
};

// Throws CliValueError when the log-likelihood is not finite at the first start (naming why).
FitResult maximise_likelihood(const FitProblem& problem, const LogLikelihood& log_likelihood);

}  // namespace pfgen::cli
