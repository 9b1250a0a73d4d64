// The Monte Carlo engine and its reports: results bitwise identical for any thread count and
// equal to simulate_truth + run_filter run by run; a hand-written Kalman-Bucy filter's RMS error
// matches the stationary Riccati solution; diverging filters, PSD losses and a blowing-up truth
// are reported with their times and never print NaN or inf; the table and CSV are deterministic
// and well-formed; gnuplot draws the plot. Also the RK4 truth scheme's order and the cheap PSD
// check's agreement with the eigenvalue check.
#include <catch2/catch.hpp>

#include <algorithm>
#include <atomic>
#include <cctype>
#include <chrono>
#include <cmath>
#include <cstdint>
#include <cstdlib>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <functional>
#include <limits>
#include <random>
#include <regex>
#include <set>
#include <sstream>
#include <stdexcept>
#include <string>
#include <vector>

#include <unistd.h>

#include <Eigen/Core>

#include "pfgen_runtime/gnuplot_plot.hpp"
#include "pfgen_runtime/guards.hpp"
#include "pfgen_runtime/monte_carlo.hpp"
#include "pfgen_runtime/results_csv.hpp"
#include "pfgen_runtime/schemes.hpp"
#include "pfgen_runtime/simulation.hpp"
#include "support/scalar_linear_system.hpp"
#include "support/shared_runs.hpp"
#include "pfgen_runtime/summary_table.hpp"

using namespace pfgen_runtime;
using pfgen_test::ScalarLinear;
using pfgen_test::scalar_linear_system;
using pfgen_test::scalar_observation;

namespace {

// The Kalman-Bucy filter written out by hand, in the generated calling convention; `gain_sign`
// -1 makes it deliberately wrong: the innovation pushes m away from x and m runs off like e^(9t).
FilterModel kalman_bucy(const ScalarLinear& model, const std::string& name, double gain_sign = 1.0,
                        double gain = 0.0) {
  FilterModel filter;
  filter.name = name;
  filter.n = 1;
  filter.p = 1;
  filter.initial_state = [model](double* state) {
    state[0] = model.m0;
    state[1] = model.P0;
  };
  filter.timing = std::make_unique<GridSteps>([model, gain_sign, gain](double* state, double, double dt, const double* dy) {
    const double m = state[0], P = state[1];
    const double K = gain > 0 ? gain : P / (model.r * model.r);
    state[0] = m - model.a * m * dt + gain_sign * K * (dy[0] - m * dt);
    state[1] = P + (-2 * model.a * P + model.s * model.s - P * P / (model.r * model.r)) * dt;
  });
  return filter;
}

// m stays 0, P = 0.5 - t: P loses definiteness just after t = 0.5.
FilterModel shrinking() {
  FilterModel filter;
  filter.name = "shrinking";
  filter.n = 1;
  filter.p = 1;
  filter.initial_state = [](double* state) {
    state[0] = 0.0;
    state[1] = 0.5;
  };
  filter.timing = std::make_unique<GridSteps>([](double* state, double, double dt, const double*) { state[1] -= dt; });
  return filter;
}

// Every number of a result except its timing, in a fixed order, for bitwise comparison.
std::vector<double> flatten(const MonteCarloResult& result) {
  std::vector<double> out{static_cast<double>(result.runs), static_cast<double>(result.n)};
  auto add = [&out](const std::vector<double>& v) { out.insert(out.end(), v.begin(), v.end()); };
  auto add_matrix = [&out](const Eigen::MatrixXd& m) { out.insert(out.end(), m.data(), m.data() + m.size()); };
  auto add_counts = [&out](const std::vector<std::size_t>& v) {
    for (std::size_t c : v) out.push_back(static_cast<double>(c));
  };
  auto add_events = [&out](const EventSummary& events) {
    out.push_back(static_cast<double>(events.count()));
    for (const RunEvent& e : events.events) {
      out.push_back(static_cast<double>(e.run));
      out.push_back(e.t);
    }
    out.push_back(events.earliest());
    out.push_back(events.median());
  };
  auto add_window = [&](const WindowStatistics& w) {
    out.insert(out.end(), {w.a, w.b, static_cast<double>(w.first), static_cast<double>(w.last),
                           static_cast<double>(w.runs)});
    add(w.rms);
  };
  for (const FilterStatistics& f : result.filters) {
    add_window(f.horizon);
    for (const WindowStatistics& w : f.windows) add_window(w);
    for (const ReportStatistics& r : f.reports) {
      out.insert(out.end(), {r.t, static_cast<double>(r.index), static_cast<double>(r.alive)});
      add(r.mean_abs);
      add(r.rms);
    }
    add(f.peak_median);
    add(f.peak_q95);
    add_events(f.divergences);
    add_events(f.psd_losses);
  }
  add_events(result.truth_divergences);
  const MonteCarloSeries& s = result.series;
  add_counts(s.index);
  add(s.t);
  add_matrix(s.truth);
  for (const SeriesStatistics* stats : {&s.truth_statistics}) {
    add_matrix(stats->mean);
    add_matrix(stats->q05);
    add_matrix(stats->q50);
    add_matrix(stats->q95);
  }
  add_counts(s.truth_alive);
  for (const FilterSeries& f : s.filters) {
    add_matrix(f.m);
    add_matrix(f.P_diagonal);
    add_matrix(f.error.mean);
    add_matrix(f.error.q05);
    add_matrix(f.error.q50);
    add_matrix(f.error.q95);
    add_counts(f.alive);
  }
  return out;
}

bool bitwise_equal(const std::vector<double>& a, const std::vector<double>& b) {
  return a.size() == b.size() && (a.empty() || std::memcmp(a.data(), b.data(), a.size() * sizeof(double)) == 0);
}

bool same_bits(double a, double b) { return std::memcmp(&a, &b, sizeof a) == 0; }

// What one run of the engine shows, for comparing two runs bit for bit: every number of the
// result (flatten), the table and the CSV, the refinement and stop counts, the criterion's
// integrals.
struct Outputs {
  std::vector<double> numbers;
  std::string table, csv;
  std::vector<std::uint64_t> counts;
  std::vector<double> integrals;
};

Outputs outputs_of(const MonteCarloResult& result) {
  Outputs out{flatten(result), format_summary_table(result, {"x"}), format_results_csv(result, {"x"}), {}, {}};
  for (const FilterStatistics& f : result.filters) {
    out.counts.insert(out.counts.end(), {f.refined_steps, f.refined_runs, f.too_stiff_runs, f.undefined_runs});
    if (f.criterion) out.integrals.insert(out.integrals.end(), f.criterion->integrals.begin(), f.criterion->integrals.end());
  }
  return out;
}

void check_same_outputs(const Outputs& a, const Outputs& b) {
  CHECK(bitwise_equal(a.numbers, b.numbers));
  CHECK(a.table == b.table);
  CHECK(a.csv == b.csv);
  CHECK(a.counts == b.counts);
  CHECK(bitwise_equal(a.integrals, b.integrals));
}

std::string lowercase(std::string text) {
  std::transform(text.begin(), text.end(), text.begin(), [](unsigned char c) { return static_cast<char>(std::tolower(c)); });
  return text;
}

bool mentions_nan_or_inf(const std::string& text) {
  const std::string lower = lowercase(text);
  return lower.find("nan") != std::string::npos || lower.find("inf") != std::string::npos;
}

// The OU truth of ScalarLinear with three filters: the right one, a diverging one and one that
// loses definiteness; the truth guard at 1.6 stops some runs early, so partial runs are covered.
struct Scenario {
  ScalarLinear model;
  std::vector<FilterModel> filters{kalman_bucy(model, "kalman-bucy"), kalman_bucy(model, "wrong", -1.0, 10.0),
                                   shrinking()};
  MonteCarloOptions options;
  Scenario() {
    options.grid = TimeGrid::to_horizon(0.0, 3.0, 0.01);
    options.runs = 23;
    options.seed = 77;
    options.record_points = 40;
    options.shown_run = 4;
    options.report_times = {0.5, 1.0, 3.0};
    options.windows = {{0.5, 1.5}, {2.0, 3.0}};
    options.truth_guard = DivergenceGuard(1.6);
  }
};

std::string temporary_directory() {
  const auto dir = std::filesystem::temp_directory_path() /
                   ("pfgen-montecarlo-" + std::to_string(static_cast<long>(getpid())));
  std::filesystem::create_directories(dir);
  return dir.string();
}

std::string read_file(const std::string& path) {
  std::ifstream file(path, std::ios::binary);
  std::stringstream text;
  text << file.rdbuf();
  return text.str();
}

}  // namespace

TEST_CASE("monte carlo: results are bitwise identical for 1, 2 and 3 threads", "[montecarlo][runtime][unit]") {
  Scenario scenario;
  EulerMaruyama scheme(scalar_linear_system(scenario.model));
  const Observation observation = scalar_observation(scenario.model.r);
  const Eigen::VectorXd x0 = Eigen::VectorXd::Constant(1, 0.3);

  Outputs reference;
  for (unsigned threads : {1u, 2u, 3u}) {
    scenario.options.threads = threads;
    const MonteCarloResult result = run_monte_carlo(scheme, observation, x0, scenario.filters, scenario.options);
    CHECK(result.timing.threads == threads);
    const Outputs outputs = outputs_of(result);
    if (threads == 1) {
      reference = outputs;
      // The scenario covers what it should: some truths stopped, every wrong filter diverged.
      CHECK(result.truth_divergences.count() > 0);
      CHECK(result.truth_divergences.count() < result.runs);
      CHECK(result.filters[1].divergences.count() > 0);
      CHECK(result.filters[2].psd_losses.count() > 0);
      continue;
    }
    INFO("threads = " << threads);
    check_same_outputs(outputs, reference);
  }
}

// A filter's lanes form as a loop over its one-state step: the engine's lanes machinery (packed
// checks and sums, the refinement and guards of a lane alone) is then what the test exercises.
FilterModel in_lanes(FilterModel filter, std::size_t width) {
  const FilterStepFunction step = dynamic_cast<const GridSteps&>(*filter.timing).step();
  FilterStepFunction step_lanes = [step, width, size = filter.state_size(), p = filter.p](
                                      double* states, double t, double dt, const double* dy) {
    std::vector<double> state(size), increment(p);
    for (std::size_t k = 0; k < width; ++k) {
      for (std::size_t i = 0; i < size; ++i) state[i] = states[i * width + k];
      for (std::size_t r = 0; r < p; ++r) increment[r] = dy[r * width + k];
      step(state.data(), t, dt, increment.data());
      for (std::size_t i = 0; i < size; ++i) states[i * width + k] = state[i];
    }
  };
  filter.timing = std::make_unique<GridSteps>(step, std::move(step_lanes), width);
  return filter;
}

// The Kalman-Bucy filter from a P0 so large that its first grid steps change P by far more than
// the stepper allows: they are refined.
FilterModel stiff_start(const ScalarLinear& model) {
  FilterModel filter = kalman_bucy(model, "stiff-start");
  filter.initial_state = [model](double* state) {
    state[0] = model.m0;
    state[1] = 1e4;
  };
  return filter;
}

TEST_CASE("monte carlo: results are bitwise identical for any batch, filters stepped in lanes or alone",
          "[montecarlo][runtime][unit]") {
  Scenario scenario;
  // The system with batched forms too, so that the truths' lanes take grid steps at once.
  SdeSystem system = scalar_linear_system(scenario.model);
  system.drift_batch = [f = system.drift](double t, std::size_t count, const double* x, double* out) {
    for (std::size_t k = 0; k < count; ++k) f(t, x + k, out + k);
  };
  system.diffusion_batch = [g = system.diffusion](double t, std::size_t count, const double* x, double* out) {
    for (std::size_t k = 0; k < count; ++k) g(t, x + k, out + k);
  };
  // Adaptive Euler bisects where |x| is large against its tolerance: lanes leave the batched
  // step for their own scheme's, with their own bridge draws.
  AdaptiveEuler::Options tight;
  tight.tolerance = 0.02;
  const EulerMaruyama euler(system);
  const AdaptiveEuler adaptive(system, tight);
  const Observation observation = scalar_observation(scenario.model.r);
  const Eigen::VectorXd x0 = Eigen::VectorXd::Constant(1, 0.3);
  // Every filter in lanes of 4 (the worker then keeps the truths only interleaved), or with one
  // of another width and one without lanes beside them (which read each run's own buffers).
  std::vector<FilterModel> in_lanes_only;
  for (const FilterModel& filter : scenario.filters) in_lanes_only.push_back(in_lanes(filter, 4));
  in_lanes_only.push_back(in_lanes(stiff_start(scenario.model), 4));
  std::vector<FilterModel> mixed = in_lanes_only;
  mixed.push_back(in_lanes(kalman_bucy(scenario.model, "other-width"), 2));  // one run at a time
  mixed.push_back(kalman_bucy(scenario.model, "no-lanes"));
  // The widths of the lane packs a generated plugin uses: the diverging, the PSD-losing and the
  // refined filter again, in lanes of 8 and 16.
  for (const std::size_t width : {8, 16})
    for (const std::size_t f : {1, 2, 3}) {
      FilterModel wide = in_lanes(in_lanes_only[f], width);
      wide.name += "-" + std::to_string(width);
      mixed.push_back(wide);
    }

  struct Variant {
    const char* name;
    const TruthScheme* scheme;
    bool criterion, stop_on_psd_loss;
    const std::vector<FilterModel>* filters;
  };
  for (const Variant& variant : {Variant{"euler", &euler, false, false, &mixed},
                                 Variant{"adaptive", &adaptive, true, false, &mixed},
                                 Variant{"stop on PSD loss", &euler, true, true, &mixed},
                                 Variant{"adaptive, lanes only", &adaptive, true, false, &in_lanes_only},
                                 Variant{"euler, lanes only", &euler, false, false, &in_lanes_only}}) {
    const std::vector<FilterModel>& filters = *variant.filters;
    MonteCarloOptions options = scenario.options;
    options.runs = 29;
    if (variant.criterion) options.criterion = CriterionOptions{};
    options.filter_guards.stop_on_psd_loss = variant.stop_on_psd_loss;
    Outputs reference;
    for (const auto& [batch, threads] : std::vector<std::pair<std::size_t, unsigned>>{
             {1, 1}, {2, 1}, {3, 2}, {4, 1}, {7, 2}, {8, 1}, {16, 2}, {64, 1}}) {
      options.batch = batch;
      options.threads = threads;
      const MonteCarloResult result = run_monte_carlo(*variant.scheme, observation, x0, filters, options);
      const Outputs outputs = outputs_of(result);
      if (batch == 1) {
        reference = outputs;
        CHECK(outputs.integrals.empty() != variant.criterion);
        // The scenario covers what it should: stopped truths, diverged, PSD-losing and refined filters.
        CHECK(result.truth_divergences.count() > 0);
        CHECK(result.filters[1].divergences.count() > 0);
        CHECK(result.filters[2].psd_losses.count() > 0);
        CHECK(result.filters[3].refined_steps > 0);
        continue;
      }
      INFO(variant.name << ": batch = " << batch << ", threads = " << threads);
      check_same_outputs(outputs, reference);
    }
  }
}

// What `mpirun pfgen simulate` does across ranks (MonteCarloOptions::share), here with threads of
// one process: three shares, one of them empty, exchanging their record series and gathered in
// run order by the first.
TEST_CASE("monte carlo: runs shared among processes fold to the single process's result bit for bit", "[montecarlo][runtime][unit]") {
  Scenario scenario;
  EulerMaruyama scheme(scalar_linear_system(scenario.model));
  const Observation observation = scalar_observation(scenario.model.r);
  const Eigen::VectorXd x0 = Eigen::VectorXd::Constant(1, 0.3);
  scenario.options.criterion = CriterionOptions{};  // the runs' integrals travel too
  scenario.options.threads = 2;
  const MonteCarloResult whole = run_monte_carlo(scheme, observation, x0, scenario.filters, scenario.options);

  // Runs [0, 9), [9, 9) and [9, 23): the shown run 4 is the first share's. Also with a record
  // series shorter than the processes (some fold no record time), and with one record per grid point.
  for (std::size_t records : {scenario.options.record_points, std::size_t{2}, scenario.options.grid.steps}) {
    MonteCarloOptions options = scenario.options;
    options.record_points = records;
    const MonteCarloResult single = run_monte_carlo(scheme, observation, x0, scenario.filters, options);
    const auto job = [&](RunShare share) {
      MonteCarloOptions part = options;
      part.share = std::move(share);
      return run_monte_carlo(scheme, observation, x0, scenario.filters, part);
    };
    // Values exchanged in rounds of at most about 3000 bytes and of 1 byte (as many rounds as the
    // shortest of the 3 ranges has records, when it has 2 or more), each over a part of every
    // process's range; and in one round, the default's for a job this small.
    const std::size_t shortest = single.series.index.size() / 3;
    const auto in_rounds = [&](std::size_t round_bytes) {
      pfgen_test::SharedRuns processes(3);
      std::vector<MonteCarloResult> results = processes.hand_out(23, 4, [&job, round_bytes](RunShare share) {
        share.exchange_round_bytes = round_bytes;
        return job(std::move(share));
      });
      INFO("rounds of " << round_bytes << " bytes, shortest range " << shortest << " records");
      if (round_bytes == 1) CHECK(processes.exchanges() == (shortest < 2 ? 1 : shortest));
      CHECK(processes.exchanges() >= 1);
      CHECK(processes.exchanges() <= std::max<std::size_t>(1, shortest));
      if (round_bytes == 3000 && shortest >= 4) CHECK((processes.exchanges() > 1 && processes.exchanges() < shortest));
      if (round_bytes == RunShare{}.exchange_round_bytes) CHECK(processes.exchanges() == 1);
      return results;
    };
    // In blocks; dealt in chunks of 4 (the 23 runs end in a short chunk, process 2's) and of 10
    // (process 2 gets none); handed out in chunks of 4 from a counter the processes share (a
    // different assignment each time), and as scripts: the shown run 4 with process 2, and every
    // chunk with process 1 (process 0, which folds, makes none).
    const std::vector<std::pair<std::string, std::function<std::vector<MonteCarloResult>()>>> ways = {
        {"in rounds of 3000 bytes", [&] { return in_rounds(3000); }},
        {"in rounds of 1 byte", [&] { return in_rounds(1); }},
        {"in one round", [&] { return in_rounds(RunShare{}.exchange_round_bytes); }},
        {"blocks", [&] { return pfgen_test::SharedRuns(3).run({9, 0, 14}, job); }},
        {"dealt by 4", [&] { return pfgen_test::SharedRuns(3).deal(23, 4, job); }},
        {"dealt by 10", [&] { return pfgen_test::SharedRuns(3).deal(23, 10, job); }},
        {"handed out by 4", [&] { return pfgen_test::SharedRuns(3).hand_out(23, 4, job); }},
        {"handed out by 4, scripted", [&] { return pfgen_test::SharedRuns(3).hand_out(23, 4, job, {2, 2, 0, 1, 2, 0}); }},
        {"handed out by 10, all to 1", [&] { return pfgen_test::SharedRuns(3).hand_out(23, 10, job, {1, 1, 1}); }},
    };
    for (const auto& [way, shared_job] : ways) {
      const std::vector<MonteCarloResult> results = shared_job();
      INFO("record_points = " << records << ", " << way);
      const MonteCarloResult& folded = results[0];
      CHECK_FALSE(results[1].folded);
      CHECK_FALSE(results[2].folded);
      REQUIRE(folded.folded);
      CHECK(folded.timing.threads == (way == "blocks" ? 2u + 1 + 2 : 2u + 2 + 2));  // every process's threads
      CHECK(folded.timing.truth_steps == single.timing.truth_steps);
      CHECK(folded.timing.exchanged_bytes > 0);
      CHECK(folded.timing.gathered_bytes > 0);
      CHECK(bitwise_equal(flatten(folded), flatten(single)));
      CHECK(format_summary_table(folded, {"x"}) == format_summary_table(single, {"x"}));
      CHECK(format_results_csv(folded, {"x"}) == format_results_csv(single, {"x"}));
      CHECK(format_criterion_csv(folded) == format_criterion_csv(single));
      CHECK(format_stops_csv(folded) == format_stops_csv(single));
    }
  }
  CHECK(pfgen_runtime::dealt_runs(23, 4, 0, 3) == 8);  // chunks 0 and 3
  CHECK(pfgen_runtime::dealt_runs(23, 4, 2, 3) == 7);  // chunks 2 and 5 (3 runs)
  CHECK(pfgen_runtime::dealt_runs(23, 10, 2, 3) == 3);
  CHECK(pfgen_runtime::dealt_runs(5, 10, 1, 3) == 0);
  CHECK(format_results_csv(whole, {"x"}) ==
        format_results_csv(pfgen_test::SharedRuns(1).run({23}, [&](RunShare share) {
          MonteCarloOptions part = scenario.options;
          part.share = std::move(share);
          return run_monte_carlo(scheme, observation, x0, scenario.filters, part);
        })[0], {"x"}));

  // Shares that miss runs, or bytes cut short, are refused rather than folded.
  const auto alone = [](std::size_t first, std::size_t count) {
    RunShare share;
    share.first = first;
    share.count = count;
    share.exchange = [](const std::vector<PiecedBlock>& outgoing, std::vector<std::vector<char>>& incoming) {
      incoming.clear();
      for (const PiecedBlock& block : outgoing) incoming.push_back(joined(block));
    };
    share.gather = [](std::vector<char> mine) { return std::vector<std::vector<char>>{mine}; };
    return share;
  };
  MonteCarloOptions gap = scenario.options;
  gap.share = alone(0, 9);
  CHECK_THROWS_WITH(run_monte_carlo(scheme, observation, x0, scenario.filters, gap),
                    Catch::Contains("hold 9 runs, not 23"));
  MonteCarloOptions cut = scenario.options;
  cut.share = alone(0, 23);
  cut.share->gather = [](std::vector<char> mine) {
    mine.pop_back();
    return std::vector<std::vector<char>>{mine};
  };
  CHECK_THROWS_WITH(run_monte_carlo(scheme, observation, x0, scenario.filters, cut), Catch::Contains("malformed"));
  {  // a slice cut short on its way from process 1 to process 0 (a process's own does not travel)
    pfgen_test::SharedRuns processes(2);
    processes.tamper_exchange = [](std::size_t from, std::size_t to, std::vector<char>& block) {
      if (from == 1 && to == 0) block.resize(block.size() / 2);
    };
    CHECK_THROWS_WITH(processes.deal(23, 4,
                                     [&](RunShare share) {
                                       MonteCarloOptions part = scenario.options;
                                       part.share = std::move(share);
                                       return run_monte_carlo(scheme, observation, x0, scenario.filters, part);
                                     }),
                      Catch::Contains("malformed"));
  }
  MonteCarloOptions dealt_wrong = scenario.options;  // dealt in chunks of 4, one process makes all 23
  dealt_wrong.share = alone(0, 22);
  dealt_wrong.share->chunk = 4;
  CHECK_THROWS_AS(run_monte_carlo(scheme, observation, x0, scenario.filters, dealt_wrong), std::invalid_argument);
  dealt_wrong.share->count = 23;
  dealt_wrong.share->gather = [](std::vector<char> mine) { return std::vector<std::vector<char>>{mine, mine}; };
  CHECK_THROWS_WITH(run_monte_carlo(scheme, observation, x0, scenario.filters, dealt_wrong),
                    Catch::Contains("2 processes' shares arrived, not 1"));
  {  // Hand-outs that break the rules are refused; a run that fails stops the hand-out, not hangs it.
    const auto handed = [&](std::function<std::vector<std::size_t>(ChunkFeed&)> hand_out) {
      MonteCarloOptions options = scenario.options;
      options.share = alone(0, 0);
      options.share->chunk = 4;  // 6 chunks
      options.share->hand_out = std::move(hand_out);
      return options;
    };
    const auto give_all = [](ChunkFeed& feed, std::size_t chunks) {
      for (std::size_t c = 0; c < chunks && !feed.stopped(); ++c) feed.give(c);
    };
    CHECK(format_results_csv(run_monte_carlo(scheme, observation, x0, scenario.filters, handed([&](ChunkFeed& feed) {
                                               give_all(feed, 6);
                                               return std::vector<std::size_t>(6, 0);
                                             })),
                             {"x"}) == format_results_csv(whole, {"x"}));
    // made() counts the chunks the threads have finished: all 6 before the hand-out returns.
    std::size_t made = 0;
    (void)run_monte_carlo(scheme, observation, x0, scenario.filters, handed([&](ChunkFeed& feed) {
                            give_all(feed, 6);
                            for (int wait = 0; wait < 100000 && feed.made() < 6; ++wait)
                              feed.wait_below(0, std::chrono::microseconds(100));
                            made = feed.made();
                            return std::vector<std::size_t>(6, 0);
                          }));
    CHECK(made == 6);
    CHECK_THROWS_WITH(run_monte_carlo(scheme, observation, x0, scenario.filters, handed([&](ChunkFeed& feed) {
                                        give_all(feed, 6);
                                        feed.give(2);
                                        return std::vector<std::size_t>(6, 0);
                                      })),
                      "monte carlo: chunk 2 was handed out twice");
    CHECK_THROWS_WITH(run_monte_carlo(scheme, observation, x0, scenario.filters, handed([&](ChunkFeed& feed) {
                                        feed.give(6);
                                        return std::vector<std::size_t>(6, 0);
                                      })),
                      "monte carlo: chunk 6 was handed out, but the job has 6 chunks");
    CHECK_THROWS_WITH(run_monte_carlo(scheme, observation, x0, scenario.filters, handed([&](ChunkFeed& feed) {
                                        give_all(feed, 5);
                                        return std::vector<std::size_t>(6, 0);
                                      })),
                      "monte carlo: process 0 was given 5 chunks, and the hand-out's table says 6 (or other ones)");
    CHECK_THROWS_WITH(run_monte_carlo(scheme, observation, x0, scenario.filters, handed([&](ChunkFeed& feed) {
                                        give_all(feed, 6);
                                        return std::vector<std::size_t>{0, 0, 0, 0, 0, 1};
                                      })),
                      "monte carlo: the hand-out's table gives chunk 5 to process 1 of 1");
    CHECK_THROWS_WITH(run_monte_carlo(scheme, observation, x0, scenario.filters, handed([&](ChunkFeed& feed) {
                                        give_all(feed, 6);
                                        return std::vector<std::size_t>(5, 0);
                                      })),
                      "monte carlo: the hand-out's table has 5 chunks, not the job's 6");
    CHECK_THROWS_WITH(run_monte_carlo(scheme, observation, x0, scenario.filters,
                                      handed([](ChunkFeed&) -> std::vector<std::size_t> {
                                        throw std::runtime_error("the hand-out failed");
                                      })),
                      "the hand-out failed");
    // The third run's callback fails: the threads stop, the hand-out sees it and ends, the error
    // reaches the caller.
    MonteCarloOptions failing = handed([&](ChunkFeed& feed) {
      for (std::size_t c = 0; c < 6 && !feed.stopped(); ++c) {
        while (feed.waiting() > 0 && !feed.stopped()) feed.wait_below(1, std::chrono::milliseconds(1));
        if (!feed.stopped()) feed.give(c);
      }
      return std::vector<std::size_t>(6, 0);
    });
    failing.on_run_finished = [](std::size_t done, std::size_t) {
      if (done == 3) throw std::runtime_error("stopped at the third run");
    };
    CHECK_THROWS_WITH(run_monte_carlo(scheme, observation, x0, scenario.filters, failing), "stopped at the third run");
    MonteCarloOptions unchunked = handed([](ChunkFeed&) { return std::vector<std::size_t>{}; });
    unchunked.share->chunk = 0;
    CHECK_THROWS_AS(run_monte_carlo(scheme, observation, x0, scenario.filters, unchunked), std::invalid_argument);
  }
  MonteCarloOptions missing = scenario.options;
  missing.share = alone(0, 23);
  missing.share->gather = [](std::vector<char> mine) { return std::vector<std::vector<char>>{mine, mine}; };
  CHECK_THROWS_WITH(run_monte_carlo(scheme, observation, x0, scenario.filters, missing),
                    Catch::Contains("2 processes' shares arrived, not 1"));
  MonteCarloOptions outside = scenario.options;
  outside.share = alone(20, 4);
  CHECK_THROWS_AS(run_monte_carlo(scheme, observation, x0, scenario.filters, outside), std::invalid_argument);
  MonteCarloOptions no_place = scenario.options;
  no_place.share = alone(0, 23);
  no_place.share->process = 1;
  CHECK_THROWS_AS(run_monte_carlo(scheme, observation, x0, scenario.filters, no_place), std::invalid_argument);
}

// What one process receives from the others is decoded defensively: bytes changed or cut anywhere
// in an exchanged slice or a gathered share are folded (a changed number is a number) or refused
// with a runtime_error, never read out of bounds or allocated by a corrupt length.
TEST_CASE("monte carlo: corrupted shares are folded or refused, never read out of bounds", "[montecarlo][runtime][unit]") {
  Scenario scenario;
  EulerMaruyama scheme(scalar_linear_system(scenario.model));
  const Observation observation = scalar_observation(scenario.model.r);
  const Eigen::VectorXd x0 = Eigen::VectorXd::Constant(1, 0.3);
  scenario.options.runs = 5;
  scenario.options.shown_run = 1;
  std::mt19937 rng(2026);
  std::size_t refused = 0, folded = 0;
  for (int trial = 0; trial < 300; ++trial) {
    const bool in_exchange = trial % 2 == 0, cut = trial % 3 == 0;
    const auto corrupt = [&](std::vector<char>& bytes) {
      if (bytes.empty()) return;
      const std::size_t at = std::uniform_int_distribution<std::size_t>(0, bytes.size() - 1)(rng);
      if (cut)
        bytes.resize(at);
      else
        bytes[at] = static_cast<char>(bytes[at] ^ (1 << std::uniform_int_distribution<int>(0, 7)(rng)));
    };
    // Two processes (a process's own slice does not travel): process 1's block to process 0 is
    // corrupted, in the exchange or in the gather.
    pfgen_test::SharedRuns processes(2);
    if (in_exchange)
      processes.tamper_exchange = [&](std::size_t from, std::size_t to, std::vector<char>& block) {
        if (from == 1 && to == 0) corrupt(block);
      };
    else
      processes.tamper_gather = [&](std::size_t from, std::vector<char>& block) {
        if (from == 1) corrupt(block);
      };
    const auto job = [&](RunShare share) {
      MonteCarloOptions options = scenario.options;
      options.share = std::move(share);
      return run_monte_carlo(scheme, observation, x0, scenario.filters, options);
    };
    try {
      if (trial % 4 < 2)
        (void)processes.run({3, 2}, job);
      else
        (void)processes.deal(5, 2, job);
      ++folded;
    } catch (const std::runtime_error& error) {
      CHECK(std::string(error.what()).find("monte carlo: ") == 0);
      ++refused;
    }
  }
  CHECK(refused > 0);
  CHECK(folded > 0);
}

TEST_CASE("monte carlo: each run equals simulate_truth + run_filter bit for bit", "[montecarlo][runtime][unit]") {
  Scenario scenario;
  ScalarLinear& model = scenario.model;
  // The adaptive scheme draws from a stream of its own (start_run): the engine must reseed it.
  AdaptiveEuler scheme(scalar_linear_system(model), AdaptiveEuler::Options{0.02, 0.1, 20});
  Observation observation = scalar_observation(model.r);
  const Eigen::VectorXd x0 = Eigen::VectorXd::Constant(1, -0.2);
  MonteCarloOptions& options = scenario.options;
  options.threads = 2;
  options.record_points = options.grid.steps;  // every grid point

  for (std::size_t shown : {std::size_t{4}, std::size_t{0}}) {
    options.shown_run = shown;
    const MonteCarloResult result = run_monte_carlo(scheme, observation, x0, scenario.filters, options);
    REQUIRE(result.series.t.size() == options.grid.steps + 1);

    std::size_t truth_events = 0;
    std::vector<std::size_t> divergence_events(scenario.filters.size(), 0), psd_events(scenario.filters.size(), 0);
    for (std::size_t run = 0; run < options.runs; ++run) {
      auto own_scheme = scheme.clone();
      const TruthRun truth = simulate_truth(*own_scheme, observation, x0, options.grid, options.seed, run,
                                            options.truth_guard);
      INFO("run " << run);
      if (truth.diverged()) {
        REQUIRE(truth_events < result.truth_divergences.count());
        const RunEvent& event = result.truth_divergences.events[truth_events++];
        CHECK(event.run == run);
        CHECK(same_bits(event.t, truth.divergence->t));
      }
      for (std::size_t f = 0; f < scenario.filters.size(); ++f) {
        const FilterRun filtered = run_filter(scenario.filters[f], truth, options.filter_guards);
        const FilterStatistics& stats = result.filters[f];
        if (filtered.divergence) {
          REQUIRE(divergence_events[f] < stats.divergences.count());
          const RunEvent& event = stats.divergences.events[divergence_events[f]++];
          CHECK(event.run == run);
          CHECK(same_bits(event.t, filtered.divergence->t));
        }
        if (filtered.psd_loss) {
          REQUIRE(psd_events[f] < stats.psd_losses.count());
          const RunEvent& event = stats.psd_losses.events[psd_events[f]++];
          CHECK(event.run == run);
          CHECK(same_bits(event.t, filtered.psd_loss->t));
        }
        if (run != shown) continue;
        const FilterSeries& series = result.series.filters[f];
        for (Eigen::Index k = 0; k <= static_cast<Eigen::Index>(options.grid.steps); ++k) {
          if (k < filtered.state.cols()) {
            CHECK(same_bits(series.m(k, 0), filtered.state(0, k)));
            CHECK(same_bits(series.P_diagonal(k, 0), filtered.state(1, k)));
          } else {
            CHECK(std::isnan(series.m(k, 0)));
          }
        }
      }
      if (run == shown) {
        for (Eigen::Index k = 0; k <= static_cast<Eigen::Index>(options.grid.steps); ++k) {
          if (k < truth.x.cols())
            CHECK(same_bits(result.series.truth(k, 0), truth.x(0, k)));
          else
            CHECK(std::isnan(result.series.truth(k, 0)));
        }
      }
    }
    CHECK(truth_events == result.truth_divergences.count());
    for (std::size_t f = 0; f < scenario.filters.size(); ++f) {
      CHECK(divergence_events[f] == result.filters[f].divergences.count());
      CHECK(psd_events[f] == result.filters[f].psd_losses.count());
    }
  }
}

TEST_CASE("monte carlo: Kalman-Bucy RMS error is sqrt(P_inf); wrong filters are reported with times", "[montecarlo][runtime][statistical]") {
  const ScalarLinear model;
  EulerMaruyama scheme(scalar_linear_system(model));
  const Observation observation = scalar_observation(model.r);
  MonteCarloOptions options;
  options.grid = TimeGrid::to_horizon(0.0, 10.0, 2e-3);
  options.runs = 1000;
  options.seed = 2024;
  options.threads = 2;
  options.record_points = 100;
  options.windows = {{2.0, 10.0}, {0.0, 0.4}};
  options.report_times = {10.0, 0.3};
  // Called from the worker threads: count there, assert here (Catch's macros are not thread-safe).
  std::atomic<std::size_t> calls{0}, largest{0}, wrong_totals{0};
  options.on_run_finished = [&](std::size_t finished, std::size_t total) {
    ++calls;
    std::size_t seen = largest.load();
    while (finished > seen && !largest.compare_exchange_weak(seen, finished)) {
    }
    if (total != 1000) ++wrong_totals;
  };
  // The truth starts at the filter's mean 0 (the error is then only the filter's, not the prior's).
  const std::vector<FilterModel> filters{kalman_bucy(model, "kalman-bucy"), kalman_bucy(model, "wrong", -1.0, 10.0),
                                         shrinking()};
  const MonteCarloResult result = run_monte_carlo(scheme, observation, Eigen::VectorXd::Zero(1), filters, options);
  CHECK(calls == 1000);
  CHECK(largest == 1000);
  CHECK(wrong_totals == 0);

  // Euler steps of the truth and of the filter shift the stationary error variance by O(dt).
  const double root_P = std::sqrt(model.P_inf());
  const FilterStatistics& kb = result.filters[0];
  INFO("sqrt(P_inf) = " << root_P << ", RMS over [2, 10] " << kb.windows[0].rms[0] << ", RMS at 10 "
                        << kb.reports[0].rms[0] << ", mean |e| at 10 " << kb.reports[0].mean_abs[0]);
  CHECK(kb.windows[0].runs == 1000);
  // About 15 independent samples per run over [2, 10]: relative sd of the RMS ~0.6 %.
  CHECK(kb.windows[0].rms[0] == Approx(root_P).epsilon(0.03));
  // 1000 samples at t = 10: relative sd of the RMS ~2.2 %.
  CHECK(kb.reports[0].alive == 1000);
  CHECK(kb.reports[0].rms[0] == Approx(root_P).epsilon(0.09));
  CHECK(kb.reports[0].mean_abs[0] == Approx(std::sqrt(2 / 3.14159265358979323846) * root_P).epsilon(0.09));
  // The transient (P0 = 1 > P_inf, but x0 = m0) has smaller error than the stationary phase.
  CHECK(kb.windows[1].rms[0] < root_P);
  CHECK(kb.horizon.runs == 1000);
  CHECK(kb.divergences.count() == 0);
  CHECK(kb.psd_losses.count() == 0);
  CHECK(kb.peak_median[0] > 2 * root_P);
  CHECK(kb.peak_q95[0] > kb.peak_median[0]);
  // The series' median error hovers around 0 and its band spans about +-1.645 sqrt(P).
  const FilterSeries& kb_series = result.series.filters[0];
  const Eigen::Index last = kb_series.error.q95.rows() - 1;
  CHECK(kb_series.alive[static_cast<std::size_t>(last)] == 1000);
  CHECK(kb_series.error.q95(last, 0) - kb_series.error.q05(last, 0) == Approx(2 * 1.645 * root_P).epsilon(0.15));
  CHECK(std::abs(kb_series.error.q50(last, 0)) < 0.15 * root_P);

  // m' = 9 m + noise: |m| reaches 1e8 around t ~ 2 in every run.
  const FilterStatistics& wrong = result.filters[1];
  CHECK(wrong.divergences.count() == 1000);
  CHECK(wrong.horizon.runs == 0);
  CHECK(std::isnan(wrong.horizon.rms[0]));
  CHECK(wrong.divergences.earliest() > 0.5);
  CHECK(wrong.divergences.earliest() <= wrong.divergences.median());
  CHECK(wrong.divergences.median() < 4.0);
  CHECK(wrong.windows[1].runs == 1000);  // [0, 0.4]: before any divergence
  CHECK(std::isfinite(wrong.windows[1].rms[0]));
  CHECK(result.series.filters[1].alive.back() == 0);
  CHECK(std::isnan(result.series.filters[1].error.q50(last, 0)));

  // P = 0.5 - t: within tolerance at t = 0.5 (round-off), lost at 0.502; the run goes on.
  const FilterStatistics& shrink = result.filters[2];
  CHECK(shrink.psd_losses.count() == 1000);
  CHECK(shrink.psd_losses.earliest() == Approx(0.502).margin(1e-9));
  CHECK(shrink.divergences.count() == 0);
  CHECK(shrink.horizon.runs == 1000);
  CHECK(result.truth_divergences.count() == 0);

  const std::string table = format_summary_table(result, {"x"});
  INFO(table);
  CHECK_FALSE(mentions_nan_or_inf(table));
  CHECK(table.find("RMS[2,10]") != std::string::npos);
  CHECK(table.find("|e|@0.3") != std::string::npos);
  CHECK_FALSE(mentions_nan_or_inf(format_results_csv(result, {"x"})));
  const std::string timing = format_timing(result);
  CHECK(timing.find("ns/step") != std::string::npos);
  CHECK(result.timing.truth_steps == 1000 * options.grid.steps);
}

TEST_CASE("monte carlo: a truth that blows up is reported near t = 1 and nothing prints nan or inf", "[montecarlo][runtime][unit]") {
  // x' = x^2 from x0 = 1: x = 1 / (1 - t), beyond the 1e8 bound at t = 1 - 1e-8.
  SdeSystem system;
  system.n = 1;
  system.q = 0;
  system.drift = [](double, const double* x, double* f) { f[0] = x[0] * x[0]; };
  const RungeKutta4 scheme(system);
  const ScalarLinear model;
  MonteCarloOptions options;
  options.grid = TimeGrid::to_horizon(0.0, 2.0, 1e-3);
  options.runs = 7;
  options.threads = 2;
  options.record_points = 50;
  options.windows = {{0.0, 0.5}};
  options.report_times = {0.5, 1.5};
  const std::vector<FilterModel> filters{kalman_bucy(model, "kalman-bucy"), shrinking()};
  const MonteCarloResult result =
      run_monte_carlo(scheme, scalar_observation(model.r), Eigen::VectorXd::Ones(1), filters, options);

  REQUIRE(result.truth_divergences.count() == 7);
  CHECK(result.truth_divergences.earliest() == Approx(1.0).margin(2e-3));
  CHECK(result.truth_divergences.median() == Approx(1.0).margin(2e-3));
  CHECK(result.scheme == "rk4");
  for (const FilterStatistics& filter : result.filters) {
    CHECK(filter.horizon.runs == 0);
    CHECK(filter.windows[0].runs == 7);
    CHECK(std::isfinite(filter.windows[0].rms[0]));
    CHECK(filter.reports[1].alive == 0);
    CHECK(std::isnan(filter.reports[1].mean_abs[0]));
    CHECK(std::isnan(filter.peak_median[0]));
  }
  CHECK(result.series.truth_alive.back() == 0);

  const std::string table = format_summary_table(result, {"x"});
  const std::string csv = format_results_csv(result, {"x"});
  INFO(table);
  CHECK_FALSE(mentions_nan_or_inf(table));
  CHECK_FALSE(mentions_nan_or_inf(csv));
  CHECK(table.find("Truth diverged: 7 of 7 runs, first at t = 1") != std::string::npos);
  // The undefined cells: '-' in the table, empty in the CSV (the last row is all empty but t and
  // the alive counts, which are 0).
  CHECK(table.find(" - ") != std::string::npos);
  const std::string last_row = csv.substr(csv.rfind('\n', csv.size() - 2) + 1);
  CHECK(last_row.rfind("2,,", 0) == 0);
}

TEST_CASE("monte carlo: the table and CSV are byte-identical across calls and the CSV is well-formed", "[montecarlo][runtime][unit]") {
  Scenario scenario;
  EulerMaruyama scheme(scalar_linear_system(scenario.model));
  const Observation observation = scalar_observation(scenario.model.r);
  const Eigen::VectorXd x0 = Eigen::VectorXd::Constant(1, 0.3);
  scenario.options.threads = 2;
  const MonteCarloResult first = run_monte_carlo(scheme, observation, x0, scenario.filters, scenario.options);
  scenario.options.threads = 1;
  const MonteCarloResult second = run_monte_carlo(scheme, observation, x0, scenario.filters, scenario.options);

  const std::string dir = temporary_directory();
  const std::string path_a = dir + "/a.csv", path_b = dir + "/b.csv";
  write_results_csv(path_a, first, {"x"});
  write_results_csv(path_b, second, {"x"});
  const std::string csv = read_file(path_a);
  CHECK(csv == read_file(path_b));
  CHECK_FALSE(std::filesystem::exists(path_a + ".tmp"));
  CHECK(format_summary_table(first, {"x"}) == format_summary_table(second, {"x"}));

  // Constant column count, every cell empty or a number that reads back completely.
  std::istringstream lines(csv);
  std::string line;
  std::getline(lines, line);
  const std::vector<std::string> columns = results_csv_columns(first, {"x"});
  CHECK(std::count(line.begin(), line.end(), ',') + 1 == static_cast<long>(columns.size()));
  CHECK(line.rfind("t,truth_x,kalman-bucy_m_x,kalman-bucy_P_x,kalman-bucy_err_x,", 0) == 0);
  CHECK(line.find(",truth_x_mean,truth_x_q05,truth_x_q50,truth_x_q95,truth_alive,") != std::string::npos);
  // The per-time RMS error and NEES come after every other column, so that theirs keep their place.
  CHECK(line.find(",shrinking_alive,kalman-bucy_err_x_rms,kalman-bucy_nees,kalman-bucy_nees_low,kalman-bucy_nees_high,") !=
        std::string::npos);
  const std::string last_column = ",shrinking_err_x_rms,shrinking_nees,shrinking_nees_low,shrinking_nees_high";
  CHECK(line.size() > last_column.size());
  CHECK(line.compare(line.size() - last_column.size(), last_column.size(), last_column) == 0);
  std::size_t rows = 0, empty = 0;
  while (std::getline(lines, line)) {
    ++rows;
    std::stringstream cells(line + ",");
    std::string cell;
    std::size_t count = 0;
    while (std::getline(cells, cell, ',')) {
      ++count;
      if (cell.empty()) {
        ++empty;
        continue;
      }
      char* end = nullptr;
      const double value = std::strtod(cell.c_str(), &end);
      CHECK(*end == '\0');
      CHECK(std::isfinite(value));
    }
    CHECK(count == columns.size());
  }
  CHECK(rows == first.series.t.size());
  CHECK(empty > 0);  // the stopped truths and the diverged filter leave empty cells

  // A failed write names the path and leaves nothing behind.
  const std::string bad = dir + "/no-such-dir/out.csv";
  try {
    write_results_csv(bad, first, {"x"});
    FAIL("writing into a missing directory succeeded");
  } catch (const std::runtime_error& error) {
    CHECK(std::string(error.what()).find(bad) != std::string::npos);
  }
  CHECK_THROWS_AS(format_summary_table(first, {"x", "y"}), std::invalid_argument);
  std::filesystem::remove_all(dir);
}

namespace {

// A result with the given filters and n = 2 (x1, x2), only as far as gnuplot_error_script reads
// it: the CSV's column names and the titles.
MonteCarloResult plotted_result(const std::vector<std::string>& filter_names, bool with_reference) {
  MonteCarloResult result;
  result.grid = TimeGrid::to_horizon(0.0, 2.0, 0.01);
  result.runs = 10;
  result.n = 2;
  for (const std::string& name : filter_names) {
    FilterStatistics filter;
    filter.name = name;
    result.filters.push_back(filter);
  }
  result.series.filters.resize(filter_names.size());
  if (with_reference) {
    result.reference.emplace();
    result.reference->particles = 200;
  }
  return result;
}

// One curve of a plot command: its style and its key title.
struct PlottedLine {
  std::string width, dash, color, title;
};

// The `with lines ... title '...'` curves of every plot command of the script, command by command.
std::vector<std::vector<PlottedLine>> plotted_lines(const std::string& script) {
  std::vector<std::vector<PlottedLine>> commands;
  const std::regex curve("with lines lw ([0-9.]+) dt ([0-9(),]+) lc rgb '(#[0-9A-Fa-f]{6})' title '([^']*)'");
  std::istringstream in(std::regex_replace(script, std::regex(", \\\\\n     "), ", "));
  for (std::string line; std::getline(in, line);) {
    if (line.rfind("plot ", 0) != 0) continue;
    commands.emplace_back();
    for (std::sregex_iterator it(line.begin(), line.end(), curve), end; it != end; ++it) {
      const std::string title = (*it)[4];
      if (title.size() > 7 && title.compare(title.size() - 7, 7, " 5-95 %") == 0) continue;  // a band's edge
      commands.back().push_back({(*it)[1], (*it)[2], (*it)[3], title});
    }
  }
  return commands;
}

}  // namespace

TEST_CASE("monte carlo: the plot gives every filter its own dash type and width, the reference black dashed on top, the key below", "[montecarlo][runtime][gnuplot][unit]") {
  const std::vector<std::string> four{"optimal", "additive", "ekf-additive", "ekf"};
  const std::string script =
      gnuplot_error_script("errors.png", "results.csv", plotted_result(four, true), {"x1", "x2"}, "van der Pol");
  INFO(script);
  CHECK(script == gnuplot_error_script("errors.png", "results.csv", plotted_result(four, true), {"x1", "x2"},
                                       "van der Pol"));  // a pure function of its inputs
  // The key does not take a column of its own beside the panels: below each, in rows.
  CHECK(script.find("set key outside below center horizontal") != std::string::npos);
  CHECK(script.find("right top") == std::string::npos);
  CHECK(script.find("set rmargin 4\n") != std::string::npos);

  const auto commands = plotted_lines(script);
  REQUIRE(commands.size() == 4);  // per state: the shown run, the median and band
  for (std::size_t c = 0; c < commands.size(); ++c) {
    const bool run_panel = c % 2 == 0;
    const auto& lines = commands[c];
    // Every filter in the command's order, then (run panels) the reference.
    REQUIRE(lines.size() == four.size() + (run_panel ? 1 : 0));
    std::set<std::string> dashes, widths;
    for (std::size_t f = 0; f < four.size(); ++f) {
      CHECK(lines[f].title == four[f]);
      CHECK(lines[f].dash != "2");  // dashed is the reference's
      dashes.insert(lines[f].dash);
      widths.insert(lines[f].width);
      // The same style in every panel.
      CHECK(lines[f].width == commands[0][f].width);
      CHECK(lines[f].dash == commands[0][f].dash);
      CHECK(lines[f].color == commands[0][f].color);
      // Drawn widest first: each later curve is narrower, so the ones beneath stay visible.
      if (f > 0) CHECK(std::stod(lines[f].width) < std::stod(lines[f - 1].width));
    }
    CHECK(dashes.size() == four.size());
    CHECK(widths.size() == four.size());
    CHECK(lines[0].dash == "1");  // the first filter solid, underneath
    CHECK(std::stod(lines[0].width) >= 2 * std::stod(lines[3].width));
    if (run_panel) {
      const PlottedLine& reference = lines.back();
      CHECK(reference.title == "reference (N=200)");
      CHECK(reference.dash == "2");
      CHECK(reference.color == "#000000");
    }
  }
  // The bands before every median, so no band veils a median drawn before it: the first filter's
  // filled, each other filter's as its two thin edges in its own colour and dash type, each band
  // in the key, so that bands that coincide do not merge into one grey area of unknown owner.
  const std::size_t band_start = script.find("5-95 % band");
  const std::string band_command = script.substr(band_start, script.find("set ylabel", band_start) - band_start);
  REQUIRE(band_command.find("filledcurves") != std::string::npos);
  CHECK(band_command.find("filledcurves") == band_command.rfind("filledcurves"));  // one filled band
  CHECK(band_command.find("title 'optimal 5-95 %'") != std::string::npos);
  const std::size_t first_median = band_command.find("title 'optimal'");
  REQUIRE(first_median != std::string::npos);
  CHECK(band_command.rfind("filledcurves") < first_median);
  for (std::size_t f = 1; f < four.size(); ++f) {
    const std::string edge = "with lines lw 1 dt " + commands[0][f].dash + " lc rgb '" + commands[0][f].color + "'";
    const std::size_t titled = band_command.find(edge + " title '" + four[f] + " 5-95 %'");
    REQUIRE(titled != std::string::npos);
    CHECK(band_command.find(edge + " notitle", titled) != std::string::npos);  // the other edge
    CHECK(titled < first_median);
  }

  // Without the reference no black dashed curve; nine filters: the first eight have distinct dash
  // types, and all nine distinct widths, widest first.
  std::vector<std::string> nine;
  for (int f = 0; f < 9; ++f) nine.push_back("f" + std::to_string(f));
  const std::string many = gnuplot_error_script("e.svg", "r.csv", plotted_result(nine, false), {"x1", "x2"}, "t");
  CHECK(many.find("dt 2 ") == std::string::npos);
  const auto first = plotted_lines(many).at(0);
  REQUIRE(first.size() == 9);
  std::set<std::string> dashes, widths;
  for (std::size_t f = 0; f < 9; ++f) {
    if (f < 8) dashes.insert(first[f].dash);
    widths.insert(first[f].width);
  }
  CHECK(dashes.size() == 8);
  CHECK(widths.size() == 9);
  CHECK(first.front().width == "6");
  CHECK(first.back().width == "2");
}

TEST_CASE("monte carlo: gnuplot draws the error plot as SVG and PNG", "[montecarlo][runtime][gnuplot][compiler]") {
  if (!pfgen_runtime::gnuplot_on_path()) {
    WARN("gnuplot is not on PATH: plot test skipped (scripts/install-deps.sh installs it)");
    return;
  }
  Scenario scenario;
  EulerMaruyama scheme(scalar_linear_system(scenario.model));
  scenario.options.threads = 2;
  const MonteCarloResult result = run_monte_carlo(scheme, scalar_observation(scenario.model.r),
                                                  Eigen::VectorXd::Constant(1, 0.3), scenario.filters, scenario.options);
  const std::string dir = temporary_directory();
  const std::string csv = dir + "/results.csv", svg = dir + "/errors.svg", png = dir + "/errors.PNG";
  write_results_csv(csv, result, {"x"});
  write_error_plot(svg, csv, result, {"x"}, "scalar OU, it's a test");
  const std::string drawing = read_file(svg);
  CHECK(drawing.rfind("<?xml", 0) == 0);
  CHECK(drawing.find("<path") != std::string::npos);
  // The first filter's curve in its fixed colour (#0072B2), and its name in the key.
  CHECK(drawing.find("rgb(  0, 114, 178)") != std::string::npos);
  CHECK(drawing.find("<text>kalman-bucy</text>") != std::string::npos);
  CHECK(std::filesystem::exists(svg + ".gp"));
  write_error_plot(svg, csv, result, {"x"}, "scalar OU, it's a test");
  CHECK(read_file(svg) == drawing);  // deterministic

  write_error_plot(png, csv, result, {"x"}, "scalar OU");
  CHECK(read_file(png).rfind("\x89PNG", 0) == 0);

  CHECK_THROWS_AS(write_error_plot(dir + "/errors.pdf", csv, result, {"x"}, "t"), std::invalid_argument);
  // gnuplot failing (no CSV to read) is reported, and leaves no plot.
  CHECK_THROWS_AS(write_error_plot(dir + "/missing.svg", dir + "/missing.csv", result, {"x"}, "t"),
                  std::runtime_error);
  CHECK_FALSE(std::filesystem::exists(dir + "/missing.svg"));
  std::filesystem::remove_all(dir);
}

TEST_CASE("monte carlo: inconsistent inputs are rejected and a worker's exception reaches the caller", "[montecarlo][runtime][unit]") {
  Scenario scenario;
  EulerMaruyama scheme(scalar_linear_system(scenario.model));
  const Observation observation = scalar_observation(scenario.model.r);
  const Eigen::VectorXd x0 = Eigen::VectorXd::Zero(1);
  auto rejects = [&](auto change) {
    Scenario copy = scenario;
    change(copy);
    CHECK_THROWS_AS(run_monte_carlo(scheme, observation, x0, copy.filters, copy.options), std::invalid_argument);
  };
  rejects([](Scenario& s) { s.options.threads = 0; });
  rejects([](Scenario& s) { s.options.runs = 0; });
  rejects([](Scenario& s) { s.options.shown_run = s.options.runs; });
  rejects([](Scenario& s) { s.options.record_points = 0; });
  rejects([](Scenario& s) { s.options.report_times = {3.5}; });
  rejects([](Scenario& s) { s.options.windows = {{1.0, 1.0}}; });
  rejects([](Scenario& s) { s.options.windows = {{-1.0, 1.0}}; });
  rejects([](Scenario& s) { s.filters[1].name = s.filters[0].name; });
  rejects([](Scenario& s) { s.filters[0].n = 2; });

  Scenario failing = scenario;
  failing.options.threads = 3;
  failing.filters[0].timing = std::make_unique<GridSteps>([](double* state, double t, double, const double*) {
    if (t > 1.0) throw std::runtime_error("filter failed on purpose");
    state[0] += 0.0;
  });
  CHECK_THROWS_WITH(run_monte_carlo(scheme, observation, x0, failing.filters, failing.options),
                    "filter failed on purpose");
}

TEST_CASE("runtime: RK4 integrates paper 001's deterministic state to order 4", "[montecarlo][runtime][schemes][unit]") {
  SdeSystem system;
  system.n = 2;
  system.q = 0;
  system.drift = [](double, const double* x, double* f) {
    f[0] = 0.1 * (x[0] * x[0] + x[1]);
    f[1] = 0.1 * x[1];
  };
  auto scheme = make_scheme(scheme_kind_from_string("rk4"), system);
  CHECK(scheme->name() == "rk4");
  const double T = 4.0;
  auto solve = [&](double dt) {
    Eigen::VectorXd x(2), dW(0);
    x << 1.1, 1.1;
    const auto steps = static_cast<int>(std::lround(T / dt));
    for (int k = 0; k < steps; ++k) scheme->step(k * dt, x, dt, dW);
    return x;
  };
  const Eigen::VectorXd reference = solve(1e-3);  // error ~ 1e-15
  // x2 = 1.1 e^(0.1 t) exactly.
  CHECK(reference[1] == Approx(1.1 * std::exp(0.1 * T)).epsilon(1e-13));
  std::vector<double> errors;
  for (double dt : {0.4, 0.2, 0.1, 0.05}) errors.push_back((solve(dt) - reference).cwiseAbs().maxCoeff());
  for (std::size_t i = 0; i + 1 < errors.size(); ++i) {
    const double order = std::log2(errors[i] / errors[i + 1]);
    INFO("dt = " << 0.4 / std::pow(2.0, static_cast<double>(i)) << ": error " << errors[i] << ", observed order "
                 << order);
    CHECK(order > 3.7);
    CHECK(order < 4.3);
  }
  // A noisy system is refused rather than its noise silently dropped.
  system.q = 1;
  system.diffusion = [](double, const double*, double* g) { g[0] = g[1] = 0.0; };
  CHECK_THROWS_AS(RungeKutta4(system), std::invalid_argument);
}

TEST_CASE("runtime: the cheap PSD check gives the eigenvalue check's verdict", "[montecarlo][runtime][guards][unit]") {
  std::mt19937_64 random(12345);
  std::normal_distribution<double> normal;
  std::uniform_real_distribution<double> uniform(0.0, 1.0);
  const double nan = std::numeric_limits<double>::quiet_NaN(), inf = std::numeric_limits<double>::infinity();
  const std::vector<CovarianceGuard> guards{CovarianceGuard(), CovarianceGuard(0.0, 0.0), CovarianceGuard(1e-2, 0.0),
                                            CovarianceGuard(0.0, 1e-6)};
  std::size_t passed = 0, failed = 0;

  // P = Q diag(lambda) Q^T with random Q and eigenvalues of every kind.
  auto check_all = [&](const Eigen::MatrixXd& P, const std::string& what) {
    const auto n = static_cast<std::size_t>(P.rows());
    Eigen::VectorXd state(static_cast<Eigen::Index>(filter_state_size(n)));
    state.head(P.rows()).setConstant(0.25);
    state.tail(static_cast<Eigen::Index>(packed_size(n))) = pack_upper(P);
    for (std::size_t g = 0; g < guards.size(); ++g) {
      const CovarianceCheck exact = guards[g].check_filter_state(state.data(), n);
      INFO(what << ", n = " << n << ", guard " << g << ": " << exact.describe() << "\nP =\n" << P);
      CHECK(guards[g].passes_filter_state(state.data(), n) == exact.ok);
      (exact.ok ? passed : failed) += 1;
      // For n > 2 the stack-sized eigenvalues agree with check_matrix's.
      if (n > 2 && P.allFinite()) {
        const CovarianceCheck reference = guards[g].check_matrix(unpack_symmetric(pack_upper(P).data(), n));
        const double scale = std::max(1e-300, reference.max_abs_eigenvalue);
        CHECK(std::abs(exact.min_eigenvalue - reference.min_eigenvalue) <= 1e-12 * scale);
        if (std::abs(reference.min_eigenvalue + reference.threshold) > 1e-9 * scale) CHECK(exact.ok == reference.ok);
      }
    }
  };
  for (std::size_t n = 1; n <= 7; ++n) {
    const auto N = static_cast<Eigen::Index>(n);
    for (int trial = 0; trial < 60; ++trial) {
      Eigen::MatrixXd M(N, N);
      for (Eigen::Index i = 0; i < M.size(); ++i) M.data()[i] = normal(random);
      // Gram-Schmidt on a Gaussian matrix: a random orthogonal Q.
      Eigen::MatrixXd Q = M;
      for (Eigen::Index j = 0; j < N; ++j) {
        for (Eigen::Index k = 0; k < j; ++k) Q.col(j) -= Q.col(k).dot(Q.col(j)) * Q.col(k);
        Q.col(j).normalize();
      }
      Eigen::VectorXd lambda(N);
      const double scale = std::pow(10.0, 6.0 * (uniform(random) - 0.5));
      for (Eigen::Index i = 0; i < N; ++i) lambda[i] = scale * uniform(random);
      switch (trial % 6) {
        case 0: break;                                                 // positive definite
        case 1: lambda[0] = 0; break;                                  // singular
        case 2: lambda[0] = -1e-3 * scale * uniform(random); break;    // around the 1e-4 tolerance
        case 3: lambda[0] = -scale * uniform(random); break;           // clearly indefinite
        case 4: lambda.setZero(); lambda[N - 1] = scale; break;        // rank 1
        case 5: lambda[0] = -1e-8 * scale; break;                      // integrator noise on a zero
      }
      check_all(Q * lambda.asDiagonal() * Q.transpose(), "random case " + std::to_string(trial % 6));
    }
    // Edge matrices: zero, all ones (paper 001's P0), tiny and huge scales, non-finite entries,
    // eigenvalue exactly at the default threshold.
    check_all(Eigen::MatrixXd::Zero(N, N), "zero");
    check_all(Eigen::MatrixXd::Ones(N, N), "all ones");
    check_all(1e-200 * Eigen::MatrixXd::Identity(N, N), "tiny");
    check_all(1e200 * Eigen::MatrixXd::Ones(N, N), "huge");
    check_all(-1e-13 * Eigen::MatrixXd::Identity(N, N), "tiny negative");
    Eigen::MatrixXd boundary = Eigen::MatrixXd::Identity(N, N);
    boundary(0, 0) = -(1e-12 + 1e-4);
    check_all(boundary, "at the threshold");
    for (double bad : {nan, inf, -inf}) {
      Eigen::MatrixXd P = Eigen::MatrixXd::Identity(N, N);
      P(N - 1, 0) = P(0, N - 1) = bad;
      check_all(P, "non-finite entry");
    }
  }
  CHECK(passed > 500);
  CHECK(failed > 500);
}

// Not run by default: `pfgen_tests "[montecarlo-benchmark]"`. The speed target's shape: a scalar
// model, 3 trivial filters, 90,000 steps per run, 2 threads.
TEST_CASE("monte carlo benchmark: 100 runs x 90,000 steps, scalar model, 3 filters, 2 threads", "[.][montecarlo-benchmark][statistical]") {
  const ScalarLinear model;
  EulerMaruyama scheme(scalar_linear_system(model));
  MonteCarloOptions options;
  options.grid = TimeGrid::to_horizon(0.0, 9.0, 1e-4);
  options.runs = 100;
  options.threads = 2;
  options.windows = {{1.0, 9.0}};
  options.report_times = {1.0, 5.0, 9.0};
  const std::vector<FilterModel> filters{kalman_bucy(model, "kalman-bucy"), kalman_bucy(model, "fixed-gain", 1.0, 2.0),
                                         kalman_bucy(model, "copy")};
  const MonteCarloResult result =
      run_monte_carlo(scheme, scalar_observation(model.r), Eigen::VectorXd::Zero(1), filters, options);
  WARN(format_timing(result));
  WARN(format_summary_table(result, {"x"}));
}
