// A filter's timing (runtime/include/pfgen_runtime/filter_timing.hpp) on its own: what each of the
// three families does with one grid step, what it refuses, and that a FilterModel's copies step
// independently. The Monte Carlo engine and run_filter call only advance(); the tests of the
// engine (test_runtime_monte_carlo, test_runtime_sampled, test_runtime_delayed) check the runs.
#include <catch2/catch.hpp>

#include <cmath>
#include <vector>

#include "pfgen_runtime/filter_timing.hpp"
#include "pfgen_runtime/simulation.hpp"

using namespace pfgen_runtime;

namespace {

using Stop = FilterStepOutcome::Stop;

// A grid of 6 steps of 0.25 from t0 = 1, and increments dy_k = k (p = 1).
struct Run {
  TimeGrid grid{1.0, 0.25, 6};
  std::vector<double> dy{0, 1, 2, 3, 4, 5};
  std::vector<double> samples{10, 20, 30};  // p = 1, a sample every 2 grid steps
  FilterInput input() const { return {grid, 1, dy.data(), samples.data(), 2, 0.5}; }
};

}  // namespace

TEST_CASE("filter timing: grid steps take each grid step on its increment, and say why they gave up", "[runtime][unit]") {
  Run run;
  std::vector<double> seen;
  const GridSteps timing([&seen](double* state, double t, double dt, const double* dy) {
    seen.insert(seen.end(), {t, dt, dy[0]});
    state[0] += dy[0];
  });
  FilterStepper stepper(1, 1, FilterStepControl{});
  double state[2] = {0.0, 1.0};
  for (std::size_t k = 0; k < 3; ++k) CHECK(timing.advance(stepper, state, run.input(), k).stop == Stop::none);
  CHECK(seen == std::vector<double>{1.0, 0.25, 0.0, 1.25, 0.25, 1.0, 1.5, 0.25, 2.0});
  CHECK(state[0] == 3.0);
  CHECK_FALSE(timing.takes_samples());
  CHECK(timing.refines_steps());
  CHECK(timing.extra_state() == 0);
  CHECK(timing.lanes() == nullptr);  // no lanes form given

  // A step whose P is NaN wherever it starts gives up as undefined; one whose P grows without
  // bound only over a step, as too stiff.
  const GridSteps undefined([](double* state, double, double, const double*) { state[1] = std::nan(""); });
  const FilterStepOutcome gave_up = undefined.advance(stepper, state, run.input(), 4);
  CHECK(gave_up.stop == Stop::equations_undefined);
  CHECK(gave_up.t == 2.0);
  state[1] = 1.0;
  const GridSteps stiff([](double* state, double, double dt, const double*) {
    if (dt > 1e-300) state[1] = std::nan("");
  });
  CHECK(stiff.advance(stepper, state, run.input(), 1).stop == Stop::too_stiff);
}

TEST_CASE("filter timing: a fixed step is taken once per grid step, unrefined, on its own grid only", "[runtime][unit]") {
  Run run;
  run.grid.t0 = 0;
  std::vector<double> seen;
  // P jumps from 1 to 100: FilterStepper would refine such a step.
  const FixedSteps timing(
      [&seen](double* state, double t, double dt, const double* dy) {
        seen.insert(seen.end(), {t, dt, dy[0]});
        state[1] *= 100;
      },
      0.25, 3);
  FilterStepper stepper(1, 1, FilterStepControl{});
  double state[5] = {0.0, 1.0, 0.0, 0.0, 0.0};
  CHECK(timing.advance(stepper, state, run.input(), 2).stop == Stop::none);
  CHECK(seen == std::vector<double>{0.5, 0.25, 2.0});
  CHECK(state[1] == 100.0);
  CHECK(stepper.refined_steps() == 0);
  CHECK(timing.extra_state() == 3);
  CHECK_FALSE(timing.refines_steps());
  timing.check_grid("ring", run.grid);
  CHECK_THROWS_WITH(timing.check_grid("ring", TimeGrid{0.0, 0.5, 6}), Catch::Contains("filter 'ring' was generated for the grid"));
  CHECK_THROWS_WITH(timing.check_grid("ring", TimeGrid{1.0, 0.25, 6}), Catch::Contains("starts after 0"));
  CHECK_THROWS_WITH(FixedSteps([](double*, double, double, const double*) {}, 0.0, 3),
                    Catch::Contains("a fixed-step filter needs a finite grid step > 0"));
}

TEST_CASE("filter timing: sampled steps predict in sub-steps and absorb a sample at each period's end", "[runtime][unit]") {
  Run run;
  std::vector<double> predictions, updates;
  int calls = 0;
  const SampledSteps timing(
      3, [&predictions](double*, double t, double dt) { predictions.insert(predictions.end(), {t, dt}); },
      [&updates, &calls](double*, double t, const double* y) {
        updates.insert(updates.end(), {t, y[0]});
        return ++calls < 2;  // the second update fails
      });
  FilterStepper stepper(1, 1, FilterStepControl{});
  double state[2] = {0.0, 1.0};
  // Grid steps 0 and 1 make up the first period [1, 1.5]: 3 predictions of 0.5 / 3 (1 then 2 of
  // them: u < (k' + 1) 3 / 2), then the update with the first sample at t = 1.5.
  const FilterStepOutcome first = timing.advance(stepper, state, run.input(), 0);
  CHECK(first.stop == Stop::none);
  CHECK(first.sample == -1);
  const FilterStepOutcome second = timing.advance(stepper, state, run.input(), 1);
  CHECK(second.stop == Stop::none);
  CHECK(second.sample == 0);
  CHECK(second.t == 1.5);
  const double delta = 0.5 / 3;
  CHECK(predictions == std::vector<double>{1.0, delta, 1.0 + delta, delta, 1.0 + 2 * delta, delta});
  CHECK(updates == std::vector<double>{1.5, 10.0});
  (void)timing.advance(stepper, state, run.input(), 2);
  const FilterStepOutcome failed = timing.advance(stepper, state, run.input(), 3);
  CHECK(failed.stop == Stop::update_failed);
  CHECK(failed.t == 2.0);
  CHECK(updates.back() == 20.0);
  CHECK(timing.takes_samples());
  CHECK_THROWS_WITH(SampledSteps(0, [](double*, double, double) {}, [](double*, double, const double*) { return true; }),
                    Catch::Contains("at least one prediction sub-step"));
}

TEST_CASE("filter timing: a FilterModel's copies step independently, and run_filter refuses a sampled filter", "[runtime][unit]") {
  FilterModel filter("counting", 1, 1, [](double* state) { state[0] = state[1] = 0; },
                     std::make_unique<GridSteps>([count = 0.0](double* state, double, double, const double*) mutable {
                       state[0] = ++count;
                     }));
  const FilterModel copy = filter;
  FilterStepper stepper(1, 1, FilterStepControl{});
  Run run;
  double a[2] = {0, 1}, b[2] = {0, 1};
  (void)filter.timing->advance(stepper, a, run.input(), 0);
  (void)filter.timing->advance(stepper, a, run.input(), 1);
  (void)copy.timing->advance(stepper, b, run.input(), 0);
  CHECK(a[0] == 2.0);
  CHECK(b[0] == 1.0);  // its own count, not the original's

  const FilterModel sampled("sampled", 1, 1, [](double* state) { state[0] = state[1] = 0; },
                            std::make_unique<SampledSteps>(
                                1, [](double*, double, double) {}, [](double*, double, const double*) { return true; }));
  TruthRun truth;
  truth.grid = run.grid;
  truth.completed_steps = 1;
  truth.dy = Eigen::MatrixXd::Zero(1, 1);
  CHECK_THROWS_WITH(run_filter(sampled, truth), Catch::Contains("run_filter: filter 'sampled'"));
}
