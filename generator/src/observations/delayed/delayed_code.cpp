// The delayed module's code generation: the grid its filters step on, and its part.
#include "pfgen/observations/delayed/delayed_code.hpp"

#include "pfgen_support/shortest_double.hpp"

namespace pfgen::codegen {

DelaySteps filter_delay_steps(const FilterEquations& eq, const CodegenOptions& options) {
  if (!options.grid_step)
    throw CodegenError("filter '" + eq.name + "': a filter for delayed observations steps on a fixed grid: give --dt "
                       "(or simulation: dt in the model file)");
  const DelaySteps steps = delay_steps(eq.delay, *options.grid_step);
  if (!steps.problem.empty()) throw CodegenError("filter '" + eq.name + "': " + steps.problem);
  return steps;
}

std::string delay_banner_line(const FilterEquations& eq, const DelaySteps& steps, double grid_step) {
  return "// Delayed observations: h = " + pfgen_support::shortest_double(eq.delay.to_double()) + " = " +
         std::to_string(steps.steps) + " steps of dt = " + pfgen_support::shortest_double(grid_step) +
         "; the caller supplies dy over each step of this dt.\n";
}

const ObservationCode& delayed_observation_code() {
  static const DelayedCode part;
  return part;
}

}  // namespace pfgen::codegen
