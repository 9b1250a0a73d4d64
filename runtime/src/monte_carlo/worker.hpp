#pragma once
// One thread's share of the Monte Carlo runs. A Worker owns its own clone of the scheme and
// copies of the observation and filters (they hold work arrays, so threads cannot share them)
// and buffers for a batch of runs' truths, reused batch after batch: nothing is allocated per
// step, and no run's path outlives its batch. Per batch it simulates each run's truth into its
// buffers, then steps each filter over them, the runs side by side where the filter has a lanes
// form, accumulating each run's error statistics as it goes and keeping values only at the plan's
// points.
#include <cstddef>
#include <cstdint>
#include <functional>
#include <memory>
#include <optional>
#include <vector>

#include <Eigen/Core>

#include "pfgen_runtime/monte_carlo.hpp"
#include "pfgen_runtime/random.hpp"
#include "pfgen_runtime/schemes.hpp"
#include "plan.hpp"
#include "run_result.hpp"

namespace pfgen_runtime::monte_carlo_detail {

// One run's buffers in a worker that carries several runs side by side.
struct RunBuffers {
  Eigen::VectorXd x0;             // the truth's initial state: fixed, or the run's draw
  Eigen::MatrixXd path;           // n x (steps + 1): x at the grid times
  Eigen::MatrixXd dy;             // p x steps
  Eigen::MatrixXd clean, noisy;   // p x samples: h(t_k, x(t_k)) and y_k (sampled observations)
  std::size_t samples = 0;        // samples of the run
  Eigen::MatrixXd reference_mean; // n x (steps + 1): the particle reference's mean
  Eigen::MatrixXd second_mean;    // and its second, independent particle set's (its error's estimate)
  std::ptrdiff_t reference_last = -1;
};

// A filter pass's running sums for one run.
struct PassSums {
  std::vector<double> sums;           // (1 + windows) x n: e^2 over the horizon and each window
  std::vector<double> error;          // n: e at the current grid point
  std::vector<double> distance_sums;  // n: (m - m_ref)^2 (with the particle reference)
  double previous_L = 0;              // the criterion's L = e^T M e at the previous grid point
};

// The lanes the engine steps this filter in: its timing's lanes form's width when it is 2, 4, 8 or
// 16; 0 (run by run) otherwise.
std::size_t lane_width(const FilterModel& filter);

class Worker {
 public:
  // Keeps references to plan and options: both must outlive the worker.
  // observation: continuous increments (every filter steps on dy) or samples (every filter is
  // sampled). batch: the most runs one call of run() carries side by side (>= 1).
  Worker(const TruthScheme& scheme, const Observation& observation, const std::vector<FilterModel>& filters, const Eigen::VectorXd& x0, const Plan& plan,
         const MonteCarloOptions& options, std::size_t batch);

  // Runs first .. first + count - 1 (count <= batch; each run's random streams depend on its
  // number alone) into out[0 .. count - 1]. A filter with a lanes form steps them side by side;
  // every run's result is bit for bit what it would be alone.
  void run(std::size_t first, std::size_t count, RunResult* out);

  // Summed over this worker's runs (MonteCarloTiming sums them over workers).
  double truth_seconds = 0, truth_cpu_seconds = 0;
  std::uint64_t truth_steps = 0;
  std::vector<double> filter_seconds, filter_cpu_seconds;
  std::vector<std::uint64_t> filter_steps;
  std::vector<std::uint64_t> filter_samples;  // samples absorbed (sampled filters)
  double reference_seconds = 0, reference_cpu_seconds = 0;
  std::uint64_t reference_steps = 0;  // particle steps

 private:
  // Run `run`'s truth x0 into lane.x0 where it is drawn per run (MonteCarloOptions::initial_prior).
  void draw_initial_state(std::size_t run, RunBuffers& lane) const;
  // Run `run`, the batch's k-th, alone (simulate_truth_into) into lanes_[k].
  void simulate_truth(std::size_t run, std::size_t k, RunResult& out);
  // truth_lanes.cpp: the truths of runs first .. first + count - 1 side by side (simulate_truth's
  // loop, each lane bit for bit), for observations without a delay.
  void simulate_truths_lanes(std::size_t first, std::size_t count, RunResult* out);
  // What simulate_truth does after the loop: the counts, the samples, the records. k: the run's
  // place in the batch.
  void finish_truth(std::size_t run, std::size_t k, RunResult& out, const std::optional<DivergenceEvent>& divergence);
  // Entry i of run k's truth at grid point j: from its buffers, or from the lanes' interleaved copy
  // where the buffers are not written (lanes_only_).
  double truth_at(std::size_t k, std::size_t j, std::size_t i) const;
  void run_reference(std::size_t run, bool shown, RunBuffers& lane, RunResult& out);
  // A filter pass's results sized and filled with NaN; false when the run has no truth to compare with.
  bool start_pass(bool shown, const RunResult& run, FilterRunResult& out, PassSums& pass) const;
  // False when the state at t diverged (out says so) or lost its PSD and must stop.
  // A moment filter's realisability (`realisability`, when given) is checked too.
  bool guard(double t, const double* state, FilterRunResult& out, const RealisabilityCheck* realisability = nullptr);
  void finish_pass(FilterRunResult& out, const PassSums& pass, const RunBuffers& lane) const;
  void step_filter(std::size_t f, bool shown, const RunResult& run, RunBuffers& lane, FilterRunResult& out);
  // worker_lanes.cpp: runs first .. first + count - 1 (count <= width_, their buffers lanes_[group_]
  // on) side by side, on their truths interleaved (lane_path_, lane_dy_, one block per group of
  // width_ runs, written by simulate_truths_lanes); step_filter_lanes steps filter f over them
  // (dispatching to a fixed width W).
  void reserve_lane_truths(std::size_t count);  // for the first `count` entries of lanes_
  std::size_t group_path_size() const;
  std::size_t group_dy_size() const;
  void step_filter_lanes(std::size_t f, std::size_t first, std::size_t count, RunResult* runs);
  template <std::size_t W>
  void step_filter_lanes(std::size_t f, std::size_t first, std::size_t count, RunResult* runs);
  void absorb_sample(double t, std::ptrdiff_t column, const double* state, const RunBuffers& lane,
                     FilterRunResult& out);
  // The plan at grid point j: enter() opens its windows and finds its events, visit() takes one
  // run's state there, leave() closes its windows. Every run of a pass visits j between the two.
  void enter_events(std::size_t j);  // enter() where j opens a window or holds an event
  void leave_events();                // leave() after such a j
  void enter(std::size_t j) {  // inline: most grid points open no window and hold no event
    if ((next_open_ < plan_.opens.size() && plan_.opens[next_open_].first == j) ||
        (next_event_ < plan_.events.size() && plan_.events[next_event_].index == j))
      enter_events(j);
    else
      events_begin_ = next_event_;
  }
  void visit(std::size_t j, const double* state, bool shown, const RunBuffers& lane, FilterRunResult& out,
             PassSums& pass) const;
  void leave() {
    if (events_begin_ != next_event_) leave_events();
  }
  // What follows the error sums in visit() (step_filter_lanes sums the errors in packed passes).
  void visit_rest(std::size_t j, const double* state, bool shown, const RunBuffers& lane, FilterRunResult& out,
                  PassSums& pass) const;
  void accumulate_criterion(std::size_t j, FilterRunResult& out, PassSums& pass) const;
  void reset_plan();

  std::unique_ptr<TruthScheme> scheme_;
  // One run's truth in simulate_truths_lanes: its scheme (for the steps taken one by one, with the
  // run's own bridge draws) and its noise streams.
  struct TruthLane {
    std::unique_ptr<TruthScheme> scheme;
    RandomStream truth_noise{0, 0}, observation_noise{0, 0};
    std::optional<WienerIncrements> dW, dW2;
  };
  std::vector<std::unique_ptr<TruthLane>> truth_lanes_;  // batch entries (pointers: dW refers to its stream)
  std::vector<double> truth_x_, truth_start_, truth_dW_, truth_dW2_, truth_dy_;  // entry-major
  std::vector<LaneFlag> truth_live_, truth_take_, truth_bounded_;
  Eigen::VectorXd truth_lane_x_, truth_lane_dW_;
  Observation observation_;
  std::vector<FilterModel> filters_;
  Eigen::MatrixXd prior_root_;  // MonteCarloOptions::initial_prior's covariance square root
  const Plan& plan_;
  const MonteCarloOptions& options_;
  std::vector<RunBuffers> lanes_;  // batch entries, reused run after run
  std::vector<PassSums> passes_;   // likewise
  std::size_t steps_per_sample_ = 0;  // samples only
  std::size_t sample_sums_size_ = 0;  // FilterRunResult::sample_sums' (samples only)
  std::vector<double> estimate_;       // a sampled filter's h(t_k, m(t_k|t_k))
  std::vector<double> state_;
  std::vector<double> margins_;  // a moment filter's realisability margins (guard)
  mutable std::vector<double> nees_work_;  // normalized_error_squared's Cholesky factor
  FilterStepper stepper_;
  // The plan's cursor of a pass: windows open at the current grid point, its events.
  std::vector<std::size_t> active_;
  std::size_t next_open_ = 0, next_event_ = 0, events_begin_ = 0;
  bool criterion_ = false, weighted_ = false;
  Eigen::MatrixXd weight_;
  std::unique_ptr<ParticleReference> reference_;
  // The lanes (worker_lanes.cpp): their width (0: none), which filters step in them, and the
  // group's truths interleaved, entry-major per grid point: x(t_j) entry i of lane k at
  // (j n + i) W + k, dy of step j at (j p + r) W + k (past a run's end, whatever was there).
  std::size_t width_ = 0;
  std::vector<bool> in_lanes_;
  std::vector<double> lane_path_, lane_dy_;
  std::vector<double> lane_before_;  // one lane's saved state
  std::vector<double> lane_increment_;  // one lane's dy
  std::size_t group_ = 0;            // lanes_ index of the current group's first run
  bool truths_interleaved_ = false;  // the batch's truths came from simulate_truths_lanes
  // Every filter steps in lanes, and nothing else reads a run's whole path or increments (no
  // particle reference, no samples): simulate_truths_lanes then writes only the interleaved copy,
  // which halves what a batch writes and keeps more of it in cache.
  bool lanes_only_ = false;
};

}  // namespace pfgen_runtime::monte_carlo_detail
