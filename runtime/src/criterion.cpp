#include "pfgen_runtime/criterion.hpp"

#include <algorithm>
#include <cmath>
#include <limits>
#include <stdexcept>
#include <string>

namespace pfgen_runtime {

namespace {
constexpr double nan = std::numeric_limits<double>::quiet_NaN();
}

CriterionEstimate estimate_criterion(const std::vector<double>& integrals, double epsilon) {
  if (!(epsilon > 0) || !std::isfinite(epsilon))
    throw std::invalid_argument("criterion: epsilon must be finite and > 0");
  CriterionEstimate out;
  out.runs = integrals.size();
  if (integrals.empty()) {
    out.J = out.J_se = out.ess = out.mean_integral = out.mean_integral_se = nan;
    return out;
  }
  double sum_I = 0;
  for (double I : integrals) {
    if (!std::isfinite(I)) throw std::invalid_argument("criterion: an integral of L is not finite");
    sum_I += I;
  }
  const double N = static_cast<double>(integrals.size());
  out.mean_integral = sum_I / N;
  // J = mean I + eps log mean exp(u_r), u_r = (I_r - mean I) / eps. Written about the mean, J is
  // exact in both limits:
  //  - small spread (max u <= 1, every large eps): e_r = expm1(u_r) keeps each run's tiny
  //    departure, and eps log1p(mean e) -> mean I + var(I) / (2 eps) with no cancellation (a shift
  //    by the maximum would leave J = max I + eps log(mean w), the difference of two numbers of
  //    size eps, all round-off for eps >= 1e12);
  //  - large spread (small eps): w_r = exp((I_r - max I) / eps) lies in (0, 1] and is 1 at the
  //    maximum, so nothing overflows and the few runs that carry J are kept.
  double top = -std::numeric_limits<double>::infinity();
  for (double I : integrals) top = std::max(top, I);
  const bool about_mean = (top - out.mean_integral) / epsilon <= 1;
  // In either form the weight is scale * (1 + e_r): about the mean scale = 1 and e_r = expm1(u_r);
  // about the maximum scale = 1 and e_r = w_r - 1 (w_r itself carries the information there).
  auto excess = [&](double I) {
    return about_mean ? std::expm1((I - out.mean_integral) / epsilon) : std::exp((I - top) / epsilon) - 1;
  };
  double sum_e = 0, sum_w2 = 0;
  for (double I : integrals) {
    const double e = excess(I);
    sum_e += e;
    sum_w2 += (1 + e) * (1 + e);
  }
  const double mean_e = sum_e / N, mean_w = 1 + mean_e;
  out.J = about_mean ? out.mean_integral + epsilon * std::log1p(mean_e) : top + epsilon * std::log(mean_w);
  out.ess = (N * mean_w) * (N * mean_w) / sum_w2;
  if (integrals.size() < 2) {
    out.J_se = out.mean_integral_se = nan;
    return out;
  }
  // Second passes about the means (not sums of squares minus squared sums: w can be nearly
  // constant, and then the difference would be all round-off).
  double squares_w = 0, squares_I = 0;
  for (double I : integrals) {
    // eps dw, not dw: for eps -> infinity dw = O(1 / eps), and its square would underflow to 0.
    const double scaled_dw = epsilon * (excess(I) - mean_e), dI = I - out.mean_integral;
    squares_w += scaled_dw * scaled_dw;
    squares_I += dI * dI;
  }
  // Delta method on J = eps log(mean w) + const: dJ = eps d(mean w) / mean w, and mean w has the
  // standard error sd(w) / sqrt(N). As eps -> infinity, eps sd(w) -> sd(I): J_se -> mean I's.
  out.J_se = std::sqrt(squares_w / (N - 1)) / (std::sqrt(N) * mean_w);
  out.mean_integral_se = std::sqrt(squares_I / (N - 1) / N);
  return out;
}

std::string criterion_weight_problem(const Eigen::MatrixXd& weight, std::size_t n) {
  if (weight.size() == 0) return {};
  const auto size = static_cast<Eigen::Index>(n);
  if (weight.rows() != size || weight.cols() != size)
    return "the weight M must be " + std::to_string(n) + " x " + std::to_string(n);
  if (!weight.allFinite()) return "the weight M has a non-finite entry";
  for (Eigen::Index i = 0; i < size; ++i)
    for (Eigen::Index j = i + 1; j < size; ++j)
      if (weight(i, j) != weight(j, i))
        return "the weight M is not symmetric (row " + std::to_string(i + 1) + ", column " + std::to_string(j + 1) + ")";
  return {};
}

}  // namespace pfgen_runtime
