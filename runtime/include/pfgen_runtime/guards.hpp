#pragma once
// Guards that stop a run instead of letting NaN, inf or runaway values through as results.
//
// DivergenceGuard: a value is non-finite, or exceeds a bound in absolute value.
// CovarianceGuard: P is not symmetric positive *semi*-definite within a tolerance, judged by its
// eigenvalues (paper 001's P0, all ones, is singular and legal; a Cholesky test would reject it).
//
// Filter states are packed as generated code packs them: m (n entries), then the upper triangle
// of P row by row: (0,0), (0,1), ..., (0,n-1), (1,1), ..., (n-1,n-1).
#include <cmath>
#include <cstddef>
#include <vector>
#include <functional>
#include <limits>
#include <optional>
#include <string>

#include <Eigen/Core>

#include "pfgen_runtime/lane_flag.hpp"
#include "pfgen_runtime/lane_pack.hpp"

namespace pfgen_runtime {

// too_stiff: a grid step of the filter would need more sub-steps than FilterStepControl allows.
// equations_undefined: the filter's equations are not finite at its own finite state (one of its
// definitions cannot be computed there), so no sub-step would help.
// covariance_indefinite: the truth's diffusion covariance G(t, x) has a negative eigenvalue
// beyond round-off (a model's state-dependent G can lose definiteness as x moves; `value` is
// the eigenvalue).
// unrealisable: a moment filter's state left the set of moments a law can have (a realisability margin not
// positive; `index` is the margin, `value` its value).
enum class DivergenceKind { non_finite, bound_exceeded, too_stiff, covariance_indefinite, equations_undefined,
                            unrealisable };

struct DivergenceEvent {
  double t = 0;           // the grid time at which the offending value was first seen
  std::size_t index = 0;  // which entry
  double value = 0;       // the offending value (NaN or inf, or beyond the bound)
  DivergenceKind kind = DivergenceKind::non_finite;
  std::string what;       // unrealisable: what the margin says ("Pearson's bound of x1")
  std::string describe() const;  // e.g. "entry 0 is inf at t = 9.0901"
};

class DivergenceGuard {
 public:
  explicit DivergenceGuard(double bound = 1e8);  // bound > 0, may be +inf (finiteness only)
  double bound() const { return bound_; }
  // The first entry that is non-finite or has |value| > bound, reported at time t.
  std::optional<DivergenceEvent> check(double t, const double* values, std::size_t count) const {
    for (std::size_t i = 0; i < count; ++i)
      if (!(std::abs(values[i]) <= bound_)) return event(t, i, values[i]);  // NaN fails <=
    return std::nullopt;
  }
  std::optional<DivergenceEvent> check(double t, const Eigen::Ref<const Eigen::VectorXd>& values) const {
    return check(t, values.data(), static_cast<std::size_t>(values.size()));
  }
  // check() of `width` value lists side by side (entry-major: values[i * width + k]): pass[k] = 0
  // where list k would have an event; the others are left as they are.
  void pass_lanes(const double* values, std::size_t count, std::size_t width, LaneFlag* pass) const {
    for (std::size_t i = 0; i < count; ++i)
      for (std::size_t k = 0; k < width; ++k) pass[k] = std::abs(values[i * width + k]) <= bound_ ? pass[k] : 0.0;
  }
  // pass_lanes for W lists side by side in W / 2 lane packs (lane_pack.hpp; W even, W between
  // entries): pass[c] keeps its ones only where lane 2c + k's list has no event.
  template <std::size_t W>
  PFGEN_LANE_PACK_INLINE void passes_packs(const double* values, std::size_t count, lane_pack::Pack* pass) const {
    namespace lp = lane_pack;
    const lp::Pack bound = lp::splat(bound_);
    for (std::size_t i = 0; i < count; ++i)
      for (std::size_t c = 0; c < W / lp::kLanes; ++c)
        pass[c] = lp::both(pass[c], lp::less_equal(lp::abs(lp::load(values + i * W + c * lp::kLanes)), bound));
  }

 private:
  DivergenceEvent event(double t, std::size_t index, double value) const;
  double bound_;
};

inline constexpr std::size_t packed_size(std::size_t n) { return n * (n + 1) / 2; }
inline constexpr std::size_t filter_state_size(std::size_t n) { return n + packed_size(n); }
// Where P(i, i) sits in the packed upper triangle: after rows 0..i-1 of n, n-1, ... entries.
// In a whole filter state it is at n + packed_diagonal(n, i).
inline constexpr std::size_t packed_diagonal(std::size_t n, std::size_t i) { return i * (2 * n - i + 1) / 2; }

// The full symmetric n x n matrix from its packed upper triangle (n(n+1)/2 entries).
Eigen::MatrixXd unpack_symmetric(const double* upper, std::size_t n);
// The packed upper triangle of a square matrix (its lower triangle is not read).
Eigen::VectorXd pack_upper(const Eigen::Ref<const Eigen::MatrixXd>& P);

struct CovarianceCheck {
  bool ok = true;
  bool finite = true;
  double asymmetry = 0;       // max |P - P^T| (0 for packed input)
  double min_eigenvalue = 0;  // NaN when not finite
  double max_abs_eigenvalue = 0;
  double threshold = 0;  // min_eigenvalue must be >= -threshold
  std::string describe() const;
};

class CovarianceGuard {
 public:
  // P passes when it is finite, max|P - P^T| <= threshold and its least eigenvalue is
  // >= -threshold, threshold = absolute_tolerance + relative_tolerance * max |eigenvalue|.
  // The default relative tolerance, 1e-4, sits well above integrator noise: a rank-deficient P
  // has least eigenvalue exactly 0 (paper 001: no process noise keeps P0's rank 1 for all t), and a
  // second-order step leaves O(dt^2) |P| of either sign there (measured on paper 001's filters:
  // -2e-6 |P| at dt = 1e-2, -3e-8 at 1e-3, -3e-10 at 1e-4). A filter that really loses
  // definiteness goes negative by a sizeable fraction of |P|.
  explicit CovarianceGuard(double relative_tolerance = 1e-4, double absolute_tolerance = 1e-12);
  CovarianceCheck check_matrix(const Eigen::Ref<const Eigen::MatrixXd>& P) const;
  // P from a packed filter state [m (n), P upper triangle]. Closed form for n <= 2, stack-sized
  // matrices up to n = 8: no heap allocation there.
  CovarianceCheck check_filter_state(const double* state, std::size_t n) const;
  // The verdict of check_filter_state(state, n).ok, cheaply enough to run after every filter
  // step: first a Cholesky certificate (P + c I factors with positive pivots, c a quarter of the
  // least possible threshold, with the factorisation's round-off bounded below c; then
  // lambda_min(P) >= -threshold / 2), allocation-free for n <= 16 and a few ns for n = 1, 2. Only
  // when it fails (P indefinite or near the threshold, non-finite, or tolerances too tight for a
  // certificate) does it fall back to the eigenvalues of check_filter_state.
  bool passes_filter_state(const double* state, std::size_t n) const {
    if (n == 1) {  // check_filter_state's own closed form, inline
      LaneFlag pass = 1.0;
      pass_lanes_1(state + 1, 1, &pass);
      return pass != 0;
    }
    return passes_filter_state_general(state, n);
  }
  // passes_filter_state for n = 1 over `width` states side by side, P (their one entry) at
  // P[k]: pass[k] = 0 where it fails; the others are left as they are.
  void pass_lanes_1(const double* P, std::size_t width, LaneFlag* pass) const {
    for (std::size_t k = 0; k < width; ++k)
      pass[k] = (std::abs(P[k]) <= std::numeric_limits<double>::max()) &
                        (P[k] >= -(absolute_tolerance_ + relative_tolerance_ * std::abs(P[k])))
                    ? pass[k]
                    : 0.0;
  }
  // pass_lanes_1 for W states side by side in W / 2 lane packs (lane_pack.hpp; P[k] lane k's P):
  // pass[c] keeps its ones only where lane 2c + k's P passes.
  template <std::size_t W>
  PFGEN_LANE_PACK_INLINE void passes_packs_1(const double* P, lane_pack::Pack* pass) const {
    namespace lp = lane_pack;
    const lp::Pack largest = lp::splat(std::numeric_limits<double>::max());
    const lp::Pack absolute = lp::splat(absolute_tolerance_), relative = lp::splat(relative_tolerance_);
    for (std::size_t c = 0; c < W / lp::kLanes; ++c) {
      const lp::Pack p = lp::load(P + c * lp::kLanes), size = lp::abs(p);
      const lp::Pack threshold = lp::negate(lp::add(absolute, lp::multiply(relative, size)));
      pass[c] = lp::both(pass[c], lp::both(lp::less_equal(size, largest), lp::greater_equal(p, threshold)));
    }
  }

 private:
  bool passes_filter_state_general(const double* state, std::size_t n) const;
  double relative_tolerance_;
  double absolute_tolerance_;
};

// A moment filter's realisability margins (closure3, closure4): each positive while its moments can be a law's.
struct RealisabilityCheck {
  std::function<void(const double* state, double* margins)> margins;  // empty: the filter has none
  std::vector<std::string> names;                                       // what each margin says
  std::size_t n = 0;  // the filter's states (P is n x n; 0: P not checked)
};

// A moment filter's first realisability margin that is not positive (NaN included) at its state, if any, and then
// its P as a covariance (CovarianceGuard's default tolerance: the margins hold P's leading minors only up to four
// states): DivergenceKind::unrealisable. `margins` is work space. run_filter, the Monte Carlo engine and a record
// run stop on it.
std::optional<DivergenceEvent> check_realisability(const RealisabilityCheck& check, double t, const double* state,
                                                   std::vector<double>& margins);

}  // namespace pfgen_runtime
