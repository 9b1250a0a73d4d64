#pragma once
// What a filter's innovations say about it over a record: the log-likelihood, the normalised
// innovations' mean square against its chi-square 95 % band, and their whiteness (Ljung & Box
// 1978). Accumulated one innovation at a time, in O(p x lags) memory, so a record of any length
// streams through.
#include <cstddef>
#include <string>
#include <vector>

namespace pfgen_runtime {

struct LjungBox {
  std::size_t lags = 0;
  double statistic = 0;  // Q = N (N + 2) sum_k rho_k^2 / (N - k), k = 1..lags
  double p_value = 1;    // 1 - F_chi2(lags)(Q)
};

struct InnovationSummary {
  std::size_t count = 0;        // innovation vectors (samples, or steps of continuous data)
  std::size_t dimension = 0;    // p, entries of each
  double log_likelihood = 0;    // sum of each step's term (RecordRun says which)
  double mean_square = 0;       // of the normalised entries: 1 for a consistent filter
  double band_low = 0, band_high = 0;  // chi2_{0.025, 0.975}(count p) / (count p)
  std::vector<LjungBox> whiteness;     // per observation entry
  bool consistent() const { return mean_square >= band_low && mean_square <= band_high; }
  bool white() const;  // every entry's p-value >= 0.05
  // The verdict in words: "passes", or which test it fails and what that suggests.
  std::string verdict() const;
};

class InnovationScores {
 public:
  // p entries per innovation; Ljung-Box at up to `max_lags` lags (fewer for a short record:
  // at most count / 5).
  explicit InnovationScores(std::size_t p, std::size_t max_lags = 10);
  // One innovation, normalised (for a consistent filter: independent standard normal entries), and
  // its log-likelihood term.
  void add(const double* normalized, double log_likelihood_term);
  std::size_t count() const { return count_; }
  double log_likelihood() const { return log_likelihood_; }
  InnovationSummary summary() const;

 private:
  std::size_t p_, max_lags_, count_ = 0;
  double log_likelihood_ = 0;
  double sum_squares_ = 0;
  // Per entry: the sum and sum of squares, the first max_lags values, the last max_lags values (a
  // ring), and sum_k e_k e_{k-l} for l = 1..max_lags.
  std::vector<double> sum_, sum2_, head_, ring_, lagged_;
};

}  // namespace pfgen_runtime
