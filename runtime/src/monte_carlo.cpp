// run_monte_carlo: checks the inputs, plans, hands the runs (this process's share of them, when
// shared among processes) to one Worker per thread, folds the runs into statistics and sums the
// workers' timing. The parts live in monte_carlo/: plan (the
// grid points where something is recorded), worker (one thread's runs), aggregate (the
// statistics, in run order) and parallel_for (the threads).
#include "pfgen_runtime/monte_carlo.hpp"

#include <algorithm>
#include <atomic>
#include <cmath>
#include <memory>
#include <mutex>
#include <set>
#include <stdexcept>
#include <string>
#include <utility>
#include <vector>

#include "monte_carlo/aggregate.hpp"
#include "monte_carlo/clock.hpp"
#include "monte_carlo/handed_out_runs.hpp"
#include "monte_carlo/parallel_for.hpp"
#include "monte_carlo/plan.hpp"
#include "monte_carlo/run_codec.hpp"
#include "monte_carlo/run_order.hpp"
#include "monte_carlo/run_result.hpp"
#include "monte_carlo/series_codec.hpp"
#include "monte_carlo/series_rows.hpp"
#include "monte_carlo/shared_series.hpp"
#include "monte_carlo/worker.hpp"
#include "pfgen_runtime/statistics.hpp"

namespace pfgen_runtime {

namespace {

using namespace monte_carlo_detail;

void validate(const TruthScheme& scheme, const Observation& observation, const Eigen::VectorXd& x0,
              const std::vector<FilterModel>& filters, const MonteCarloOptions& options) {
  const std::size_t n = scheme.system().n;
  const std::size_t p = observation.p();
  if (static_cast<std::size_t>(x0.size()) != n || observation.n() != n)
    throw std::invalid_argument("monte carlo: x0 and the observation must have the truth's n states");
  if (options.initial_prior &&
      (static_cast<std::size_t>(options.initial_prior->mean.size()) != n ||
       static_cast<std::size_t>(options.initial_prior->covariance.rows()) != n ||
       static_cast<std::size_t>(options.initial_prior->covariance.cols()) != n))
    throw std::invalid_argument("monte carlo: the initial prior must have the truth's n states");
  if (!(options.grid.dt > 0) || options.grid.steps == 0 || !std::isfinite(options.grid.t0) ||
      !std::isfinite(options.grid.end()))
    throw std::invalid_argument("monte carlo: the time grid needs dt > 0 and at least one step");
  if (options.runs == 0) throw std::invalid_argument("monte carlo: runs must be at least 1");
  if (options.threads == 0) throw std::invalid_argument("monte carlo: threads must be at least 1");
  if (options.batch == 0) throw std::invalid_argument("monte carlo: batch must be at least 1");
  if (options.record_points == 0) throw std::invalid_argument("monte carlo: record_points must be at least 1");
  if (options.shown_run >= options.runs) throw std::invalid_argument("monte carlo: the shown run is not among the runs");
  if (options.share) {
    const RunShare& share = *options.share;
    const bool runs_among =
        share.chunk == 0 ? share.first <= options.runs && share.count <= options.runs - share.first && !share.hand_out
                         : share.process < share.processes &&
                               (share.hand_out ||
                                share.count == dealt_runs(options.runs, share.chunk, share.process, share.processes));
    if (!runs_among || share.process >= share.processes || !share.exchange || !share.gather)
      throw std::invalid_argument(
          "monte carlo: a process's share must be runs among the job's (chunks when handed out), of a process among "
          "the job's, with an exchange and a gather");
  }
  std::set<std::string> names;
  for (const FilterModel& filter : filters) {
    if (filter.name.empty() || !names.insert(filter.name).second)
      throw std::invalid_argument("monte carlo: filter names must be non-empty and distinct ('" + filter.name + "')");
    // A filter of the observation's timing: on samples it predicts and updates, on increments it steps.
    if (!filter.initial_state || !filter.timing || !filter.timing->complete() ||
        filter.timing->takes_samples() != observation.sampled())
      throw std::invalid_argument("monte carlo: filter '" + filter.name + "' lacks initial_state or step " +
                                  "(predict and update for sampled observations)");
    if (filter.n != n || filter.p != p)
      throw std::invalid_argument("monte carlo: filter '" + filter.name +
                                  "' must have the truth's n states and the observation's p");
    check_filter_grid(filter, options.grid);
  }
  if (options.criterion) {
    if (!(options.criterion->epsilon > 0) || !std::isfinite(options.criterion->epsilon))
      throw std::invalid_argument("monte carlo: the criterion's epsilon must be finite and > 0");
    const std::string problem = criterion_weight_problem(options.criterion->weight, n);
    if (!problem.empty()) throw std::invalid_argument("monte carlo: " + problem);
  }
  if (options.reference)  // its checks
    (void)ParticleReference(scheme, observation, *options.reference, options.truth_guard.bound());
  if (observation.sampled()) (void)observation.steps_per_sample(options.grid.dt);  // throws unless whole
  (void)observation.delay_steps(options.grid.dt);  // throws unless h is a whole number of steps
}

}  // namespace

std::size_t dealt_runs(std::size_t runs, std::size_t chunk, std::size_t process, std::size_t processes) {
  if (chunk == 0 || processes == 0) throw std::invalid_argument("monte carlo: runs are dealt in chunks of >= 1 run");
  return runs_of(dealt_owners(runs, chunk, processes), chunk, runs, process).size();
}

double EventSummary::earliest() const {
  double t = nan;
  for (const RunEvent& event : events)
    if (!(event.t >= t)) t = event.t;  // the first comparison with NaN takes the event
  return t;
}

double EventSummary::median() const {
  if (events.empty()) return nan;
  std::vector<double> times;
  for (const RunEvent& event : events) times.push_back(event.t);
  return quantile(std::move(times), 0.5);
}

namespace {

// The most runs a worker carries at once: each keeps its truth path and increments (and, in the
// lanes, a second copy of both), which stay within kBatchBytes together; long runs go fewer at a
// time, down to one.
std::size_t batch_limit(const Plan& plan) {
  const double per_run = 2.0 * static_cast<double>(plan.grid.steps + 1) * static_cast<double>(plan.n + plan.p) *
                         sizeof(double);
  return static_cast<std::size_t>(std::max(1.0, std::floor(static_cast<double>(kBatchBytes) / per_run)));
}

}  // namespace

MonteCarloResult run_monte_carlo(const TruthScheme& scheme, const Observation& observation, const Eigen::VectorXd& x0,
                                 const std::vector<FilterModel>& filters, const MonteCarloOptions& options) {
  const Clock::time_point wall_start = Clock::now();
  validate(scheme, observation, x0, filters, options);
  const Plan plan = make_plan(scheme.system().n, observation.p(), options);

  // This process's runs: all of them, or its share (a block, or chunks dealt or handed out to it).
  const RunShare* share = options.share ? &*options.share : nullptr;
  const std::size_t chunk = share ? share->chunk : 0;
  std::vector<std::size_t> owners;  // with chunks: the process of each chunk of the job
  std::vector<std::size_t> numbers;  // the job's number of this process's k-th run
  std::vector<RunResult> runs;
  std::vector<std::unique_ptr<Worker>> workers;
  std::size_t finished = 0;
  std::mutex finished_mutex;
  const auto one_run_finished = [&](std::size_t count) {
    std::lock_guard<std::mutex> lock(finished_mutex);
    ++finished;
    if (options.on_run_finished) options.on_run_finished(finished, count);
  };
  const auto make_worker = [&](std::size_t batch) {
    return [&, batch](unsigned thread) {
      workers[thread] = std::make_unique<Worker>(scheme, observation, filters, x0, plan, options, batch);
      return workers[thread].get();
    };
  };
  if (share && share->hand_out) {
    // Handed out: batches of a chunk's consecutive runs; the chunks come as the threads are free.
    const std::size_t chunks = chunk_count(options.runs, chunk);
    const std::size_t batch = std::max<std::size_t>(1, std::min({options.batch, chunk, batch_limit(plan)}));
    workers.resize(std::max<std::size_t>(1, std::min<std::size_t>(options.threads, chunks)));
    HandedOutRuns handed = make_handed_out_runs(*share, options.runs, static_cast<unsigned>(workers.size()), batch,
                                                make_worker(batch), [&] { one_run_finished(options.runs); });
    owners = std::move(handed.owners);
    numbers = runs_of(owners, chunk, options.runs, share->process);
    runs.reserve(numbers.size());
    for (std::size_t c = 0; c < chunks; ++c)
      for (RunResult& run : handed.made[c]) runs.push_back(std::move(run));
  } else {
    const std::size_t count = share ? share->count : options.runs;
    if (chunk != 0) {
      owners = dealt_owners(options.runs, chunk, share->processes);
      numbers = runs_of(owners, chunk, options.runs, share->process);
    } else {
      for (std::size_t k = 0; k < count; ++k) numbers.push_back(share ? share->first + k : k);
    }
    runs.resize(count);
    // The runs in batches of consecutive runs, a batch to a worker at a time; smaller batches where
    // there would not be one for every thread, and none across the end of a dealt chunk (the next
    // run of this process is then not the next run of the job).
    const std::size_t per_thread = (count + options.threads - 1) / options.threads;
    const std::size_t batch = std::max<std::size_t>(1, std::min({options.batch, per_thread, batch_limit(plan)}));
    std::vector<std::pair<std::size_t, std::size_t>> batch_runs;  // (this process's first run, count)
    for (std::size_t k = 0; k < count;) {
      const std::size_t size = std::min({batch, count - k, chunk == 0 ? count : chunk - k % chunk});
      batch_runs.emplace_back(k, size);
      k += size;
    }
    const std::size_t batches = batch_runs.size();
    workers.resize(std::max<std::size_t>(1, std::min<std::size_t>(options.threads, batches)));
    parallel_for(batches, static_cast<unsigned>(workers.size()), make_worker(batch), [&](std::size_t b, Worker* worker) {
      const auto [k, size] = batch_runs[b];
      worker->run(numbers[k], size, runs.data() + k);
      for (std::size_t r = 0; r < size; ++r) one_run_finished(count);
    });
  }
  const unsigned threads = static_cast<unsigned>(workers.size());

  // Zero timing with one entry per filter (and per sampled filter).
  const auto no_timing = [&] {
    MonteCarloTiming zero;
    zero.threads = 0;
    zero.filter_seconds.assign(filters.size(), 0.0);
    zero.filter_cpu_seconds.assign(filters.size(), 0.0);
    zero.filter_steps.assign(filters.size(), 0);
    if (observation.sampled()) zero.filter_samples.assign(filters.size(), 0);
    return zero;
  };
  MonteCarloResult result;
  MonteCarloTiming& timing = result.timing;
  timing = no_timing();
  timing.threads = threads;
  for (const auto& worker : workers) {
    timing.truth_seconds += worker->truth_seconds;
    timing.truth_cpu_seconds += worker->truth_cpu_seconds;
    timing.truth_steps += worker->truth_steps;
    timing.reference_seconds += worker->reference_seconds;
    timing.reference_cpu_seconds += worker->reference_cpu_seconds;
    timing.reference_steps += worker->reference_steps;
    for (std::size_t f = 0; f < filters.size(); ++f) {
      timing.filter_seconds[f] += worker->filter_seconds[f];
      timing.filter_cpu_seconds[f] += worker->filter_cpu_seconds[f];
      timing.filter_steps[f] += worker->filter_steps[f];
      if (observation.sampled()) timing.filter_samples[f] += worker->filter_samples[f];
    }
  }

  const bool reference = options.reference.has_value();
  start_series(plan, filters.size(), reference, result.series);
  double series_seconds = 0;  // folding the series (this process's range of them)
  if (!options.share) {
    const Clock::time_point fold_start = Clock::now();
    const RecordRange all_records{0, plan.records.size()};
    const SliceRows rows = rows_of(runs, all_records, plan.n, filters.size());
    fold_series(plan, filters.size(), rows.runs, all_records, reference, threads, result.series);
    series_seconds = seconds_since(fold_start);
  } else {
    const RunShare& share = *options.share;
    const auto range = [&](std::size_t process) { return series_range(plan.records.size(), process, share.processes); };
    const SharedFoldTiming shared =
        fold_shared_series(plan, filters.size(), runs, reference, threads, options.runs, owners, share, result.series);
    timing.exchange_seconds = shared.exchange_seconds;
    timing.exchanged_bytes = shared.exchanged_bytes;
    series_seconds = shared.fold_seconds;
    // Folded: of the record vectors only the shown run's paths are still read.
    for (std::size_t k = 0; k < runs.size(); ++k) {
      RunResult& run = runs[k];
      for (FilterRunResult& filter : run.filters) filter.error_record = filter.nees_record = {};
      run.reference.error_record = {};
      if (numbers[k] == options.shown_run) continue;
      run.truth_record = {};
      for (FilterRunResult& filter : run.filters) filter.reference_record = {};
    }
    // Every process's runs and the rows each folded, on the one that writes the result (which puts
    // the runs back in run order); the others stop here.
    std::vector<char> mine = encode_share(runs, timing, encode_series_rows(result.series, range(share.process)));
    const Clock::time_point gather_start = Clock::now();
    const std::vector<std::vector<char>> blocks = share.gather(std::move(mine));
    timing.gather_seconds = seconds_since(gather_start);
    if (blocks.empty()) {
      result.series = MonteCarloSeries{};
      result.folded = false;
      timing.series_seconds = timing.aggregation_seconds = series_seconds;
      timing.wall_seconds = seconds_since(wall_start);
      return result;
    }
    MonteCarloTiming all = no_timing();  // every process's threads and times
    std::vector<std::vector<RunResult>> made(std::min(blocks.size(), share.processes));
    for (std::size_t process = 0; process < made.size(); ++process)
      decode_series_rows(decode_share(blocks[process], filters.size(), made[process], all), range(process),
                         result.series);
    runs = in_run_order(std::move(made), share, options.runs, owners);
    check_share_count(blocks.size(), runs.size(), share, options.runs);
    all.exchange_seconds = timing.exchange_seconds;
    all.exchanged_bytes = timing.exchanged_bytes;
    all.gather_seconds = timing.gather_seconds;
    for (const std::vector<char>& block : blocks) all.gathered_bytes += block.size();
    timing = all;
  }

  const Clock::time_point summaries_start = Clock::now();
  result.grid = options.grid;
  result.runs = options.runs;
  result.seed = options.seed;
  result.scheme = scheme.name();
  result.x0_from_prior = options.initial_prior.has_value();
  result.refined_stepping = options.filter_guards.stepping.adaptive && options.filter_guards.stepping.max_depth > 0;
  result.n = plan.n;
  result.criterion = options.criterion;
  aggregate(plan, filters, runs, options, result);
  for (FilterStatistics& filter : result.filters)
    if (filter.sampled) filter.sampled->nonlinear = !observation.rate().affine();
  timing.series_seconds = series_seconds;
  timing.aggregation_seconds = series_seconds + seconds_since(summaries_start);
  timing.wall_seconds = seconds_since(wall_start);
  return result;
}

}  // namespace pfgen_runtime
