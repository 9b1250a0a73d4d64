#include "pfgen_runtime/filter_timing.hpp"

#include <cmath>
#include <cstdio>
#include <stdexcept>

namespace pfgen_runtime {

void FilterTiming::check_grid(const std::string&, const TimeGrid&) const {}  // any grid

FilterStepOutcome GridSteps::advance(FilterStepper& stepper, double* state, const FilterInput& input,
                                     std::size_t k) const {
  const double t = input.grid.time(k);
  stepper.set_extra_state(extra_state_);
  if (stepper.advance(step_, state, t, input.grid.dt, input.dy + k * input.p) != 0) return {};
  using Stop = FilterStepOutcome::Stop;  // given up mid-step
  return {stepper.equations_finite_at_start(step_, t) ? Stop::too_stiff : Stop::equations_undefined, t};
}

FixedSteps::FixedSteps(FilterStepFunction step, double fixed_dt, std::size_t extra_state)
    : step_(std::move(step)), fixed_dt_(fixed_dt), extra_state_(extra_state) {
  if (!(fixed_dt > 0) || !std::isfinite(fixed_dt))
    throw std::invalid_argument("a fixed-step filter needs a finite grid step > 0");
}

void FixedSteps::check_grid(const std::string& name, const TimeGrid& grid) const {
  if (std::abs(grid.dt - fixed_dt_) > 1e-9 * fixed_dt_ || grid.t0 != 0) {
    char text[200];
    std::snprintf(text, sizeof text, "was generated for the grid t_k = k dt, dt = %.17g; this one has dt = %.17g%s",
                  fixed_dt_, grid.dt, grid.t0 != 0 ? " and starts after 0" : "");
    throw std::invalid_argument("filter '" + name + "' " + text);
  }
}

FilterStepOutcome FixedSteps::advance(FilterStepper&, double* state, const FilterInput& input, std::size_t k) const {
  step_(state, input.grid.time(k), input.grid.dt, input.dy + k * input.p);  // once per grid step, never refined
  return {};
}

SampledSteps::SampledSteps(std::size_t substeps, FilterPredictFunction predict, FilterUpdateFunction update,
                           std::size_t extra_state)
    : substeps_(substeps), predict_(std::move(predict)), update_(std::move(update)), extra_state_(extra_state) {
  if (substeps == 0) throw std::invalid_argument("a sampled filter needs at least one prediction sub-step");
}

FilterStepOutcome SampledSteps::advance(FilterStepper&, double* state, const FilterInput& input, std::size_t k) const {
  const std::size_t N = input.steps_per_sample, sample = k / N, within = k % N;
  const double period = input.period, delta = period / static_cast<double>(substeps_);
  const double start = input.grid.t0 + static_cast<double>(sample) * period;
  for (std::size_t u = within * substeps_ / N; u < (within + 1) * substeps_ / N; ++u)
    predict_(state, start + static_cast<double>(u) * delta, delta);
  if (within + 1 != N) return {};
  const double t = input.grid.t0 + static_cast<double>(sample + 1) * period;  // t_k = t0 + k T, as draw_samples
  if (!update_(state, t, input.samples + sample * input.p)) return {FilterStepOutcome::Stop::update_failed, t};
  return {FilterStepOutcome::Stop::none, t, static_cast<std::ptrdiff_t>(sample)};
}

}  // namespace pfgen_runtime
