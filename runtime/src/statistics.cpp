#include "pfgen_runtime/statistics.hpp"

#include <algorithm>
#include <cmath>
#include <stdexcept>

namespace pfgen_runtime {

namespace {

void check_sample(const std::vector<double>& sample, const char* what) {
  if (sample.empty()) throw std::invalid_argument(std::string(what) + ": empty sample");
  for (double v : sample)
    if (std::isnan(v)) throw std::invalid_argument(std::string(what) + ": NaN in the sample");
}

}  // namespace

double quantile(std::vector<double> sample, double q) {
  std::vector<double> out;
  quantiles_in_place(sample, {q}, out);
  return out[0];
}

void quantiles_in_place(std::vector<double>& sample, const std::vector<double>& qs, std::vector<double>& out) {
  check_sample(sample, "quantile");
  out.clear();
  const std::size_t size = sample.size();
  // No element before `placed` is larger than one after it, and sample[placed - 1] is order
  // statistic placed - 1: ranks are asked for in ascending order, so one below `placed` is that one.
  std::size_t placed = 0;
  auto place = [&](std::size_t rank) {  // afterwards sample[rank] is the rank-th order statistic
    if (rank < placed) return;
    if (rank == placed) {
      std::iter_swap(sample.begin() + static_cast<std::ptrdiff_t>(rank),
                     std::min_element(sample.begin() + static_cast<std::ptrdiff_t>(rank), sample.end()));
    } else {
      std::nth_element(sample.begin() + static_cast<std::ptrdiff_t>(placed),
                       sample.begin() + static_cast<std::ptrdiff_t>(rank), sample.end());
    }
    placed = rank + 1;
  };
  double previous = 0;
  for (double q : qs) {
    if (!(q >= 0 && q <= 1)) throw std::invalid_argument("quantile: q must be in [0, 1]");
    if (q < previous) throw std::invalid_argument("quantiles: q must be in ascending order");
    previous = q;
    const double position = q * static_cast<double>(size - 1);
    const auto below = static_cast<std::size_t>(std::floor(position));
    place(below);
    if (below + 1 >= size) {
      out.push_back(sample[below]);
      continue;
    }
    place(below + 1);
    const double fraction = position - static_cast<double>(below);
    out.push_back(sample[below] + fraction * (sample[below + 1] - sample[below]));
  }
}

double kolmogorov_tail(double z) {
  if (z < 0.2) return 1.0;  // the series converges slowly here and the tail is 1 to 1e-15
  double sum = 0, sign = 1;
  for (int k = 1; k <= 100; ++k) {
    const double term = sign * std::exp(-2.0 * k * k * z * z);
    sum += term;
    if (std::abs(term) < 1e-16) break;
    sign = -sign;
  }
  return std::clamp(2.0 * sum, 0.0, 1.0);
}

KolmogorovSmirnovResult ks_two_sample(std::vector<double> a, std::vector<double> b) {
  check_sample(a, "ks_two_sample");
  check_sample(b, "ks_two_sample");
  std::sort(a.begin(), a.end());
  std::sort(b.begin(), b.end());
  const double na = static_cast<double>(a.size()), nb = static_cast<double>(b.size());
  std::size_t i = 0, j = 0;
  double d = 0;
  while (i < a.size() && j < b.size()) {
    const double v = std::min(a[i], b[j]);
    while (i < a.size() && a[i] == v) ++i;  // ties move both empirical distributions together
    while (j < b.size() && b[j] == v) ++j;
    d = std::max(d, std::abs(static_cast<double>(i) / na - static_cast<double>(j) / nb));
  }
  const double n = std::sqrt(na * nb / (na + nb));
  return {d, kolmogorov_tail((n + 0.12 + 0.11 / n) * d)};
}

double regularized_gamma_p(double a, double x) {
  if (!(a > 0) || !(x >= 0)) throw std::invalid_argument("regularized_gamma_p: need a > 0 and x >= 0");
  if (x == 0) return 0;
  const double log_prefix = a * std::log(x) - x - std::lgamma(a);
  if (x < a + 1) {  // the series sum x^k / (a (a + 1) ... (a + k)), converging fast below a + 1
    double term = 1 / a, sum = term;
    for (int k = 1; k < 100000 && std::abs(term) > 1e-16 * std::abs(sum); ++k) {
      term *= x / (a + k);
      sum += term;
    }
    return std::min(1.0, sum * std::exp(log_prefix));
  }
  // Q(a, x) by its continued fraction (modified Lentz), converging fast above a + 1.
  constexpr double tiny = 1e-300;
  double b = x + 1 - a, c = 1 / tiny, d = 1 / b, h = d;
  for (int k = 1; k < 100000; ++k) {
    const double an = -k * (k - a);
    b += 2;
    d = an * d + b;
    if (std::abs(d) < tiny) d = tiny;
    c = b + an / c;
    if (std::abs(c) < tiny) c = tiny;
    d = 1 / d;
    const double delta = d * c;
    h *= delta;
    if (std::abs(delta - 1) < 1e-16) break;
  }
  return std::max(0.0, 1 - std::exp(log_prefix) * h);
}

namespace {

// The standard normal's p-quantile (Acklam's rational approximation refined by one Halley step
// on erfc, good to double precision for the 0.025 and 0.975 used here).
double normal_quantile(double p) {
  static const double a[] = {-3.969683028665376e+01, 2.209460984245205e+02, -2.759285104469687e+02,
                             1.383577518672690e+02, -3.066479806614716e+01, 2.506628277459239e+00};
  static const double b[] = {-5.447609879822406e+01, 1.615858368580409e+02, -1.556989798598866e+02,
                             6.680131188771972e+01, -1.328068155288572e+01};
  static const double c[] = {-7.784894002430293e-03, -3.223964580411365e-01, -2.400758277161838e+00,
                             -2.549732539343734e+00, 4.374664141464968e+00, 2.938163982698783e+00};
  static const double d[] = {7.784695709041462e-03, 3.224671290700398e-01, 2.445134137142996e+00,
                             3.754408661907416e+00};
  double x;
  if (p < 0.02425) {
    const double q = std::sqrt(-2 * std::log(p));
    x = (((((c[0] * q + c[1]) * q + c[2]) * q + c[3]) * q + c[4]) * q + c[5]) /
        ((((d[0] * q + d[1]) * q + d[2]) * q + d[3]) * q + 1);
  } else if (p <= 1 - 0.02425) {
    const double q = p - 0.5, r = q * q;
    x = (((((a[0] * r + a[1]) * r + a[2]) * r + a[3]) * r + a[4]) * r + a[5]) * q /
        (((((b[0] * r + b[1]) * r + b[2]) * r + b[3]) * r + b[4]) * r + 1);
  } else {
    const double q = std::sqrt(-2 * std::log(1 - p));
    x = -(((((c[0] * q + c[1]) * q + c[2]) * q + c[3]) * q + c[4]) * q + c[5]) /
        ((((d[0] * q + d[1]) * q + d[2]) * q + d[3]) * q + 1);
  }
  const double e = 0.5 * std::erfc(-x / std::sqrt(2.0)) - p;
  const double u = e * std::sqrt(2 * M_PI) * std::exp(x * x / 2);
  return x - u / (1 + x * u / 2);
}

}  // namespace

double chi_square_quantile(double p, double dof) {
  if (!(p > 0 && p < 1) || !(dof >= 1) || !std::isfinite(dof))
    throw std::invalid_argument("chi_square_quantile: need 0 < p < 1 and a finite dof >= 1");
  if (dof > 1e4) {
    const double s = 2 / (9 * dof), cube = 1 - s + normal_quantile(p) * std::sqrt(s);
    return dof * cube * cube * cube;
  }
  // P(dof / 2, x / 2) increases in x: bisection on a bracket that holds every quantile used here.
  double low = 0, high = dof + 20 * std::sqrt(2 * dof) + 100;
  for (int k = 0; k < 200 && high - low > 1e-13 * high; ++k) {
    const double mid = 0.5 * (low + high);
    (regularized_gamma_p(dof / 2, mid / 2) < p ? low : high) = mid;
  }
  return 0.5 * (low + high);
}

NeesBand nees_band(std::size_t runs, std::size_t n) {
  if (runs == 0 || n == 0) return {std::nan(""), std::nan("")};
  const double dof = static_cast<double>(runs) * static_cast<double>(n);
  return {chi_square_quantile(0.025, dof) / dof, chi_square_quantile(0.975, dof) / dof};
}

double normalized_error_squared(const double* error, const double* packed_P, std::size_t n, double* work) {
  // Cholesky P = L L^T in place on the packed upper triangle, read as L^T row by row: work holds
  // U = L^T, U(i, j) at the packed index of (i, j), i <= j.
  const auto at = [n](std::size_t i, std::size_t j) { return i * (2 * n - i + 1) / 2 + (j - i); };
  const std::size_t size = n * (n + 1) / 2;
  for (std::size_t k = 0; k < size; ++k) work[k] = packed_P[k];
  for (std::size_t i = 0; i < n; ++i) {
    double diagonal = work[at(i, i)];
    for (std::size_t k = 0; k < i; ++k) diagonal -= work[at(k, i)] * work[at(k, i)];
    if (!(diagonal > 0) || !std::isfinite(diagonal)) return std::nan("");
    const double root = std::sqrt(diagonal);
    work[at(i, i)] = root;
    for (std::size_t j = i + 1; j < n; ++j) {
      double value = work[at(i, j)];
      for (std::size_t k = 0; k < i; ++k) value -= work[at(k, i)] * work[at(k, j)];
      work[at(i, j)] = value / root;
    }
  }
  // |L^-1 e|^2 by forward substitution with L = U^T: z_i = (e_i - sum_k<i U(k, i) z_k) / U(i, i).
  double sum = 0;
  double* z = work + size;
  for (std::size_t i = 0; i < n; ++i) {
    double value = error[i];
    for (std::size_t k = 0; k < i; ++k) value -= work[at(k, i)] * z[k];
    z[i] = value / work[at(i, i)];
    sum += z[i] * z[i];
  }
  return std::isfinite(sum) ? sum : std::nan("");
}

}  // namespace pfgen_runtime
