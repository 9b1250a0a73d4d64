#pragma once
// Monte Carlo runs of a truth and any number of filters on its observations, across threads.
//
// Run r draws from RandomStream(seed, r, substream), so it is the same run whichever thread makes
// it; runs are taken from an atomic counter, each run's results go into the slot of its index,
// and all statistics are folded in run order after every run has finished. The result is
// therefore bitwise identical for any thread count (timing aside).
//
// Per run a thread simulates the truth into its own reusable buffers (the x path and the dy
// increments of one run, exactly as simulate_truth does), then steps each filter over them in
// turn, accumulating the run's error statistics on the fly and recording values only at the
// record times: no run's full path outlives the run, and nothing is allocated per step.
//
// Undefined numbers (no run alive at a time, no run reached a window's end, ...) are NaN here;
// the writers print them as '-' or empty cells, never as "nan".
#include <chrono>
#include <cstddef>
#include <cstdint>
#include <functional>
#include <limits>
#include <optional>
#include <string>
#include <utility>
#include <vector>

#include <Eigen/Core>

#include "pfgen_runtime/criterion.hpp"
#include "pfgen_runtime/guards.hpp"
#include "pfgen_runtime/observation.hpp"
#include "pfgen_runtime/particle_reference.hpp"
#include "pfgen_runtime/schemes.hpp"
#include "pfgen_runtime/simulation.hpp"

namespace pfgen_runtime {

// How many of `runs` runs process `process` of `processes` makes when they are dealt in chunks of
// `chunk` runs (chunk >= 1), chunk c to process c mod processes.
std::size_t dealt_runs(std::size_t runs, std::size_t chunk, std::size_t process, std::size_t processes);
// How many chunks of `chunk` consecutive runs (chunk >= 1) `runs` runs make, the last one shorter.
inline std::size_t chunk_count(std::size_t runs, std::size_t chunk) { return (runs + chunk - 1) / chunk; }

// This process's side of chunks handed out while the runs are made (RunShare::hand_out): the
// chunks it has been given wait here until one of its threads starts them. Safe to call from any
// thread.
class ChunkFeed {
 public:
  virtual ~ChunkFeed() = default;
  // Chunks given and not yet started.
  virtual std::size_t waiting() const = 0;
  // Chunks this process's threads have finished.
  virtual std::size_t made() const = 0;
  // Chunk `chunk` of the job (runs chunk * RunShare::chunk onwards) is this process's to make.
  virtual void give(std::size_t chunk) = 0;
  // This process's runs failed: a chunk given now would not be made.
  virtual bool stopped() const = 0;
  // Returns when waiting() is below `below`, the runs have stopped, or `timeout` has passed.
  virtual void wait_below(std::size_t below, std::chrono::microseconds timeout) const = 0;
};

// Bytes that go out where they are (RunShare::exchange): a block is its pieces one after the
// other, so that a process's values leave from its runs' record vectors without first being copied
// into one buffer (2000 satellite runs on 2 processes: 40 MB a process, 24 ms of copying). The
// memory a piece points to stays valid and unchanged until the exchange returns.
struct BytePiece {
  const char* data = nullptr;
  std::size_t size = 0;
};
using PiecedBlock = std::vector<BytePiece>;

// The bytes of a block, copied into one buffer (for an exchange that needs them together).
inline std::vector<char> joined(const PiecedBlock& block) {
  std::size_t size = 0;
  for (const BytePiece& piece : block) size += piece.size;
  std::vector<char> bytes;
  bytes.reserve(size);
  for (const BytePiece& piece : block) bytes.insert(bytes.end(), piece.data, piece.data + piece.size);
  return bytes;
}

// The runs of one job shared among processes (the MPI ranks of `pfgen simulate`, whose MPI code
// lives in the program, not here): this process is number `process` of `processes`. Its runs are
// - with `chunk` 0: the block [first, first + count);
// - with `chunk` > 0, the job's runs in chunks of `chunk` consecutive runs (the last one shorter):
//   - without hand_out, chunk c is process c mod processes's (count is then dealt_runs(...));
//   - with hand_out, the chunks go to the processes as they ask for them, so that a process that
//     drew cheaper runs makes more of them and none is left finishing alone. The runtime makes the
//     chunks given to this process on `threads` threads of their own and calls hand_out(feed) on
//     the calling thread. hand_out gives this process its chunks through `feed`, keeping a few
//     waiting, and returns once no more will come, with the process that was given each chunk of
//     the job: the same table on every process. count is not read.
//   Either way every process gets runs from all along the job: runs whose cost changes with
//   their number (their random streams do) no longer leave one process the slower block.
// Every process then calls the same two collectives, in this order:
// - exchange, in rounds (the same number on every process, from the job alone): in each, every
//   process hands one block per process (outgoing[j] for process j, in pieces) and receives into
//   incoming[j], in process order, the bytes of the block process j addressed to it (its own,
//   empty: a process's values at its own range do not travel). incoming holds one buffer per
//   process on return; a buffer's memory is reused from round to round where it is large enough.
//   Each process folds the series at its own range of record times from them, a part of the range
//   a round, so that the largest part of folding is shared. A round brings a process about
//   exchange_round_bytes (0: everything in one round), so that what it receives lands in memory
//   the round before used, not in ever more fresh pages.
// - gather: each process hands one block (its runs' results and its folded rows); process 0 gets
//   every process's, in process order, and the others get nothing.
// The processes' runs, in process order (blocks) or put back chunk by chunk, must be runs
// 0 .. runs - 1. Every value is folded in run order exactly as one process folds it, so the result
// is bitwise the same whichever process made which run.
struct RunShare {
  std::size_t first = 0, count = 0;
  std::size_t process = 0, processes = 1;
  std::function<void(const std::vector<PiecedBlock>& outgoing, std::vector<std::vector<char>>& incoming)> exchange;
  std::function<std::vector<std::vector<char>>(std::vector<char> mine)> gather;
  std::size_t chunk = 0;
  std::function<std::vector<std::size_t>(ChunkFeed& feed)> hand_out;
  std::size_t exchange_round_bytes = std::size_t(64) << 20;
};

// The truth's initial state drawn per run from N(mean, covariance) instead of a fixed x0: the
// setting under which a Bayes filter started from that prior (the particle reference) is the
// conditional mean. Run r draws from RandomStream(seed, r, substream::initial_state), so the draw
// is the same for any thread or rank count; the covariance may be singular (positive semi-definite).
struct InitialPrior {
  Eigen::VectorXd mean;
  Eigen::MatrixXd covariance;
};

// The memory a worker's batch of runs may keep (MonteCarloOptions::batch).
inline constexpr std::size_t kBatchBytes = std::size_t(64) << 20;

struct MonteCarloOptions {
  TimeGrid grid;
  std::size_t runs = 100;
  std::uint64_t seed = 1;
  unsigned threads = 1;              // >= 1; more threads than runs are not started
  // Runs a thread carries side by side (>= 1): their truths are stepped together, and so are the
  // filters with a lanes form (GridSteps::step_lanes). Fewer when the runs' paths would take
  // more than kBatchBytes, or when there would not be a batch for every thread. Every result is
  // the same for any batch, as for any thread count.
  std::size_t batch = 8;
  std::size_t record_points = 1000;  // series at every max(1, steps / record_points)-th grid point, plus the last
  std::size_t shown_run = 0;         // the run whose truth, estimates and P diagonals go into the series
  std::vector<double> report_times;  // snapped to the nearest grid time; must lie in [t0, T]
  std::vector<std::pair<double, double>> windows;  // [a, b] in [t0, T], a < b, snapped to the grid
  DivergenceGuard truth_guard{1e8};
  FilterGuardOptions filter_guards;
  // The exponential criterion J per filter (criterion.hpp), when set; the weight, when given, must
  // be n x n, finite and symmetric.
  std::optional<CriterionOptions> criterion;
  // The particle reference (particle_reference.hpp) on every run, when set: continuous undelayed
  // or sampled observations and a truth with noise only (std::invalid_argument otherwise).
  std::optional<ParticleReferenceOptions> reference;
  // Set: each run's truth starts from a draw of this prior, and the x0 argument is not used.
  std::optional<InitialPrior> initial_prior;
  // Called from worker threads (must be thread-safe) after each finished run with the number of
  // runs finished so far.
  std::function<void(std::size_t finished, std::size_t total)> on_run_finished;
  // Set: this process makes only its share of the runs (then on_run_finished counts those).
  std::optional<RunShare> share;
};

// The per-run mean of e^2 over a window's grid points, averaged over the runs in which neither
// the truth nor the filter stopped before the window's end.
struct WindowStatistics {
  double a = 0, b = 0;              // grid times of the first and last point
  std::size_t first = 0, last = 0;  // their grid indices
  std::size_t runs = 0;             // runs that entered
  std::vector<double> rms;          // per state component: sqrt(mean over runs); NaN when runs == 0
  // Its standard error by the delta method, sd(runs' mean squares) / (sqrt(runs) 2 rms); NaN when
  // runs < 2.
  std::vector<double> rms_se;
  // Paired run by run with the first filter (empty for the first filter itself): over the runs both
  // completed, the mean of this filter's mean square minus the first's, and its standard error.
  std::size_t paired_runs = 0;
  std::vector<double> paired_difference, paired_difference_se;
};

struct ReportStatistics {
  double t = 0;  // the grid time the requested time snapped to
  std::size_t index = 0;
  std::size_t alive = 0;                // runs with truth and filter alive at t
  std::vector<double> mean_abs, rms;    // per component, over those runs; NaN when alive == 0
  // The signed mean of e = x - m (with a deterministic truth, mean m = x - mean e) and the
  // standard errors (sample standard deviation / sqrt(alive)) of it and of mean_abs; per
  // component, NaN when alive == 0 (the standard errors: alive < 2). format_report_errors prints them.
  std::vector<double> mean_error, mean_error_se, mean_abs_se;
  // Paired with the first filter (empty for the first itself): over the runs both have alive at t,
  // the mean of |e| minus the first's |e|, and its standard error.
  std::size_t paired_alive = 0;
  std::vector<double> paired_abs_difference, paired_abs_difference_se;
};

// The truth itself at a report time, over the runs whose truth is alive there (a paper's
// printed state values can be checked against it).
struct TruthReportStatistics {
  double t = 0;
  std::size_t index = 0;
  std::size_t alive = 0;
  std::vector<double> mean, q05, q50, q95;  // per component; NaN when alive == 0
};

struct RunEvent {
  std::size_t run = 0;
  double t = 0;
};

struct EventSummary {
  std::vector<RunEvent> events;  // in run order, at most one per run
  std::size_t count() const { return events.size(); }
  double earliest() const;  // NaN when there are none
  double median() const;    // of the times; NaN when there are none
};

// Paper 003's metrics of a sampled filter (docs/theory.md, section 2.5.6): over the runs that
// absorbed every sample (K of them), per measurement component, RMSE(s) = sqrt(1/K sum_k
// (Y(t_k) - Yhat(t_k|t_k))^2) and MRAE(s) = 1/K sum_k |Y(t_k) - Yhat(t_k|t_k)| / |Y(t_k)|, with
// Yhat = C0 + C m(t_k|t_k), in two readings of the "true value of the measurement" Y: the
// noise-free C0 + C x(t_k) (clean) and the sample y_k itself (noisy). Av* is the mean over runs,
// *_se its standard error (sample standard deviation / sqrt(runs)); NaN when runs < 1 (se: < 2).
struct SampledMetrics {
  // Samples through a rate that is not affine (a polynomial c, FunctionRate): Yhat = c(m(t_k|t_k))
  // and the clean Y = c(x(t_k)) instead of C0 + C m and C0 + C x.
  bool nonlinear = false;
  std::size_t runs = 0;
  std::size_t samples = 0;  // K
  std::vector<double> rmse_clean, rmse_clean_se, mrae_clean, mrae_clean_se;
  std::vector<double> rmse_noisy, rmse_noisy_se, mrae_noisy, mrae_noisy_se;
  std::size_t update_failures = 0;  // runs stopped by an update with S not positive definite
  // Paired against the first filter (same runs, same samples): per run this filter's RMSE(s) or
  // MRAE(s) minus the first filter's, over the runs both completed (paired_runs); mean and
  // standard error. Empty for the first filter itself.
  std::size_t paired_runs = 0;
  std::vector<double> diff_rmse_clean, diff_rmse_clean_se, diff_mrae_clean, diff_mrae_clean_se;
  std::vector<double> diff_rmse_noisy, diff_rmse_noisy_se, diff_mrae_noisy, diff_mrae_noisy_se;
};

// The exponential criterion J of one filter (criterion.hpp; docs/theory.md, "The exponential
// criterion J"). A run whose truth or filter stopped before T (divergence, bound, PSD loss with
// stop_on_psd_loss) has no I_r, and the error it left behind is unbounded: J over all runs is
// then +infinity. `completed` is J over the runs that reached T, a conditional figure, not J.
struct CriterionStatistics {
  double epsilon = 0;
  std::vector<double> integrals;  // I_r per run, in run order; NaN for a run stopped before T
  EventSummary stopped;           // those runs, with the time the truth or the filter stopped
  CriterionEstimate all;          // every run: J and mean_integral +inf, the rest NaN when one stopped
  CriterionEstimate completed;    // the runs that reached T
};

// One filter against the particle reference over [t0, T], on the runs where both the filter and
// the reference reached T (`runs`), per component: the RMS over runs and grid points of the
// distance m - m_ref, of the filter's error x - m and of the reference's x - m_ref on those runs
// (for the exact conditional mean, RMS(x - m)^2 = RMS(x - m_ref)^2 + RMS(m - m_ref)^2 up to Monte
// Carlo error). NaN when runs == 0.
struct ReferenceComparison {
  std::size_t runs = 0;
  std::vector<double> distance, filter_rms, reference_rms;
  // Their standard errors by the delta method on the runs' mean squares; NaN when runs < 2.
  std::vector<double> distance_se, filter_rms_se, reference_rms_se;
};

// Per state component, the filter closest to the reference and whether it is closer than the
// runner-up beyond the Monte Carlo error: the paired difference of the runs' mean squared distances
// (runner-up minus closest, over the runs where both and the reference reached T) and its standard
// error. Indices into MonteCarloResult::filters; no runner-up with one filter.
struct PairedDistance {
  std::size_t filter = 0;  // index into MonteCarloResult::filters
  std::size_t runs = 0;
  double difference = std::numeric_limits<double>::quiet_NaN(), difference_se = std::numeric_limits<double>::quiet_NaN();
  bool significant() const { return difference > 2 * difference_se; }
};
struct ClosestToReference {
  std::size_t closest = 0;
  std::optional<std::size_t> runner_up;
  std::size_t runs = 0;
  double difference = std::numeric_limits<double>::quiet_NaN(), difference_se = std::numeric_limits<double>::quiet_NaN();
  bool significant() const { return difference > 2 * difference_se; }
  // Every other filter with a distance, nearest first (the runner-up first): its mean squared
  // distance minus the closest's, paired run by run as above, so that the farthest is said to be
  // worse only where that is beyond the Monte Carlo error.
  std::vector<PairedDistance> others;
};

// The reference itself: its error x - m_ref over [t0, T] (horizon: the runs it reached T in), the
// runs where every particle diverged before the truth's end, and its resamplings.
struct ReferenceStatistics {
  std::size_t particles = 0;
  WindowStatistics horizon;
  // Its own Monte Carlo error per component: sqrt(mean over runs and grid points of
  // (m_ref - m_ref')^2 / 2), m_ref' the mean of a second, independent set of N particles on the
  // same run (so (m_ref - m_ref')^2 / 2 estimates the variance of m_ref about what an infinite set
  // would give), over the `error_runs` runs where both sets reached T; NaN when none did.
  std::size_t error_runs = 0;
  std::vector<double> error;
  std::vector<ClosestToReference> closest;  // per state component
  EventSummary stopped;
  double mean_resamplings = 0;  // per run with a reference
};

struct FilterStatistics {
  std::string name;
  WindowStatistics horizon;              // [t0, T]; horizon.runs runs completed
  std::vector<WindowStatistics> windows;  // as MonteCarloOptions::windows
  std::vector<ReportStatistics> reports;  // as MonteCarloOptions::report_times
  std::vector<double> peak_median, peak_q95;  // of max_t |e| over completed runs, per component
  EventSummary divergences;  // m or P non-finite or beyond its bound (the guard's event time)
  EventSummary psd_losses;   // the first time P failed the PSD check, per run
  // A continuous filter stepped on the grid (not sampled, not a delayed one's fixed step): its grid
  // steps are refined or not as MonteCarloResult::refined_stepping says.
  bool grid_stepped = false;
  std::uint64_t refined_steps = 0;  // grid steps taken in sub-steps (FilterStepper), all runs
  std::size_t refined_runs = 0;     // runs with at least one
  std::size_t too_stiff_runs = 0;   // runs stopped (and counted as diverged) for want of sub-steps
  // A moment filter's runs stopped where its moments left the realisable set (among divergences too).
  EventSummary unrealisable;
  std::size_t undefined_runs = 0;   // runs stopped (diverged) where its equations were not finite at its state
  std::optional<SampledMetrics> sampled;  // sampled filters only
  std::optional<CriterionStatistics> criterion;  // when MonteCarloOptions::criterion is set
  std::optional<ReferenceComparison> reference;  // when MonteCarloOptions::reference is set
  // The consistency of P, at each report time and at T (reports + 1 entries, T last): over the
  // runs alive there whose P was positive definite (nees_runs), the mean NEES per state dimension
  // e^T P^-1 e / n (NaN without such a run) and its two-sided 95 % band (nees_band).
  std::vector<std::size_t> nees_runs;
  std::vector<double> nees, nees_low, nees_high;
};

// Across runs at each record time, per component; NaN where no run is alive.
struct SeriesStatistics {
  Eigen::MatrixXd mean, q05, q50, q95;  // records x n
};

struct FilterSeries {
  Eigen::MatrixXd m, P_diagonal;  // records x n: the shown run; NaN where it had stopped
  SeriesStatistics error;         // e = x - m over the runs alive
  std::vector<std::size_t> alive;  // per record time
  Eigen::MatrixXd error_rms;       // records x n: sqrt(mean e^2) over the runs alive
  // records x 1: the mean over runs of the NEES per state dimension, e^T P^-1 e / n, over the
  // runs alive whose P was positive definite (nees_runs of them; its 95 % band: nees_band).
  Eigen::MatrixXd nees;
  std::vector<std::size_t> nees_runs;
  // With the particle reference (else empty), records x n: the shown run's m - m_ref (NaN where
  // either had stopped) and, over the runs where both are alive, sqrt(mean (m - m_ref)^2).
  Eigen::MatrixXd reference_distance, reference_distance_rms;
};

struct MonteCarloSeries {
  std::vector<std::size_t> index;  // grid indices of the record times
  std::vector<double> t;
  std::size_t shown_run = 0;
  Eigen::MatrixXd truth;            // records x n: the shown run's x; NaN where it had stopped
  SeriesStatistics truth_statistics;
  std::vector<std::size_t> truth_alive;
  std::vector<FilterSeries> filters;  // as the filters passed in
  // With the particle reference (else empty), records x n: the shown run's m_ref, and over the
  // runs where the reference is alive sqrt(mean (x - m_ref)^2).
  Eigen::MatrixXd reference_m, reference_error_rms;
};

// Wall time of the whole call, and per phase the elapsed (steady_clock) and CPU seconds of the
// threads summed over threads, measured per run, not per step. Elapsed exceeds CPU time when
// other processes share the cores. The only part of a result that differs between identical
// calls.
struct MonteCarloTiming {
  unsigned threads = 1;
  double wall_seconds = 0;
  double truth_seconds = 0, truth_cpu_seconds = 0;
  std::uint64_t truth_steps = 0;  // steps taken, over all runs
  std::vector<double> filter_seconds, filter_cpu_seconds;
  std::vector<std::uint64_t> filter_steps;
  std::vector<std::uint64_t> filter_samples;  // samples absorbed, over all runs (sampled filters)
  // The particle reference: its time and the particles' scheme steps, over all runs.
  double reference_seconds = 0, reference_cpu_seconds = 0;
  std::uint64_t reference_steps = 0;
  // Folding the runs into statistics, after they finished; of it, folding the record series
  // (with shared runs: this process's range of record times).
  double aggregation_seconds = 0, series_seconds = 0;
  // Runs shared among processes (MonteCarloOptions::share), on the one that writes the result:
  // the seconds from handing its blocks to the exchange (the gather) to holding every process's,
  // and the bytes it then holds (its own included). Zero otherwise.
  double exchange_seconds = 0, gather_seconds = 0;
  std::uint64_t exchanged_bytes = 0, gathered_bytes = 0;
};

struct MonteCarloResult {
  // False on a process that only made its share of the runs (MonteCarloOptions::share) for
  // another to fold: then only `timing` (its own) is filled in.
  bool folded = true;
  TimeGrid grid;
  std::size_t runs = 0;
  std::uint64_t seed = 0;
  std::string scheme;  // the truth scheme's name()
  bool x0_from_prior = false;  // each run's truth started from a draw of MonteCarloOptions::initial_prior
  // filter_guards.stepping.adaptive: the grid-stepped filters' steps split where P would change
  // too fast (FilterStepper), or, false, one step() per grid step as the generated code takes.
  bool refined_stepping = true;
  std::size_t n = 0;   // state components
  std::vector<FilterStatistics> filters;
  std::optional<CriterionOptions> criterion;  // as asked (the writers say which L was used)
  EventSummary truth_divergences;  // the truth guard's event time
  EventSummary truth_covariance_losses;  // those of them where G lost definiteness
  std::vector<TruthReportStatistics> truth_reports;  // as MonteCarloOptions::report_times
  std::optional<ReferenceStatistics> reference;  // when MonteCarloOptions::reference is set
  MonteCarloSeries series;
  MonteCarloTiming timing;
};

// Runs options.runs runs of the truth (scheme from x0, observation) and steps every filter on
// each. Each thread works on its own clone of the scheme and copies of the observation and of
// the filters. Run r reproduces simulate_truth(scheme, observation, x0, grid, seed, r,
// truth_guard) and run_filter(filter, truth, filter_guards) bit for bit. Filters must have the
// truth's n states and the observation's p, distinct non-empty names, and the observation's
// timing: continuous filters (GridSteps, FixedSteps) on increments, sampled ones (SampledSteps:
// predict and update) on samples. With samples the truth is stepped on its grid as above (its steps and
// truth stream unchanged), the samples drawn at t_k = t0 + k T (draw_samples; the period must be
// a whole number of grid steps, std::invalid_argument otherwise), the filters predicting between
// samples and updating at each, and each FilterStatistics has `sampled` set.
// std::invalid_argument for inconsistent inputs or options; an exception thrown by a callback in a
// worker stops the other workers and is rethrown here.
MonteCarloResult run_monte_carlo(const TruthScheme& scheme, const Observation& observation,
                                 const Eigen::VectorXd& x0, const std::vector<FilterModel>& filters,
                                 const MonteCarloOptions& options);

}  // namespace pfgen_runtime
