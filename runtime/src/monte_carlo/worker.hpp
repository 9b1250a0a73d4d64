#pragma once
// One thread's share of the Monte Carlo runs. A Worker owns its own clone of the scheme and
// copies of the observation and filters (they hold work arrays, so threads cannot share them)
// and buffers for one run's truth, reused run after run: nothing is allocated per step, and no
// run's path outlives the run. Per run it simulates the truth into the buffers, then steps each
// filter over them in turn, accumulating the run's error statistics as it goes and keeping values
// only at the plan's points.
#include <cstddef>
#include <cstdint>
#include <functional>
#include <memory>
#include <optional>
#include <vector>

#include <Eigen/Core>

#include "pfgen_runtime/monte_carlo.hpp"
#include "plan.hpp"
#include "run_result.hpp"

namespace pfgen_runtime::monte_carlo_detail {

class Worker {
 public:
  // Keeps references to plan and options: both must outlive the worker.
  // measurement: the samples of a model with sampled observations (then `observation` is only
  // the truth loop's placeholder and every filter is sampled); nullptr for continuous ones.
  Worker(const TruthScheme& scheme, const LinearObservation& observation, const SampledMeasurement* measurement,
         const std::vector<FilterModel>& filters, const Eigen::VectorXd& x0, const Plan& plan,
         const MonteCarloOptions& options);

  // Run number `run` (its random streams depend on the number alone) into `out`.
  void run(std::size_t run, RunResult& out);

  // Summed over this worker's runs (MonteCarloTiming sums them over workers).
  double truth_seconds = 0, truth_cpu_seconds = 0;
  std::uint64_t truth_steps = 0;
  std::vector<double> filter_seconds, filter_cpu_seconds;
  std::vector<std::uint64_t> filter_steps;
  std::vector<std::uint64_t> filter_samples;  // samples absorbed (sampled filters)
  double reference_seconds = 0, reference_cpu_seconds = 0;
  std::uint64_t reference_steps = 0;  // particle steps

 private:
  void simulate_truth(std::size_t run, RunResult& out);
  void run_reference(std::size_t run, bool shown, RunResult& out);
  void step_filter(std::size_t f, bool shown, const RunResult& run, FilterRunResult& out);
  void step_sampled_filter(const FilterModel& filter, std::ptrdiff_t truth_last, FilterRunResult& out,
                           const std::function<bool(double)>& guard, bool shown, std::uint64_t& steps);
  void visit(std::size_t j, const double* state, bool shown, FilterRunResult& out);
  void accumulate_criterion(std::size_t j, FilterRunResult& out);
  void finish_reference_distance(FilterRunResult& out);

  std::unique_ptr<TruthScheme> scheme_;
  LinearObservation observation_;
  std::vector<FilterModel> filters_;
  Eigen::VectorXd x0_;          // the truth's initial state: fixed, or the current run's draw
  Eigen::MatrixXd prior_root_;  // MonteCarloOptions::initial_prior's covariance square root
  const Plan& plan_;
  const MonteCarloOptions& options_;
  Eigen::MatrixXd path_;  // n x (steps + 1): x at the grid times of the current run
  Eigen::MatrixXd dy_;    // p x steps
  std::optional<SampledMeasurement> measurement_;
  std::size_t steps_per_sample_ = 0;
  Eigen::MatrixXd clean_, noisy_;  // p x samples: C0 + C x(t_k) and y_k of the current run
  std::size_t samples_ = 0;        // samples of the current run
  std::vector<double> zeros_, estimate_;
  std::vector<double> state_, error_, sums_;
  FilterStepper stepper_;
  std::vector<std::size_t> active_;  // windows open at the current grid point
  std::size_t next_open_ = 0, next_event_ = 0;
  // The criterion's L = e^T M e at the previous grid point (the trapezoid's left end).
  bool criterion_ = false, weighted_ = false;
  Eigen::MatrixXd weight_;
  double previous_L_ = 0;
  // The particle reference: its mean on the current run's grid (n x (steps + 1)) up to
  // reference_last_, and a filter pass's sums of (m - m_ref)^2 (n).
  std::unique_ptr<ParticleReference> reference_;
  Eigen::MatrixXd reference_mean_;
  std::ptrdiff_t reference_last_ = -1;
  std::vector<double> distance_sums_;
};

}  // namespace pfgen_runtime::monte_carlo_detail
