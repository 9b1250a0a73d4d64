#include "pfgen/model/delay_grid.hpp"

#include <cmath>

#include "pfgen_support/shortest_double.hpp"
#include "pfgen_support/whole_steps.hpp"

namespace pfgen {

DelaySteps delay_steps(const GiNaC::numeric& delay, double dt) {
  DelaySteps out;
  const double h = delay.to_double();
  const std::string where =
      "the delay h = " + pfgen_support::shortest_double(h) + " and the step dt = " + pfgen_support::shortest_double(dt);
  if (!(dt > 0) || !std::isfinite(dt)) {
    out.problem = "the step dt = " + pfgen_support::shortest_double(dt) + " must be positive and finite";
    return out;
  }
  const double ratio = h / dt;
  if (!std::isfinite(ratio) || ratio > static_cast<double>(kMaxDelaySteps)) {
    out.problem = where + ": h / dt is above the limit of " + std::to_string(kMaxDelaySteps) +
                  " steps of history; take a larger dt";
    return out;
  }
  const std::optional<double> whole = pfgen_support::whole_steps(h, dt);
  if (!whole) {
    out.problem = where + ": h must be a whole number of steps (h / dt = " + pfgen_support::shortest_double(ratio) + ")";
    return out;
  }
  if (*whole < 1 && h > 0) {  // a step longer than the delay rounds h / dt to 0 steps, which no history holds
    out.problem = where + ": h must be at least one step (h / dt = " + pfgen_support::shortest_double(ratio) + ")";
    return out;
  }
  out.steps = static_cast<std::size_t>(*whole);
  return out;
}

}  // namespace pfgen
