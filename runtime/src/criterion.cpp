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
  double top = -std::numeric_limits<double>::infinity();
  for (double I : integrals) {
    if (!std::isfinite(I)) throw std::invalid_argument("criterion: an integral of L is not finite");
    top = std::max(top, I);
  }
  // w_r = exp((I_r - max I) / eps) lies in (0, 1] and is 1 at the maximum: no overflow for any
  // I / eps, and the sums below are at least 1.
  const double N = static_cast<double>(integrals.size());
  double sum_w = 0, sum_w2 = 0, sum_I = 0;
  for (double I : integrals) {
    const double w = std::exp((I - top) / epsilon);
    sum_w += w;
    sum_w2 += w * w;
    sum_I += I;
  }
  const double mean_w = sum_w / N;
  out.J = top + epsilon * std::log(mean_w);
  out.ess = sum_w * sum_w / sum_w2;
  out.mean_integral = sum_I / N;
  if (integrals.size() < 2) {
    out.J_se = out.mean_integral_se = nan;
    return out;
  }
  // Second passes about the means (not sums of squares minus squared sums: w can be nearly
  // constant, and then the difference would be all round-off).
  double squares_w = 0, squares_I = 0;
  for (double I : integrals) {
    const double dw = std::exp((I - top) / epsilon) - mean_w, dI = I - out.mean_integral;
    squares_w += dw * dw;
    squares_I += dI * dI;
  }
  // Delta method on J = eps log(mean w) + const: dJ = eps d(mean w) / mean w, and mean w has the
  // standard error sd(w) / sqrt(N).
  out.J_se = epsilon * std::sqrt(squares_w / (N - 1)) / (std::sqrt(N) * mean_w);
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
