// A continuous filter stepped over several runs side by side (Worker::step_filter_lanes): one call
// of its GridSteps' step_lanes advances W runs over a grid step, and what step_filter does around
// its step (the stepper's check, the guards, the error sums) runs over the W lanes in packed passes
// of compile-time width. Only a lane that fails a check goes through step_filter's own sequence,
// alone. Each lane's arithmetic is step_filter's, in its order, so every run's results are bit for
// bit what it gives alone.
#include <algorithm>
#include <array>
#include <cmath>
#include <cstdint>

#include "pfgen_runtime/lane_pack.hpp"
#include "worker.hpp"

namespace pfgen_runtime::monte_carlo_detail {

std::size_t lane_width(const FilterModel& filter) {
  const GridSteps* form = filter.timing->lanes();
  const std::size_t w = form ? form->width() : 0;
  return w == 2 || w == 4 || w == 8 || w == 16 ? w : 0;
}

std::size_t Worker::group_path_size() const { return (plan_.grid.steps + 1) * plan_.n * width_; }
std::size_t Worker::group_dy_size() const { return plan_.grid.steps * plan_.p * width_; }

void Worker::reserve_lane_truths(std::size_t count) {
  const std::size_t groups = (count + width_ - 1) / width_;
  // Grown, never cleared: a lane's entries past its run's end, and an unused lane's, keep earlier
  // runs' finite values (or 0), which the filters' lanes step and never read.
  if (lane_path_.size() < groups * group_path_size()) lane_path_.resize(groups * group_path_size(), 0.0);
  if (lane_dy_.size() < groups * group_dy_size()) lane_dy_.resize(groups * group_dy_size(), 0.0);
}

void Worker::step_filter_lanes(std::size_t f, std::size_t first, std::size_t count, RunResult* runs) {
  switch (width_) {
    case 2: return step_filter_lanes<2>(f, first, count, runs);
    case 4: return step_filter_lanes<4>(f, first, count, runs);
    case 8: return step_filter_lanes<8>(f, first, count, runs);
    default: return step_filter_lanes<16>(f, first, count, runs);  // lane_width allows no other
  }
}

namespace {

using Flags = std::array<LaneFlag, 16>;  // W <= 16 entries used

// FilterStepper::keeps, the divergence guards and (n = 1) the PSD test over W lanes in W / 2 lane
// packs: pass[c] is all ones where lane 2c + k passes them all.
template <std::size_t W>
void packed_checks(const FilterStepper& stepper, const FilterGuardOptions& guards, std::size_t n, bool psd_packed,
                   const double* saved, const double* state, lane_pack::Pack* pass) {
  for (std::size_t c = 0; c < W / lane_pack::kLanes; ++c) pass[c] = lane_pack::all_set();
  stepper.keeps_packs<W>(saved, state, pass);
  guards.estimate_guard.passes_packs<W>(state, n, pass);
  guards.covariance_guard.passes_packs<W>(state + n * W, packed_size(n), pass);
  if (guards.check_psd && psd_packed) guards.psd.passes_packs_1<W>(state + W, pass);
}

}  // namespace

template <std::size_t W>
void Worker::step_filter_lanes(std::size_t f, std::size_t first, std::size_t count, RunResult* runs) {
  namespace lp = lane_pack;
  const FilterModel& filter = filters_[f];
  const GridSteps& stepped = *filter.timing->lanes();  // in_lanes_[f]: it has a lanes form of width W
  stepper_.set_extra_state(0);  // a filter with lanes has no state beyond m and P
  const FilterGuardOptions& guards = options_.filter_guards;
  const TimeGrid& grid = plan_.grid;
  const std::size_t size = filter.state_size(), n = plan_.n, p = plan_.p, windows = plan_.windows.size();
  RunBuffers* lanes = lanes_.data() + group_;
  const double* lane_path = lane_path_.data() + group_ / W * group_path_size();
  const double* lane_dy = lane_dy_.data() + group_ / W * group_dy_size();
  std::array<FilterRunResult*, W> outs{};
  for (std::size_t k = 0; k < count; ++k) outs[k] = &runs[k].filters[f];
  std::vector<double> states(size * W), saved(size * W), peak(n * W, 0.0),
      sums((1 + windows) * n * W, 0.0);
  double* state = state_.data();
  double* before = lane_before_.data();
  // live: the lane's run goes on; visited: the lane's state at the grid point is kept and counted.
  // A lane's out.last is written when it stops, not at every grid point.
  Flags live{}, visited{}, pass{}, psd{};
  std::array<std::ptrdiff_t, W> end{};  // the lane's truth_last
  std::array<std::uint64_t, W> refined{};
  std::size_t living = 0;
  std::uint64_t steps = 0;
  // Lane k's run stops; `last` is its last grid point with a stored state.
  auto stop = [&](std::size_t k, std::size_t last) {
    outs[k]->last = static_cast<std::ptrdiff_t>(last);
    live[k] = 0.0;
    --living;
  };
  reset_plan();

  // Grid point j's visit for the lanes with visited[k]: the errors and their sums in packed passes
  // (a lane not visited adds 0, leaving its sums as they are), then each visited lane's criterion,
  // reference distance and events where there are any.
  auto visit_lanes = [&](std::size_t j) {
    enter(j);
    const double* x = lane_path + j * n * W;
    constexpr std::size_t packs = W / lp::kLanes;
    lp::Pack seen[packs];
    for (std::size_t c = 0; c < packs; ++c) seen[c] = lp::not_equal(lp::load(visited.data() + c * lp::kLanes), lp::splat(0.0));
    for (std::size_t i = 0; i < n; ++i) {
      lp::Pack sq[packs];
      for (std::size_t c = 0; c < packs; ++c) {
        const std::size_t at = i * W + c * lp::kLanes;
        const lp::Pack e = lp::subtract(lp::load(x + at), lp::load(states.data() + at));
        const lp::Pack size = lp::keep_where(seen[c], lp::abs(e));
        sq[c] = lp::keep_where(seen[c], lp::multiply(e, e));
        lp::store(sums.data() + at, lp::add(lp::load(sums.data() + at), sq[c]));
        const lp::Pack peak_so_far = lp::load(peak.data() + at);
        lp::store(peak.data() + at, lp::select(lp::less(peak_so_far, size), size, peak_so_far));  // std::max
      }
      for (std::size_t w : active_) {
        double* window = sums.data() + ((1 + w) * n + i) * W;
        for (std::size_t c = 0; c < packs; ++c)
          lp::store(window + c * lp::kLanes, lp::add(lp::load(window + c * lp::kLanes), sq[c]));
      }
    }
    if (criterion_ || reference_ || events_begin_ != next_event_) {
      for (std::size_t k = 0; k < count; ++k) {
        if (visited[k] == 0) continue;
        for (std::size_t i = 0; i < n + packed_size(n); ++i) state[i] = states[i * W + k];
        PassSums& pass_sums = passes_[k];
        for (std::size_t i = 0; i < n; ++i) pass_sums.error[i] = x[i * W + k] - state[i];
        for (std::size_t e = 0; e < pass_sums.sums.size(); ++e) pass_sums.sums[e] = sums[e * W + k];
        visit_rest(j, state, first + k == options_.shown_run, lanes[k], *outs[k], pass_sums);
      }
    }
    leave();
  };

  for (std::size_t k = 0; k < count; ++k) {
    FilterRunResult& out = *outs[k];
    end[k] = runs[k].truth_last;
    if (!start_pass(first + k == options_.shown_run, runs[k], out, passes_[k])) continue;
    filter.initial_state(state);
    const bool going = guard(grid.t0, state, out);
    if (out.diverged) continue;
    for (std::size_t i = 0; i < size; ++i) states[i * W + k] = state[i];
    visited[k] = 1.0;
    out.last = 0;
    live[k] = going && end[k] > 0 ? 1.0 : 0.0;
    living += live[k] != 0;
  }
  for (std::size_t k = count; k < W; ++k)  // unused lanes: a copy of lane 0, never visited
    for (std::size_t i = 0; i < size; ++i) states[i * W + k] = states[i * W];
  visit_lanes(0);
  // The n = 1 PSD test packs (CovarianceGuard::passes_packs_1); for n > 1 each lane is tested alone.
  const bool psd_packed = n == 1;
  std::ptrdiff_t first_end = 0;  // no live lane's truth ends before this grid point
  for (std::size_t step = 0; living > 0; ++step) {
    const double t = grid.time(step), next = grid.time(step + 1);
    // Entry by entry in packs: memmove's wider loads would straddle the step's narrower stores.
    lp::copy(states.data(), size * W, saved.data());
    stepped.step_lanes()(states.data(), t, grid.dt, lane_dy + step * p * W);
    // Whether a live lane failed a check (a PSD test of n > 1 is left to each lane).
    constexpr std::size_t packs = W / lp::kLanes;
    lp::Pack passes[packs];
    packed_checks<W>(stepper_, guards, n, psd_packed, saved.data(), states.data(), passes);
    lp::Pack failing = lp::splat(0.0);
    for (std::size_t c = 0; c < packs; ++c) {
      const lp::Pack living_lanes = lp::not_equal(lp::load(live.data() + c * lp::kLanes), lp::splat(0.0));
      failing = lp::either(failing, lp::except(living_lanes, passes[c]));
    }
    if (lp::none(failing) && !(guards.check_psd && !psd_packed)) {
      steps += living;
      visited = live;
    } else {
      // The lanes' flags for the loop below: pass (the stepper and the guards) and psd apart.
      lp::Pack psd_passes[packs];
      for (std::size_t c = 0; c < packs; ++c) psd_passes[c] = lp::all_set();
      if (guards.check_psd && psd_packed) guards.psd.passes_packs_1<W>(states.data() + W, psd_passes);
      packed_checks<W>(stepper_, guards, n, false, saved.data(), states.data(), passes);
      for (std::size_t c = 0; c < packs; ++c) {
        const std::size_t lane = c * lp::kLanes;
        lp::store(pass.data() + lane, lp::keep_where(passes[c], lp::load(live.data() + lane)));
        lp::store(psd.data() + lane, lp::keep_where(psd_passes[c], lp::splat(1.0)));
      }
      for (std::size_t k = 0; k < W; ++k) visited[k] = 0.0;
      for (std::size_t k = 0; k < count; ++k) {
        if (live[k] == 0) continue;
        FilterRunResult& out = *outs[k];
        for (std::size_t i = 0; i < size; ++i) state[i] = states[i * W + k];
        bool going = true;
        if (pass[k] != 0) {  // kept and bounded: only the PSD check is left
          ++steps;
          if (guards.check_psd && !out.psd_lost && (psd_packed ? psd[k] == 0 : !guards.psd.passes_filter_state(state, n))) {
            out.psd_lost = true;
            out.psd_t = next;
            going = !guards.stop_on_psd_loss;
          }
        } else {  // step_filter's sequence on the lane alone
          for (std::size_t i = 0; i < size; ++i) before[i] = saved[i * W + k];
          if (!stepper_.keeps(before, state)) {
            std::copy(before, before + size, state);
            ++refined[k];
            // The lane's increment from the interleaved copy (the run's own buffer may be unwritten).
            for (std::size_t r = 0; r < p; ++r) lane_increment_[r] = lane_dy[(step * p + r) * W + k];
            const double* dy = lane_increment_.data();
            if (stepper_.refine(stepped.step(), state, t, grid.dt, dy) == 0) {
              out.diverged = true;  // mid-step: the state is not stored
              (stepper_.equations_finite_at_start(stepped.step(), t) ? out.too_stiff : out.undefined) = true;
              out.divergence_t = t;
              stop(k, step);
              continue;
            }
            for (std::size_t i = 0; i < size; ++i) states[i * W + k] = state[i];
          }
          ++steps;
          going = guard(next, state, out);
          if (out.diverged) {  // a diverged state is not stored
            stop(k, step);
            continue;
          }
        }
        visited[k] = 1.0;
        if (!going) stop(k, step + 1);
      }
    }
    visit_lanes(step + 1);
    // Runs whose truth ends here stop.
    if (static_cast<std::ptrdiff_t>(step + 1) >= first_end) {
      first_end = PTRDIFF_MAX;
      for (std::size_t k = 0; k < count; ++k) {
        if (live[k] == 0) continue;
        if (static_cast<std::ptrdiff_t>(step + 1) < end[k]) {
          first_end = std::min(first_end, end[k]);
          continue;
        }
        stop(k, step + 1);
      }
    }
  }
  filter_steps[f] += steps;
  for (std::size_t k = 0; k < count; ++k) {
    FilterRunResult& out = *outs[k];
    out.refined_steps = refined[k];
    if (end[k] < 0) continue;
    PassSums& pass_sums = passes_[k];
    for (std::size_t e = 0; e < pass_sums.sums.size(); ++e) pass_sums.sums[e] = sums[e * W + k];
    if (out.last >= 0)
      for (std::size_t i = 0; i < n; ++i) out.peak[i] = peak[i * W + k];
    finish_pass(out, pass_sums, lanes[k]);
  }
}

template void Worker::step_filter_lanes<2>(std::size_t, std::size_t, std::size_t, RunResult*);
template void Worker::step_filter_lanes<4>(std::size_t, std::size_t, std::size_t, RunResult*);
template void Worker::step_filter_lanes<8>(std::size_t, std::size_t, std::size_t, RunResult*);
template void Worker::step_filter_lanes<16>(std::size_t, std::size_t, std::size_t, RunResult*);

}  // namespace pfgen_runtime::monte_carlo_detail
