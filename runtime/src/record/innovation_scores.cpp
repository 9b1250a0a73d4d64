#include "pfgen_runtime/innovation_scores.hpp"

#include <algorithm>
#include <cmath>
#include <cstdio>

#include "pfgen_runtime/statistics.hpp"

namespace pfgen_runtime {

InnovationScores::InnovationScores(std::size_t p, std::size_t max_lags)
    : p_(p), max_lags_(max_lags), sum_(p), sum2_(p), head_(p * max_lags), ring_(p * max_lags), lagged_(p * max_lags) {}

void InnovationScores::add(const double* normalized, double log_likelihood_term) {
  log_likelihood_ += log_likelihood_term;
  const std::size_t L = max_lags_;
  for (std::size_t i = 0; i < p_; ++i) {
    const double e = normalized[i];
    sum_[i] += e;
    sum2_[i] += e * e;
    sum_squares_ += e * e;
    double* ring = ring_.data() + i * L;  // ring[(k) % L] holds e_k
    for (std::size_t l = 1; l <= std::min(L, count_); ++l) lagged_[i * L + l - 1] += e * ring[(count_ - l) % L];
    if (L > 0) {
      ring[count_ % L] = e;
      if (count_ < L) head_[i * L + count_] = e;
    }
  }
  ++count_;
}

bool InnovationSummary::white() const {
  for (const LjungBox& test : whiteness)
    if (!(test.p_value >= 0.05)) return false;
  return true;
}

InnovationSummary InnovationScores::summary() const {
  InnovationSummary out;
  out.count = count_;
  out.dimension = p_;
  out.log_likelihood = log_likelihood_;
  const double entries = static_cast<double>(count_ * p_);
  if (count_ == 0) return out;
  out.mean_square = sum_squares_ / entries;
  out.band_low = chi_square_quantile(0.025, entries) / entries;
  out.band_high = chi_square_quantile(0.975, entries) / entries;
  const std::size_t lags = std::min(max_lags_, count_ / 5);
  if (lags == 0) return out;
  const double N = static_cast<double>(count_);
  const std::size_t L = max_lags_;
  for (std::size_t i = 0; i < p_; ++i) {
    const double mean = sum_[i] / N;
    const double centred = sum2_[i] - N * mean * mean;  // sum (e_k - mean)^2
    LjungBox test;
    test.lags = lags;
    double head = 0, tail = 0;  // sums of the first and the last l values
    for (std::size_t l = 1; l <= lags; ++l) {
      head += head_[i * L + l - 1];
      tail += ring_[i * L + (count_ - l) % L];
      // sum_{k > l} (e_k - mean)(e_{k-l} - mean): the lagged products less the mean times the
      // sums of the two overlapping ranges, plus (N - l) mean^2.
      const double covariance = lagged_[i * L + l - 1] - mean * ((sum_[i] - head) + (sum_[i] - tail)) +
                                (N - static_cast<double>(l)) * mean * mean;
      const double rho = centred > 0 ? covariance / centred : 0;
      test.statistic += rho * rho / (N - static_cast<double>(l));
    }
    test.statistic *= N * (N + 2);
    test.p_value = 1 - regularized_gamma_p(static_cast<double>(lags) / 2, test.statistic / 2);
    out.whiteness.push_back(test);
  }
  return out;
}

std::string InnovationSummary::verdict() const {
  if (count == 0) return "no innovations: nothing to score";
  std::string out;
  char text[200];
  if (mean_square > band_high) {
    std::snprintf(text, sizeof text, "fails consistency: innovations larger than the filter predicts (mean square %.3g > %.3g)",
                  mean_square, band_high);
    out = text;
  } else if (mean_square < band_low) {
    std::snprintf(text, sizeof text, "fails consistency: innovations smaller than the filter predicts (mean square %.3g < %.3g)",
                  mean_square, band_low);
    out = text;
  }
  for (std::size_t i = 0; i < whiteness.size(); ++i)
    if (!(whiteness[i].p_value >= 0.05)) {
      std::snprintf(text, sizeof text, "%sfails whiteness: innovation %zu is correlated (Ljung-Box p = %.2g at %zu lags)",
                    out.empty() ? "" : "; ", i + 1, whiteness[i].p_value, whiteness[i].lags);
      out += text;
      break;
    }
  return out.empty() ? "passes: consistent and white" : out;
}

}  // namespace pfgen_runtime
