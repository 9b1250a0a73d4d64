#include "pfgen_support/whole_steps.hpp"

#include <algorithm>
#include <cmath>

namespace pfgen_support {

std::optional<double> whole_steps(double length, double dt) {
  const double ratio = length / dt;
  if (!std::isfinite(ratio)) return std::nullopt;
  const double whole = std::round(ratio);
  if (!(whole >= 0) || std::abs(ratio - whole) > 1e-9 * std::max(1.0, whole)) return std::nullopt;
  return whole;
}

}  // namespace pfgen_support
