// The truths of a batch of runs side by side (Worker::simulate_truths_lanes): simulate_truth_into's
// loop with the runs as lanes. Each run keeps its own noise streams and its own scheme; the scheme
// steps at once the lanes it can (TruthScheme::step_lanes_at_once: one batched evaluation of f and
// g), and the run's own scheme steps the others alone, with its own bridge draws. The guard, the
// observation's increment and the stores follow for every lane. Each lane's arithmetic and draws
// are simulate_truth_into's, so every run's truth is bit for bit what it is alone.
#include <algorithm>

#include "pfgen_runtime/lane_pack.hpp"
#include "pfgen_runtime/simulation.hpp"
#include "worker.hpp"

namespace pfgen_runtime::monte_carlo_detail {

void Worker::simulate_truths_lanes(std::size_t first, std::size_t count, RunResult* out) {
  const TimeGrid& grid = plan_.grid;
  const DivergenceGuard& guard = options_.truth_guard;
  const std::size_t n = plan_.n, q = scheme_->system().q, r = observation_.increment_noise(), p = observation_.p();
  const std::size_t W = count;
  while (truth_lanes_.size() < count) {
    truth_lanes_.push_back(std::make_unique<TruthLane>());
    truth_lanes_.back()->scheme = scheme_->clone();
  }
  truth_x_.resize(n * W);
  truth_start_.resize(n * W);
  // The lanes' increments a chunk of steps at a time, step-major: step s's entry j of lane k at
  // (s * q + j) * W + k. Every living lane's stream is at a chunk's start together, since each
  // takes one increment a step; a lane that stops takes no more.
  constexpr std::size_t chunk_steps = WienerIncrements::kChunkSteps;
  truth_dW_.resize(chunk_steps * q * W);
  truth_dW2_.resize(chunk_steps * r * W);
  truth_dy_.resize(p * W);
  truth_live_.assign(W, 0.0);
  truth_take_.resize(W);
  truth_bounded_.resize(W);
  truth_lane_x_.resize(static_cast<Eigen::Index>(n));
  truth_lane_dW_.resize(static_cast<Eigen::Index>(q));
  double* x = truth_x_.data();
  LaneFlag* live = truth_live_.data();
  std::vector<std::optional<DivergenceEvent>> divergence(count);
  // The filters' lanes read the truths interleaved: written here as they are made (width_ 0: no
  // filter steps in lanes).
  const std::size_t width = width_;
  std::vector<double*> path_of(count), dy_of(count);  // lane k's first entry in its group's block
  if (width > 0) {
    reserve_lane_truths(count);
    for (std::size_t k = 0; k < count; ++k) {
      path_of[k] = lane_path_.data() + k / width * group_path_size() + k % width;
      dy_of[k] = lane_dy_.data() + k / width * group_dy_size() + k % width;
    }
  }
  std::size_t living = 0;
  for (std::size_t k = 0; k < count; ++k) {
    const std::size_t run = first + k;
    RunBuffers& lane = lanes_[k];
    TruthLane& truth = *truth_lanes_[k];
    draw_initial_state(run, lane);
    truth.scheme->start_run(options_.seed, run);
    truth.scheme->set_escape_bound(guard.bound());
    truth.truth_noise = RandomStream(options_.seed, run, substream::truth_noise);
    truth.observation_noise = RandomStream(options_.seed, run, substream::observation_noise);
    truth.dW.emplace(truth.truth_noise, q, grid.dt);
    truth.dW2.emplace(truth.observation_noise, r, grid.dt);
    divergence[k] = guard.check(grid.t0, lane.x0);
    if (divergence[k]) {
      out[k].truth_last = -1;
      continue;
    }
    if (!lanes_only_) lane.path.col(0) = lane.x0;
    for (std::size_t i = 0; i < n; ++i) x[i * W + k] = lane.x0[static_cast<Eigen::Index>(i)];
    if (width > 0)
      for (std::size_t i = 0; i < n; ++i) path_of[k][i * width] = lane.x0[static_cast<Eigen::Index>(i)];
    live[k] = 1.0;
    ++living;
  }
  for (std::size_t step = 0; living > 0 && step < grid.steps; ++step) {
    const double t = grid.time(step);
    const std::size_t in_chunk = step % chunk_steps;
    if (in_chunk == 0)
      for (std::size_t k = 0; k < count; ++k) {
        if (live[k] == 0) continue;
        TruthLane& truth = *truth_lanes_[k];
        const double* dW = truth.dW->next_chunk();
        const double* dW2 = truth.dW2->next_chunk();
        for (std::size_t e = 0; e < chunk_steps * q; ++e) truth_dW_[e * W + k] = dW[e];
        for (std::size_t e = 0; e < chunk_steps * r; ++e) truth_dW2_[e * W + k] = dW2[e];
      }
    const double* step_dW = truth_dW_.data() + in_chunk * q * W;
    const double* step_dW2 = truth_dW2_.data() + in_chunk * r * W;
    lane_pack::copy(truth_x_.data(), n * W, truth_start_.data());
    LaneFlag* take = truth_take_.data();
    lane_pack::copy(live, W, take);
    scheme_->step_lanes_at_once(t, W, x, grid.dt, step_dW, take);
    const double next = grid.time(step + 1);
    // DivergenceGuard::check's test of every lane, packed; a lane stepped alone below is checked
    // after its step.
    LaneFlag* bounded = truth_bounded_.data();
    std::fill(bounded, bounded + W, 1.0);
    guard.pass_lanes(x, n, W, bounded);
    // done: the lane was stepped at once and is bounded. Most often every living lane is done, and
    // the loop below has nothing to do.
    for (std::size_t k = 0; k < W; ++k) bounded[k] *= take[k];
    const LaneFlag* done = bounded;
    const bool all_done = lanes_set(done, W) == living;
    for (std::size_t k = 0; !all_done && k < count; ++k) {
      if (live[k] == 0 || done[k] != 0) continue;
      // The lane's state alone: stepped by its run's own scheme where the batch left it, as
      // simulate_truth_into steps it, then checked by the guard, which reports the event.
      for (std::size_t i = 0; i < n; ++i) truth_lane_x_[static_cast<Eigen::Index>(i)] = x[i * W + k];
      std::optional<DivergenceEvent> event;
      if (take[k] == 0) {
        for (std::size_t j = 0; j < q; ++j) truth_lane_dW_[static_cast<Eigen::Index>(j)] = step_dW[j * W + k];
        event = take_truth_step(*truth_lanes_[k]->scheme, t, truth_lane_x_, grid.dt, truth_lane_dW_);
        if (!event) {
          for (std::size_t i = 0; i < n; ++i) x[i * W + k] = truth_lane_x_[static_cast<Eigen::Index>(i)];
          event = guard.check(next, truth_lane_x_);
        }
      } else {
        event = guard.check(next, truth_lane_x_);
      }
      if (!event) continue;
      divergence[k] = event;
      out[k].truth_last = static_cast<std::ptrdiff_t>(step);
      live[k] = 0.0;
      --living;
    }
    observation_.increment_lanes(t, grid.dt, W, truth_start_.data(), x, step_dW2, truth_dy_.data());
    if (lanes_only_ && width > 0 && living == count && count % width == 0) {
      // Every lane lives and fills its group: the interleaved rows are the step's rows, group by
      // group, copied whole.
      for (std::size_t g = 0; g < count / width; ++g) {
        double* path = lane_path_.data() + g * group_path_size() + (step + 1) * n * width;
        double* dy = lane_dy_.data() + g * group_dy_size() + step * p * width;
        for (std::size_t i = 0; i < n; ++i) lane_pack::copy(x + i * W + g * width, width, path + i * width);
        for (std::size_t a = 0; a < p; ++a) lane_pack::copy(truth_dy_.data() + a * W + g * width, width, dy + a * width);
      }
      continue;
    }
    for (std::size_t k = 0; k < count; ++k) {
      if (live[k] == 0) continue;
      if (!lanes_only_) {
        RunBuffers& lane = lanes_[k];
        const auto column = static_cast<Eigen::Index>(step);
        for (std::size_t a = 0; a < p; ++a) lane.dy(static_cast<Eigen::Index>(a), column) = truth_dy_[a * W + k];
        for (std::size_t i = 0; i < n; ++i) lane.path(static_cast<Eigen::Index>(i), column + 1) = x[i * W + k];
      }
      if (width == 0) continue;
      for (std::size_t a = 0; a < p; ++a) dy_of[k][(step * p + a) * width] = truth_dy_[a * W + k];
      for (std::size_t i = 0; i < n; ++i) path_of[k][((step + 1) * n + i) * width] = x[i * W + k];
    }
  }
  for (std::size_t k = 0; k < count; ++k) {
    if (live[k] != 0) out[k].truth_last = static_cast<std::ptrdiff_t>(grid.steps);
    finish_truth(first + k, k, out[k], divergence[k]);
  }
}

}  // namespace pfgen_runtime::monte_carlo_detail
