#pragma once
// One grid step of a filter, refined where a single step would be numerically unstable.
//
// A generated filter's step() is an explicit (Heun) step of fixed length. Its stability needs
// roughly |P A^T (BB^T)^-1 A| dt < 1: the Riccati term -P A^T R^-1 A P dt changes P by P itself
// when P dt ~ 1. Where the truth runs far out (paper 000's heavy-tailed Ito state reaches 100s,
// and its optimal filter's P ~ 0.1 m^2 follows), a fixed dt becomes unstable and the filter would
// "diverge" because of the integrator, not because of its equations. So: take the step; if any
// entry of P changed by more than `tolerance` of its scale, or anything became non-finite, undo
// it and take two half steps, each with half of dy, recursively. Halving dy is exact for the
// filter's equations: y enters only through dm = ... + K(P) dy, and K depends on P alone, which
// has no dy term, so the Ito and Stratonovich forms agree and y may be taken as linear across the
// step (docs/theory.md §7). The refinement is deterministic (no random numbers) and costs one copy of
// the state and one comparison per step where nothing happens.
//
// It guards stability, not accuracy: a step that changes P little is kept even where
// P A^T R^-1 A dt is near 1, at the edge of Heun's stability region, where the filter settles
// slowly (tests/test_runtime_filter_stepping.cpp: 3 % off). dt still sets the accuracy.
//
// The scale of P_ij is sqrt(|P_ii P_jj|) (its Cauchy-Schwarz bound) plus `floor`, so an
// off-diagonal entry passing through zero, or a singular P (paper 001's P0), is not refined.
#include <cmath>
#include <cstddef>
#include <cstdint>
#include <stdexcept>
#include <vector>

#include "pfgen_runtime/guards.hpp"
#include "pfgen_runtime/lane_flag.hpp"
#include "pfgen_runtime/lane_pack.hpp"


namespace pfgen_runtime {

struct FilterStepControl {
  bool adaptive = true;     // false: exactly one step() per grid step
  double tolerance = 0.02;  // largest change of P_ij per step, relative to its scale
  double floor = 1e-9;      // added to every scale
  int max_depth = 20;       // sub-steps no shorter than dt / 2^max_depth
  // step() calls one grid step may take. A filter that needs more is blowing up or too stiff for
  // this dt: the run stops there (advance() returns 0) instead of spending up to 2^max_depth calls
  // on each grid step (a dense cubic filter spent 0.94 s a grid step before it was reported).
  std::uint64_t max_substeps = 4096;
};

class FilterStepper {
 public:
  // extra_capacity: the most entries after m and P a state it steps may have (set_extra_state).
  FilterStepper(std::size_t n, std::size_t p, const FilterStepControl& control, std::size_t extra_capacity = 0);
  // The entries after m and P of the states the next steps take (saved and restored with them); at most
  // extra_capacity. 0 unless set.
  void set_extra_state(std::size_t extra) {
    if (extra > capacity_ - filter_state_size(n_)) throw std::invalid_argument("filter stepper: too much extra state");
    size_ = filter_state_size(n_) + extra;
  }
  // Advances `state` over [t, t + dt] given dy (p entries) with `step`; returns the number of
  // step() calls that were kept (1 unless the step was refined), or 0 when the grid step would
  // need more than control.max_substeps calls: `state` is then mid-step and the run must stop.
  template <class Step>
  std::uint64_t advance(const Step& step, double* state, double t, double dt, const double* dy) {
    // The common case inline: save, step, check. Only a rejected step goes through advance_at.
    double* saved = saved_.data();
    for (std::size_t i = 0; i < size_; ++i) saved[i] = state[i];
    step(state, t, dt, dy);
    if (!control_.adaptive || control_.max_depth == 0 || acceptable(saved, state)) return 1;
    ++refined_;
    calls_ = 1;
    exhausted_ = false;
    const std::uint64_t kept = split(step, state, t, dt, dy, 0);
    return exhausted_ ? 0 : kept;
  }
  std::uint64_t refined_steps() const { return refined_; }  // grid steps that needed sub-steps

  // For steps taken elsewhere (several runs side by side): whether advance() would keep the step
  // from `before` to `after` as it is.
  bool keeps(const double* before, const double* after) const {
    return !control_.adaptive || control_.max_depth == 0 || acceptable(before, after);
  }
  // keeps() for W states side by side in W / 2 lane packs (lane_pack.hpp; W even, W between
  // entries): keep[c] keeps its ones only where lane 2c + k's step would be kept. reject_lanes'
  // tests, term for term; each entry's tests over every pack in turn, so that the loops over the
  // entries run once, not once a pack.
  template <std::size_t W>
  PFGEN_LANE_PACK_INLINE void keeps_packs(const double* before, const double* after, lane_pack::Pack* keep) const {
    namespace lp = lane_pack;
    constexpr std::size_t packs = W / lp::kLanes;
    if (!control_.adaptive || control_.max_depth == 0) return;
    for (std::size_t i = 0; i < n_; ++i)
      for (std::size_t c = 0; c < packs; ++c)
        keep[c] = lp::both(keep[c], lp::finite(lp::load(after + i * W + c * lp::kLanes)));
    const double* P0 = before + n_ * W;
    const double* P1 = after + n_ * W;
    const lp::Pack tolerance = lp::splat(control_.tolerance), floor = lp::splat(control_.floor);
    for (std::size_t i = 0, e = 0; i < n_; ++i)
      for (std::size_t j = i; j < n_; ++j, ++e) {
        const double* d_i = P0 + packed_diagonal(n_, i) * W;
        const double* d_j = P0 + packed_diagonal(n_, j) * W;
        for (std::size_t c = 0; c < packs; ++c) {
          const std::size_t lane = c * lp::kLanes;
          const lp::Pack p0 = lp::load(P0 + e * W + lane), p1 = lp::load(P1 + e * W + lane);
          const lp::Pack change = lp::abs(lp::subtract(p1, p0));
          lp::Pack too_large;
          if (i == j) {  // scale |P_ii| + floor
            too_large = lp::greater(change, lp::multiply(tolerance, lp::add(lp::abs(p0), floor)));
          } else {  // change <= tolerance (sqrt|P_ii P_jj| + floor), squared
            const lp::Pack excess = lp::subtract(lp::divide(change, tolerance), floor);
            const lp::Pack scale = lp::abs(lp::multiply(lp::load(d_i + lane), lp::load(d_j + lane)));
            too_large = lp::both(lp::greater(excess, lp::splat(0.0)), lp::greater(lp::multiply(excess, excess), scale));
          }
          keep[c] = lp::both(keep[c], lp::except(lp::finite(p1), too_large));
        }
      }
  }
  // What advance() does after its first step was not kept: `state` holds the grid step's start
  // again, and the step is taken in halves. Same return value as advance().
  template <class Step>
  std::uint64_t refine(const Step& step, double* state, double t, double dt, const double* dy) {
    double* saved = saved_.data();
    for (std::size_t i = 0; i < size_; ++i) saved[i] = state[i];
    ++refined_;
    calls_ = 1;
    exhausted_ = false;
    const std::uint64_t kept = split(step, state, t, dt, dy, 0);
    return exhausted_ ? 0 : kept;
  }

  // After advance() gave up (0): whether the filter's equations are finite at the grid step's
  // start, a finite state. A step of length 0 with dy = 0 leaves a state unchanged exactly when
  // its rates are finite; where they are not (a definition that cannot be computed there: 0/0,
  // the root of a negative number) no sub-step helps, and the run must not be called too stiff.
  template <class Step>
  bool equations_finite_at_start(const Step& step, double t) {
    for (std::size_t i = 0; i < size_; ++i) probe_[i] = saved_[i];
    step(probe_.data(), t, 0.0, zero_dy_.data());
    for (std::size_t i = 0; i < size_; ++i)
      if (!std::isfinite(probe_[i])) return false;
    return true;
  }

 private:
  // Undoes the step taken at `depth` (its start is saved there) and takes two halves with dy / 2.
  template <class Step>
  std::uint64_t split(const Step& step, double* state, double t, double dt, const double* dy, int depth) {
    const double* saved = saved_.data() + static_cast<std::size_t>(depth) * size_;
    for (std::size_t i = 0; i < size_; ++i) state[i] = saved[i];
    double* half_dy = half_dy_.data() + static_cast<std::size_t>(depth) * p_;
    for (std::size_t i = 0; i < p_; ++i) half_dy[i] = 0.5 * dy[i];
    const double half = 0.5 * dt;
    const std::uint64_t first = advance_at(step, state, t, half, half_dy, depth + 1);
    return first + advance_at(step, state, t + half, half, half_dy, depth + 1);
  }
  template <class Step>
  std::uint64_t advance_at(const Step& step, double* state, double t, double dt, const double* dy, int depth) {
    if (exhausted_ || ++calls_ > control_.max_substeps) {
      exhausted_ = true;
      return 0;
    }
    double* saved = saved_.data() + static_cast<std::size_t>(depth) * size_;
    for (std::size_t i = 0; i < size_; ++i) saved[i] = state[i];
    step(state, t, dt, dy);
    if (depth >= control_.max_depth || acceptable(saved, state)) return 1;
    return split(step, state, t, dt, dy, depth);
  }
  static bool finite(double x) { return x - x == 0; }  // false for inf and NaN; a compare that packs
  // Every entry finite, and no P_ij changed by more than tolerance (sqrt|P_ii P_jj| + floor).
  bool acceptable(const double* before, const double* after) const {
    LaneFlag keep = 1.0;
    reject_lanes(before, after, 1, &keep);
    return keep != 0;
  }
  // acceptable()'s tests for `width` states side by side, entry-major: keep[k] = 0 where lane k
  // fails one. One pass over the lanes per entry, which compilers vectorise; & rather than &&,
  // since both sides are cheap and free of side effects and a branch per lane would keep the loops
  // scalar.
  void reject_lanes(const double* before, const double* after, std::size_t width, LaneFlag* keep) const {
    const std::size_t w = width;
    for (std::size_t i = 0; i < n_; ++i)
      for (std::size_t k = 0; k < w; ++k) keep[k] = finite(after[i * w + k]) ? keep[k] : 0.0;
    const double* P0 = before + n_ * w;
    const double* P1 = after + n_ * w;
    const double tolerance = control_.tolerance, floor = control_.floor;
    for (std::size_t i = 0, e = 0; i < n_; ++i)
      for (std::size_t j = i; j < n_; ++j, ++e) {
        const double* p0 = P0 + e * w;
        const double* p1 = P1 + e * w;
        if (i == j) {  // scale |P_ii| + floor
          for (std::size_t k = 0; k < w; ++k) {
            const double change = std::abs(p1[k] - p0[k]);
            keep[k] = finite(p1[k]) & !(change > tolerance * (std::abs(p0[k]) + floor)) ? keep[k] : 0.0;
          }
          continue;
        }
        // change <= tolerance (sqrt|P_ii P_jj| + floor), without a square root on every step.
        const double* d_i = P0 + packed_diagonal(n_, i) * w;
        const double* d_j = P0 + packed_diagonal(n_, j) * w;
        for (std::size_t k = 0; k < w; ++k) {
          const double excess = std::abs(p1[k] - p0[k]) / tolerance - floor;
          keep[k] = finite(p1[k]) & !((excess > 0) & (excess * excess > std::abs(d_i[k] * d_j[k]))) ? keep[k] : 0.0;
        }
      }
  }

  std::size_t n_, p_, size_, capacity_;
  FilterStepControl control_;
  std::vector<double> saved_;    // (max_depth + 1) states
  std::vector<double> half_dy_;  // (max_depth + 1) increments
  std::vector<double> probe_, zero_dy_;  // equations_finite_at_start's state and dy
  std::uint64_t refined_ = 0;
  std::uint64_t calls_ = 0;  // step() calls of the grid step being refined
  bool exhausted_ = false;   // that grid step ran out of control_.max_substeps
};

}  // namespace pfgen_runtime
