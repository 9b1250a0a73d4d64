#pragma once
// A delayed observation's filters keep m (and x*) over the last h / dt grid steps, and the
// simulator reads the truth h / dt steps back: both need h to be a whole number D of steps of the
// grid dt. One rule for `pfgen codegen --dt`, the model's `simulation: dt` and `pfgen simulate --dt`.
#include <cstddef>
#include <string>

#include <ginac/ginac.h>

namespace pfgen {

// The history a delayed filter may keep: D <= 10^7 grid steps (80 MB of doubles per state), so
// that h = 1e9 with dt = 1e-3 is refused before anything is allocated.
inline constexpr std::size_t kMaxDelaySteps = 10000000;

struct DelaySteps {
  std::size_t steps = 0;  // D, when `problem` is empty
  std::string problem;    // why h is not a whole number of steps of dt, in one sentence
};

// D = h / dt when that is a whole number within a relative 1e-9 (dt is a double, h exact) and at
// most kMaxDelaySteps; dt must be positive and finite.
DelaySteps delay_steps(const GiNaC::numeric& delay, double dt);

}  // namespace pfgen
