#pragma once
// How many steps of dt a length is, when it is a whole number of them: a sampling period and an
// observation delay must be, for samples and delayed values to fall on the simulation grid. The
// generator's checks and the runtime's use the one rule, so they never disagree on a borderline
// dt: length / dt within a relative 1e-9 of a whole number N >= 0 (a decimal period or delay over
// a decimal dt is rarely exact in double: 0.8 / 0.001 = 799.9999999999999).
#include <cstddef>
#include <optional>

namespace pfgen_support {

// N, or nothing when length / dt is not finite, negative, or not within 1e-9 * max(1, N) of N.
// Callers bound N from above (and from below, when 0 steps is no use to them) before using it.
std::optional<double> whole_steps(double length, double dt);

}  // namespace pfgen_support
