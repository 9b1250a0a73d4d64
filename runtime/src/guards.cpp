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
  if (kind == DivergenceKind::too_stiff) {
    out << "a grid step needs more sub-steps than allowed at t = " << t << " (too stiff for this dt)";
    return out.str();
  }
  if (kind == DivergenceKind::equations_undefined) {
    out << "the filter's equations are not finite at its own state at t = " << t
        << " (a definition such as a Cholesky entry cannot be computed there)";
    return out.str();
  }
  if (kind == DivergenceKind::unrealisable) {
    out << "the moments left the realisable set at t = " << t << " (" << (what.empty() ? "margin " + std::to_string(index) : what)
        << " is " << value << ")";
    return out.str();
  }
  if (kind == DivergenceKind::covariance_indefinite) {
    out << "the diffusion covariance G is not positive semi-definite at t = " << t << " (eigenvalue " << value << ")";
    return out.str();
  }
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

namespace {

// Eigenvalue check of a packed P on stack-sized matrices (MaxN >= n): same algorithm as
// check_matrix (Eigen's self-adjoint solver), without heap allocation.
template <int MaxN>
CovarianceCheck check_packed_bounded(const double* P, std::size_t n, double relative_tolerance,
                                     double absolute_tolerance) {
  using Matrix = Eigen::Matrix<double, Eigen::Dynamic, Eigen::Dynamic, 0, MaxN, MaxN>;
  CovarianceCheck result;
  const auto size = static_cast<Eigen::Index>(n);
  Matrix symmetric(size, size);
  std::size_t k = 0;
  for (Eigen::Index i = 0; i < size; ++i)
    for (Eigen::Index j = i; j < size; ++j, ++k) {
      if (!std::isfinite(P[k])) {
        result.ok = false;
        result.finite = false;
        result.min_eigenvalue = std::numeric_limits<double>::quiet_NaN();
        return result;
      }
      symmetric(i, j) = symmetric(j, i) = P[k];
    }
  Eigen::SelfAdjointEigenSolver<Matrix> solver(symmetric, Eigen::EigenvaluesOnly);
  const auto& eigenvalues = solver.eigenvalues();  // ascending
  result.min_eigenvalue = eigenvalues[0];
  result.max_abs_eigenvalue = eigenvalues.cwiseAbs().maxCoeff();
  result.threshold = absolute_tolerance + relative_tolerance * result.max_abs_eigenvalue;
  result.ok = result.min_eigenvalue >= -result.threshold;
  return result;
}

}  // namespace

bool CovarianceGuard::passes_filter_state_general(const double* state, std::size_t n) const {
  constexpr std::size_t max_n = 16;
  const double* P = state + n;
  if (n >= 2 && n <= max_n) {
    // Any eigenvalue bounds |P_ii| (Rayleigh quotient of e_i), so floor <= the threshold.
    double max_diagonal = 0;
    for (std::size_t i = 0; i < n; ++i) max_diagonal = std::max(max_diagonal, std::abs(P[packed_diagonal(n, i)]));
    const double floor = absolute_tolerance_ + relative_tolerance_ * max_diagonal;
    const double shift = 0.25 * floor;
    // A Cholesky factorisation that completes in floating point factors P + shift I + E exactly,
    // |E_ij| <= gamma_(n+1) sqrt(a_ii a_jj), so ||E||_2 <= n gamma_(n+1) max a_ii (Higham,
    // Accuracy and Stability, Thm 10.5); 3 n (n + 1) u covers gamma_(n+1) = (n+1)u / (1 - (n+1)u)
    // with room for the rounding of a_ii + shift. With it below the shift,
    // lambda_min(P) >= -2 shift = -floor / 2: a verdict of ok with room to spare for the
    // eigen-solver's own round-off.
    const double size = static_cast<double>(n);
    const double roundoff = 3.0 * size * (size + 1) * 0x1p-53 * (max_diagonal + shift);
    if (roundoff <= shift && max_diagonal <= std::numeric_limits<double>::max()) {
      if (n == 2) {  // the same test without a square root: a > 0 and det > 0
        const double a = P[0] + shift, d = P[2] + shift;
        if (a > 0 && a * d - P[1] * P[1] > 0) return true;  // NaN fails
      } else {
        double L[max_n * max_n];  // row-major, lower triangle used
        bool certified = true;
        // Row j of P's packed upper triangle starts at offset_j and holds P(j, j), P(j, j + 1), ...
        for (std::size_t j = 0, offset_j = 0; j < n && certified; offset_j += n - j, ++j) {
          for (std::size_t i = j; i < n; ++i) {
            double s = P[offset_j + (i - j)];  // P(j, i) = P(i, j)
            if (i == j) s += shift;
            for (std::size_t k = 0; k < j; ++k) s -= L[i * max_n + k] * L[j * max_n + k];
            if (i == j) {
              if (!(s > 0)) {  // NaN fails too
                certified = false;
                break;
              }
              L[j * max_n + j] = std::sqrt(s);
            } else {
              L[i * max_n + j] = s / L[j * max_n + j];
            }
          }
        }
        if (certified) return true;
      }
    }
  }
  return check_filter_state(state, n).ok;
}

CovarianceCheck CovarianceGuard::check_filter_state(const double* state, std::size_t n) const {
  const double* P = state + n;
  if (n > 8) return check_matrix(unpack_symmetric(P, n));
  if (n > 2) return check_packed_bounded<8>(P, n, relative_tolerance_, absolute_tolerance_);
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

std::optional<DivergenceEvent> check_realisability(const RealisabilityCheck& check, double t, const double* state,
                                                   std::vector<double>& margins) {
  if (!check.margins) return std::nullopt;
  margins.resize(check.names.size());
  check.margins(state, margins.data());
  for (std::size_t k = 0; k < margins.size(); ++k)
    if (!(margins[k] > 0)) return DivergenceEvent{t, k, margins[k], DivergenceKind::unrealisable, check.names[k]};
  static const CovarianceGuard covariance;
  if (check.n == 0 || covariance.passes_filter_state(state, check.n)) return std::nullopt;
  const CovarianceCheck P = covariance.check_filter_state(state, check.n);
  return DivergenceEvent{t, margins.size(), P.min_eigenvalue, DivergenceKind::unrealisable, "P's least eigenvalue"};
}

}  // namespace pfgen_runtime
