#pragma once
// `pfgen fit MODEL --data FILE --estimate a,b`: the named parameters at the maximum of one
// filter's log-likelihood over a record (likelihood_fit.hpp), printed as a table (estimate,
// standard error, 95 % Wald and, with --profile, profile-likelihood intervals, the log-likelihood
// and AIC) and written as JSON (-o).
#include <string>
#include <vector>

#include "likelihood_fit.hpp"
#include "record_job.hpp"

namespace pfgen::cli {

struct FitOptions {
  RecordJobOptions record;
  std::string filter;                    // empty: the model's first default filter
  std::vector<std::string> estimate;     // parameter names
  std::vector<std::string> bounds;       // name=low:high
  std::size_t starts = 1;
  unsigned long long seed = 1;
  bool profile = false;
  std::string json_path;                 // -o
};

struct FitOutcome {
  std::string report;  // stdout
  std::string json;
  FitResult result;
  double aic = 0;
};

FitOutcome fit(const FitOptions& options);
int run_fit(const FitOptions& options);

}  // namespace pfgen::cli
