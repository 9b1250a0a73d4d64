#include "pfgen_runtime/guards.hpp"

#include <algorithm>
#include <cmath>
#include <limits>
#include <sstream>
#include <stdexcept>

#include <Eigen/Eigenvalues>

namespace pfgen_runtime {

std::string DivergenceEvent::describe() const {
  std::ostringstream out;
  out.precision(10);
  out << "entry " << index << " is " << value;
  if (kind == DivergenceKind::bound_exceeded) out << " (beyond the bound)";
  out << " at t = " << t;
  return out.str();
}

DivergenceGuard::DivergenceGuard(double bound) : bound_(bound) {
  if (!(bound > 0)) throw std::invalid_argument("divergence guard: the bound must be positive");
}

DivergenceEvent DivergenceGuard::event(double t, std::size_t index, double value) const {
  return DivergenceEvent{t, index, value,
                         std::isfinite(value) ? DivergenceKind::bound_exceeded : DivergenceKind::non_finite};
}

Eigen::MatrixXd unpack_symmetric(const double* upper, std::size_t n) {
  Eigen::MatrixXd P(n, n);
  std::size_t k = 0;
  for (std::size_t i = 0; i < n; ++i)
    for (std::size_t j = i; j < n; ++j, ++k) P(i, j) = P(j, i) = upper[k];
  return P;
}

Eigen::VectorXd pack_upper(const Eigen::Ref<const Eigen::MatrixXd>& P) {
  if (P.rows() != P.cols()) throw std::invalid_argument("pack_upper: P must be square");
  const auto n = static_cast<std::size_t>(P.rows());
  Eigen::VectorXd packed(packed_size(n));
  std::size_t k = 0;
  for (Eigen::Index i = 0; i < P.rows(); ++i)
    for (Eigen::Index j = i; j < P.cols(); ++j) packed[k++] = P(i, j);
  return packed;
}

std::string CovarianceCheck::describe() const {
  std::ostringstream out;
  out.precision(6);
  if (!finite) return "P has a non-finite entry";
  if (asymmetry > threshold) {
    out << "P is not symmetric: max |P - P^T| = " << asymmetry;
    return out.str();
  }
  out << "least eigenvalue of P " << min_eigenvalue << (ok ? " >= " : " < ") << -threshold
      << (ok ? " (positive semi-definite)" : " (not positive semi-definite)");
  return out.str();
}

CovarianceGuard::CovarianceGuard(double relative_tolerance, double absolute_tolerance)
    : relative_tolerance_(relative_tolerance), absolute_tolerance_(absolute_tolerance) {
  if (!(relative_tolerance >= 0) || !(absolute_tolerance >= 0))
    throw std::invalid_argument("covariance guard: tolerances must be non-negative");
}

CovarianceCheck CovarianceGuard::check_matrix(const Eigen::Ref<const Eigen::MatrixXd>& P) const {
  if (P.rows() != P.cols()) throw std::invalid_argument("covariance guard: P must be square");
  CovarianceCheck result;
  if (!P.allFinite()) {
    result.ok = false;
    result.finite = false;
    result.min_eigenvalue = std::numeric_limits<double>::quiet_NaN();
    return result;
  }
  result.asymmetry = P.rows() > 0 ? (P - P.transpose()).cwiseAbs().maxCoeff() : 0.0;
  const Eigen::MatrixXd symmetric = 0.5 * (P + P.transpose());
  Eigen::SelfAdjointEigenSolver<Eigen::MatrixXd> solver(symmetric, Eigen::EigenvaluesOnly);
  const Eigen::VectorXd& eigenvalues = solver.eigenvalues();  // ascending
  result.min_eigenvalue = eigenvalues.size() > 0 ? eigenvalues[0] : 0.0;
  result.max_abs_eigenvalue = eigenvalues.size() > 0 ? eigenvalues.cwiseAbs().maxCoeff() : 0.0;
  result.threshold = absolute_tolerance_ + relative_tolerance_ * result.max_abs_eigenvalue;
  result.ok = result.asymmetry <= result.threshold && result.min_eigenvalue >= -result.threshold;
  return result;
}

CovarianceCheck CovarianceGuard::check_filter_state(const double* state, std::size_t n) const {
  const double* P = state + n;
  if (n > 2) return check_matrix(unpack_symmetric(P, n));
  // n = 1, 2: closed-form eigenvalues, no allocation (this runs after every filter step).
  CovarianceCheck result;
  for (std::size_t k = 0; k < packed_size(n); ++k)
    if (!std::isfinite(P[k])) {
      result.ok = false;
      result.finite = false;
      result.min_eigenvalue = std::numeric_limits<double>::quiet_NaN();
      return result;
    }
  double low, high;
  if (n == 1) {
    low = high = P[0];
  } else {
    const double mean = 0.5 * (P[0] + P[2]), half_difference = 0.5 * (P[0] - P[2]);
    const double radius = std::hypot(half_difference, P[1]);
    low = mean - radius;
    high = mean + radius;
  }
  result.min_eigenvalue = low;
  result.max_abs_eigenvalue = std::max(std::abs(low), std::abs(high));
  result.threshold = absolute_tolerance_ + relative_tolerance_ * result.max_abs_eigenvalue;
  result.ok = result.min_eigenvalue >= -result.threshold;
  return result;
}

}  // namespace pfgen_runtime
