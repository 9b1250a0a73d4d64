#include "pfgen_runtime/filter_stepping.hpp"

#include <cmath>
#include <stdexcept>

#include "pfgen_runtime/guards.hpp"

namespace pfgen_runtime {

FilterStepper::FilterStepper(std::size_t n, std::size_t p, const FilterStepControl& control)
    : n_(n), p_(p), size_(filter_state_size(n)), control_(control) {
  if (control.max_depth < 0 || !(control.tolerance > 0) || !(control.floor >= 0))
    throw std::invalid_argument("filter step control: need max_depth >= 0, tolerance > 0, floor >= 0");
  const auto levels = static_cast<std::size_t>(control.max_depth) + 1;
  saved_.assign(levels * size_, 0.0);
  half_dy_.assign(levels * p_, 0.0);
  for (std::size_t i = 0, offset = n; i < n; offset += n - i, ++i) diagonal_.push_back(offset);
}

bool FilterStepper::acceptable(const double* before, const double* after) const {
  for (std::size_t i = 0; i < n_; ++i)
    if (!std::isfinite(after[i])) return false;
  const double* P0 = before + n_;
  const double* P1 = after + n_;
  const double tolerance = control_.tolerance, floor = control_.floor;
  for (std::size_t i = 0, k = 0; i < n_; ++i)
    for (std::size_t j = i; j < n_; ++j, ++k) {
      if (!std::isfinite(P1[k])) return false;
      const double change = std::abs(P1[k] - P0[k]);
      if (i == j) {  // scale |P_ii| + floor
        if (change > tolerance * (std::abs(P0[k]) + floor)) return false;
        continue;
      }
      // change <= tolerance (sqrt|P_ii P_jj| + floor), without a square root on every step.
      const double excess = change / tolerance - floor;
      if (excess > 0 && excess * excess > std::abs(before[diagonal_[i]] * before[diagonal_[j]])) return false;
    }
  return true;
}

}  // namespace pfgen_runtime
