#pragma once
// Small statistics for Monte Carlo summaries and tests of simulated laws.
#include <cstddef>
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

// The regularised lower incomplete gamma function P(a, x) = gamma(a, x) / Gamma(a), a > 0, x >= 0:
// the chi-square law's CDF with k degrees of freedom at x is P(k / 2, x / 2).
double regularized_gamma_p(double a, double x);

// The p-quantile (0 < p < 1) of the chi-square law with `dof` >= 1 degrees of freedom: by bisection
// on P up to 10^4 degrees of freedom, above by Wilson & Hilferty's cube-root normal approximation
// (relative error below 1e-5 there). std::invalid_argument otherwise.
double chi_square_quantile(double p, double dof);

// The two-sided 95 % band of the mean NEES per state dimension over `runs` runs of n states, as
// Bar-Shalom, Li & Kirubarajan 2001 test a filter's consistency: for a consistent filter runs x n x
// (the mean of e^T P^-1 e / n) is chi-square with runs x n degrees of freedom, so the band is
// [chi2_0.025(runs n), chi2_0.975(runs n)] / (runs n). NaN, NaN for runs == 0.
struct NeesBand {
  double low = 0, high = 0;
};
NeesBand nees_band(std::size_t runs, std::size_t n);

// e^T P^-1 e for P given as its packed upper triangle (n(n+1)/2 entries, the filters' layout), by
// Cholesky in `work` (n(n+1)/2 + n doubles); NaN when P is not positive definite or e not finite.
double normalized_error_squared(const double* error, const double* packed_P, std::size_t n, double* work);

}  // namespace pfgen_runtime
