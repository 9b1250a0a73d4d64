#pragma once
// Small statistics for Monte Carlo summaries and tests of simulated laws.
#include <vector>

namespace pfgen_runtime {

// The q-quantile (0 <= q <= 1) by linear interpolation between order statistics (Hyndman-Fan
// type 7, R's default). std::invalid_argument for an empty sample, q outside [0, 1] or a NaN.
double quantile(std::vector<double> sample, double q);

// Several quantiles of one sample, each as quantile() defines it (quantile() is the case of one),
// for q in ascending order: out[k] is the qs[k]-quantile. The sample is reordered in place: the order statistics needed are
// selected (std::nth_element) instead of sorting the whole sample, which the Monte Carlo statistics
// do for every state at every record time. Same errors as quantile().
void quantiles_in_place(std::vector<double>& sample, const std::vector<double>& qs, std::vector<double>& out);

struct KolmogorovSmirnovResult {
  double statistic = 0;  // D = sup |F_a - F_b|
  double p_value = 1;    // asymptotic, with Stephens' small-sample correction
};

// The two-sample Kolmogorov-Smirnov test of H0 "a and b come from the same continuous law".
// p_value = Q_KS((sqrt(N) + 0.12 + 0.11 / sqrt(N)) D), N = n_a n_b / (n_a + n_b),
// Q_KS(z) = 2 sum_{k>=1} (-1)^(k-1) exp(-2 k^2 z^2).
KolmogorovSmirnovResult ks_two_sample(std::vector<double> a, std::vector<double> b);

// Q_KS(z), the Kolmogorov distribution's upper tail.
double kolmogorov_tail(double z);

}  // namespace pfgen_runtime
