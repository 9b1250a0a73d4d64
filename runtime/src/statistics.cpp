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

}  // namespace pfgen_runtime
