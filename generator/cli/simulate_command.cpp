#include "simulate_command.hpp"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <iomanip>
#include <iostream>
#include <optional>
#include <sstream>
#include <thread>

#include <unistd.h>

#include "cli_options.hpp"
#include "commands.hpp"
#include "job_group.hpp"
#include "memory_budget.hpp"
#include "observation_command.hpp"
#include "output_paths.hpp"
#include "plugin_loading.hpp"
#include "progress_bar.hpp"
#include "redirected_stderr.hpp"
#include "pfgen/codegen/backends/cpp/simulation_plugin.hpp"
#include "pfgen/derivation/filter_equations.hpp"
#include "pfgen/model/simulation_rules.hpp"
#include "pfgen/model/yaml_model_loader.hpp"
#include "pfgen/toolchain/plugin_compiler.hpp"
#include "pfgen_runtime/gnuplot_plot.hpp"
#include "pfgen_runtime/monte_carlo.hpp"
#include "pfgen_runtime/particle_reference.hpp"
#include "pfgen_runtime/results_csv.hpp"
#include "pfgen_runtime/simulation_plugin.hpp"
#include "pfgen_runtime/summary_table.hpp"
#include "pfgen_support/shortest_double.hpp"

namespace pfgen::cli {
namespace {

static_assert(kMaxReferenceParticles == pfgen_runtime::kMaxParticles,
              "--reference's limit and the runtime's must agree");

using Clock = std::chrono::steady_clock;

double seconds_since(Clock::time_point start) {
  return std::chrono::duration<double>(Clock::now() - start).count();
}

unsigned core_count() {
  const unsigned cores = std::thread::hardware_concurrency();
  return cores > 0 ? cores : 1;
}

// At most this many threads per core: results do not depend on the count, and beyond a few per
// core more threads only cost memory (--threads 10000 ended in "Resource temporarily unavailable").
constexpr unsigned kThreadsPerCore = 16;

// Only min(threads, runs) threads start (run_monte_carlo), so --threads 1000000 --runs 3 is fine.
unsigned thread_count(unsigned requested, std::size_t runs) {
  if (requested == 0) return core_count();
  if (std::min<std::size_t>(requested, runs) > kThreadsPerCore * core_count())
    throw CliValueError("--threads: " + std::to_string(requested) + " threads on a machine with " +
                        std::to_string(core_count()) + " cores; at most " + std::to_string(kThreadsPerCore) +
                        " per core (" + std::to_string(kThreadsPerCore * core_count()) +
                        "), or 0 for one per core; results do not depend on the count");
  return requested;
}

// The time series (record points) only feed the CSV and the plot: without either, each run records
// its two ends only, so --record-points 10000000 costs nothing it does not write.
std::size_t effective_record_points(const SimulateOptions& options, const SimulationSettings& s) {
  return options.csv_path.empty() && options.plot_path.empty() && !options.keep_series ? 1 : s.record_points;
}

// The CSV the plot reads: -o's file, or one beside the plot.
std::string csv_for_plot(const SimulateOptions& options) {
  if (!options.csv_path.empty()) return options.csv_path;
  return std::filesystem::path(options.plot_path).replace_extension(".csv").string();
}

void check_output_paths(const SimulateOptions& options) {
  if (!(options.plot_ylim >= 0) || !std::isfinite(options.plot_ylim))
    throw CliValueError("--plot-ylim: must be a finite number >= 0");
  if (!options.plot_path.empty()) {
    std::string ext = std::filesystem::path(options.plot_path).extension().string();
    for (char& c : ext) c = static_cast<char>(std::tolower(static_cast<unsigned char>(c)));
    if (ext != ".png" && ext != ".svg")
      throw CliValueError("--plot: '" + options.plot_path + "' must end in .png or .svg");
    require_plotter();
  }
  // Every file the run writes, the CSV beside a plot and the plot's gnuplot script included.
  std::vector<NamedPath> written;
  if (!options.csv_path.empty()) written.push_back({"-o", options.csv_path});
  if (!options.plot_path.empty()) {
    if (options.csv_path.empty()) written.push_back({"--plot's CSV", csv_for_plot(options)});
    written.push_back({"--plot", options.plot_path});
    written.push_back({"--plot's gnuplot script", pfgen_runtime::gnuplot_script_path(options.plot_path)});
  }
  if (!options.timing_path.empty()) written.push_back({"--timing", options.timing_path});
  if (!options.criterion_csv_path.empty()) written.push_back({"--criterion-csv", options.criterion_csv_path});
  if (!options.stops_csv_path.empty()) written.push_back({"--stops-csv", options.stops_csv_path});
  check_distinct_outputs({{"the model file", options.model_path}}, written);
  // --timing too: it is written last, and a failure there used to follow a printed table.
  const std::pair<const std::string*, const char*> outputs[] = {{&options.csv_path, "-o"},
                                                                {&options.plot_path, "--plot"},
                                                                {&options.timing_path, "--timing"},
                                                                {&options.criterion_csv_path, "--criterion-csv"},
                                                                {&options.stops_csv_path, "--stops-csv"}};
  for (const auto& [path, option] : outputs)
    if (!path->empty()) check_output_file({option, *path});
  // gnuplot reads the CSV back from its file: -o /dev/stdout with --plot would draw nothing.
  std::error_code error;
  if (!options.plot_path.empty() && !options.csv_path.empty() && std::filesystem::exists(options.csv_path, error) &&
      !std::filesystem::is_regular_file(options.csv_path, error))
    throw CliValueError("-o: '" + options.csv_path +
                        "' is not a regular file, and --plot reads the CSV back from it; give -o a file, or drop it");
}

// Each thread keeps one run's truth path and observation increments; the statistics keep the
// recorded points of every run. Refuse a job that would not fit instead of dying in bad_alloc.
void check_memory(const Model& model, const SimulationSettings& s, unsigned threads, std::size_t filters,
                  std::size_t record_points) {
  const double steps = std::floor(s.T / s.dt + 0.5);
  // A delayed filter also keeps D = h / dt grid values of m and x* (at most 2n each) per thread.
  const double history = std::round(model.observation.delay().to_double() / s.dt) * 2.0 *
                         static_cast<double>(model.n() * filters);
  // The particle reference: the mean paths of its two particle sets, and N particles with their
  // rates, twice (resampling).
  const double particles = s.reference_particles
                               ? static_cast<double>(kReferenceParticleSets) * (steps + 1) * static_cast<double>(model.n()) +
                                     2.0 * static_cast<double>(*s.reference_particles) *
                                         static_cast<double>(model.n() + model.p() + 2)
                               : 0.0;
  const double per_thread =
      ((steps + 1) * static_cast<double>(model.n() + model.p()) + history + particles) * sizeof(double);
  const double records = std::min(steps + 1, static_cast<double>(record_points) + 1);
  // Per run and record point: the truth and each filter's error and NEES; with the particle
  // reference also its error and each filter's distance from it.
  const double recorded = static_cast<double>((filters + 1) * (s.reference_particles ? 2 : 1)) +
                          static_cast<double>(filters) / static_cast<double>(model.n());
  const double statistics = static_cast<double>(s.runs) * records * recorded * static_cast<double>(model.n()) *
                            sizeof(double);
  // Only min(threads, runs) threads are started (run_monte_carlo): --threads 1000000 --runs 2 is fine.
  // A thread's batch of runs (MonteCarloOptions::batch) adds at most kBatchBytes.
  const double paths = (per_thread + static_cast<double>(pfgen_runtime::kBatchBytes)) *
                       static_cast<double>(std::min<std::size_t>(threads, s.runs));
  const MemoryBudget budget = memory_budget(read_memory_facts());
  const double bytes = paths + statistics, limit = budget.bytes;
  if (bytes > limit) {
    // Named by the larger part: the recorded series (--record-points, with the CSV or plot), or the
    // paths the threads keep.
    const bool series = statistics > paths;
    char text[600];
    std::snprintf(text, sizeof text,
                  series ? "--record-points: the job needs about %.1f GiB (%.0f runs x %.0f recorded points); the "
                           "limit on this machine is %.1f GiB (%s): lower --record-points or --runs"
                         : "--dt: the job needs about %.1f GiB (%.3g steps per run on %.0f threads); the limit on "
                           "this machine is %.1f GiB (%s): raise --dt, lower --T, or lower --threads",
                  bytes / (1024.0 * 1024 * 1024), series ? static_cast<double>(s.runs) : steps,
                  series ? records : static_cast<double>(threads), limit / (1024.0 * 1024 * 1024),
                  budget.reason.c_str());
    throw CliValueError(text);
  }
}

std::string timing_json(const pfgen_runtime::MonteCarloResult& result, const toolchain::PluginBuild& build,
                        double derive_seconds, double total_seconds) {
  double filter_seconds = 0;
  for (double s : result.timing.filter_seconds) filter_seconds += s;
  std::ostringstream out;
  out.precision(6);
  out << "{\"threads\": " << result.timing.threads << ", \"runs\": " << result.runs
      << ", \"steps\": " << result.grid.steps << ", \"derive_seconds\": " << derive_seconds
      << ", \"cache_hit\": " << (build.cache_hit ? "true" : "false")
      << ", \"compile_seconds\": " << build.compile_seconds << ", \"wall_seconds\": " << result.timing.wall_seconds
      << ", \"truth_seconds\": " << result.timing.truth_seconds << ", \"filter_seconds\": " << filter_seconds;
  if (result.reference) out << ", \"reference_seconds\": " << result.timing.reference_seconds;
  out << ", \"aggregation_seconds\": " << result.timing.aggregation_seconds
      << ", \"series_seconds\": " << result.timing.series_seconds;
  if (result.timing.gathered_bytes != 0)
    out << ", \"exchange_seconds\": " << result.timing.exchange_seconds << ", \"exchanged_bytes\": "
        << result.timing.exchanged_bytes << ", \"gather_seconds\": " << result.timing.gather_seconds
        << ", \"gathered_bytes\": " << result.timing.gathered_bytes;
  out << ", \"total_seconds\": " << total_seconds << "}\n";
  return out.str();
}

// The runtime's form of J's settings: M as an Eigen matrix, left empty (L = |x - m|^2, printed
// "M = identity") when it is the identity.
pfgen_runtime::CriterionOptions criterion_options(const CriterionSettings& criterion, std::size_t n) {
  pfgen_runtime::CriterionOptions out;
  out.epsilon = criterion.epsilon;
  if (criterion.weight.empty()) return out;
  const auto size = static_cast<Eigen::Index>(n);
  Eigen::MatrixXd weight(size, size);
  for (Eigen::Index i = 0; i < size; ++i)
    for (Eigen::Index j = 0; j < size; ++j) weight(i, j) = criterion.weight[static_cast<std::size_t>(i * size + j)];
  if (!weight.isIdentity(0.0)) out.weight = weight;
  return out;
}

// What every process of a job reads and derives alike: the model, the settings, the filters'
// equations and the plugin's source (whose hash keys the compiled plugin in the cache).
struct PreparedJob {
  Model model;
  SimulationSettings settings;
  std::vector<FilterEquations> filters;
  std::string source;
  double derive_seconds = 0;
};

// `speaks`: the process that writes the outputs checks their paths (other machines of an MPI
// job need not have its directories) and says the settings' notes, once for the job.
PreparedJob prepare(const SimulateOptions& options, bool speaks, Clock::time_point start) {
  // Nothing on stderr from a process that does not speak (its errors are exceptions, reported by main).
  std::optional<RedirectedStderr> quiet;
  if (!speaks) quiet.emplace(nullptr);
  if (speaks) check_output_paths(options);
  Model model = options.model ? *options.model : load_model_file(options.model_path);
  // --set a=0.2: the job's value of a, compiled into the plugin as its default (so a new value
  // is a new source, and a new cache entry).
  apply_parameter_assignments(model, options.assignments);
  const SimulationSettings settings = resolve_simulation_settings(model, options.overrides);
  if (!options.criterion_csv_path.empty() && !settings.criterion)
    throw CliValueError("--criterion-csv: no criterion J to write; give --risk-epsilon or a risk: section in " +
                        model.source);
  if (!settings.x0_from_prior && (!model.initial || model.initial->x0.empty()))
    throw CliValueError(model.source + ": initial: the model gives no x0, the truth's initial state (or x0: prior, "
                        "or --x0 prior, to draw it from N(m0, P0) in each run)");
  // An x0 or m0 beyond the divergence bound stops every run at t = 0: the table was all '-'
  // with "Truth diverged: 3 of 3 runs, first at t = 0" and no hint why. Say so instead.
  const std::pair<const char*, const std::vector<GiNaC::numeric>*> starts[] = {{"x0", &model.initial->x0},
                                                                               {"m0", &model.initial->m0}};
  for (const auto& [field, values] : starts)
    for (std::size_t i = 0; i < values->size(); ++i)
      if (!(std::abs((*values)[i].to_double()) <= settings.bound)) {
        char text[160];
        std::snprintf(text, sizeof text, "initial.%s, entry %zu: %g is beyond the divergence bound %g", field, i + 1,
                      (*values)[i].to_double(), settings.bound);
        throw CliValueError(model.source + ": " + text + "; every run would stop at t = 0 (raise --bound)");
      }

  // Derive and generate: deterministic text, whose hash keys the compiled plugin in the cache.
  std::vector<FilterEquations> filters;
  for (const std::string& name : settings.filters.empty() ? default_filter_names(model) : settings.filters)
    filters.push_back(derive_named_filter(model, name));
  for (const FilterEquations& eq : filters)  // sub-steps a filter chose (the model gives none)
    if (eq.update.substeps_chosen)
      if (auto problem = substep_budget_problem(eq.name, settings.T, eq.update.period.to_double(),
                                                static_cast<double>(eq.update.substeps)))
        throw CliValueError(model.source + ": observation.sampled: " + *problem);
  check_memory(model, settings, thread_count(options.threads, settings.runs), filters.size(),
               effective_record_points(options, settings));
  // Delayed observations: filters generated for this grid step (settings checked D = h / dt).
  const std::string source = codegen::generate_simulation_plugin(model, filters, settings.dt);
  const double derive_seconds = seconds_since(start);
  return PreparedJob{std::move(model), settings, std::move(filters), source, derive_seconds};
}


// What makes one job's results: the plugin's source (model, parameters, filters) and every
// setting the runs read, numbers in hexadecimal so that no digit is lost. --threads, the output
// paths and the cache are not in it: they do not change the results.
std::string job_text(const PreparedJob& job) {
  const SimulationSettings& s = job.settings;
  std::string text = job.source;
  auto number = [&text](double value) {
    char digits[40];
    std::snprintf(digits, sizeof digits, " %a", value);
    text += digits;
  };
  text += "\nscheme " + s.scheme + " runs " + std::to_string(s.runs) + " seed " + std::to_string(s.seed) +
          " record_points " + std::to_string(s.record_points) + " shown_run " + std::to_string(s.shown_run) +
          (s.x0_from_prior ? " x0 prior" : "") + (s.refined_stepping ? "" : " stepping generated") + "\n";
  for (double value : {s.T, s.dt, s.bound}) number(value);
  text += "\nreports";
  for (double t : s.report_times) number(t);
  text += "\nwindows";
  for (const auto& [a, b] : s.windows) number(a), number(b);
  if (s.reference_particles) text += "\nreference particles " + std::to_string(*s.reference_particles);
  if (s.criterion) {
    text += "\ncriterion";
    number(s.criterion->epsilon);
    for (double m : s.criterion->weight) number(m);
  }
  return text;
}

// Why the particle reference cannot run on this model (empty: it can). docs/theory.md §7.4.
std::string reference_obstacle(const Model& model, const pfgen_runtime::SimulationPlugin& plugin) {
  const std::string observation = observation_command(model.observation.kind()).reference_obstacle(model);
  if (!observation.empty()) return observation;
  if (plugin.diffusion_is_zero())
    return "the truth has no process noise (g = 0): the particles would never spread, so their weights would "
           "collapse onto one";
  if (!model.initial || model.initial->m0.size() != model.n() || model.initial->P0.size() != model.n())
    return "the model gives no prior m0, P0 to draw the particles from";
  return {};
}

// The reference's settings: N, and the filters' prior N(m0, P0) from the model.
// The filters' prior N(m0, P0) as numbers: where the particle reference starts, and what --x0
// prior draws each run's truth from.
pfgen_runtime::InitialPrior filters_prior(const Model& model) {
  pfgen_runtime::InitialPrior out;
  const auto n = static_cast<Eigen::Index>(model.n());
  out.mean.resize(n);
  out.covariance.resize(n, n);
  for (Eigen::Index i = 0; i < n; ++i) {
    out.mean[i] = model.initial->m0[static_cast<std::size_t>(i)].to_double();
    for (Eigen::Index j = 0; j < n; ++j)
      out.covariance(i, j) = model.initial->P0[static_cast<std::size_t>(i)][static_cast<std::size_t>(j)].to_double();
  }
  return out;
}

pfgen_runtime::ParticleReferenceOptions reference_options(const Model& model, std::size_t particles) {
  pfgen_runtime::ParticleReferenceOptions out;
  out.particles = particles;
  const pfgen_runtime::InitialPrior prior = filters_prior(model);
  out.m0 = prior.mean;
  out.P0 = prior.covariance;
  return out;
}

// The particle reference is E[x | Y] only for truths drawn from the prior it starts from: with a
// fixed x0 away from m0 it can lose to ekf, and RMS(x - m)^2 = RMS(x - m_ref)^2 + RMS(m - m_ref)^2
// no longer holds. Said once, on stderr.
void warn_fixed_x0_against_reference(const Model& model, const SimulationSettings& settings) {
  if (!settings.reference_particles || settings.x0_from_prior) return;
  const InitialConditions& initial = *model.initial;
  if (initial.x0 == initial.m0) return;
  std::string x0, m0;
  for (std::size_t i = 0; i < initial.x0.size(); ++i) {
    x0 += (i ? ", " : "") + pfgen_support::shortest_chars(initial.x0[i].to_double());
    m0 += (i ? ", " : "") + pfgen_support::shortest_chars(initial.m0[i].to_double());
  }
  std::cerr << "pfgen: note: --reference: every run's truth starts at x0 = (" << x0
            << "), not from the filters' prior N(m0, P0) with m0 = (" << m0
            << "): the reference is the conditional mean only for truths drawn from that prior; --x0 prior draws "
               "them so\n";
}

}  // namespace

int run_simulate(const SimulateOptions& options) {
  LocalJob alone;
  return run_simulate(options, alone);
}

SimulationOutcome simulate(const SimulateOptions& options, JobGroup& group) {
  const Clock::time_point start = Clock::now();
  const bool speaks = group.speaks();
  const bool talk = speaks && !options.quiet;  // stderr's messages: one process's only
  std::optional<PreparedJob> job;
  group.together([&] { job.emplace(prepare(options, speaks, start)); });
  group.check_same_job(job_text(*job), "the processes of this MPI job were given different jobs (model, "
                                      "parameters or settings differ between ranks): give every rank the same");
  const Model& model = job->model;
  const SimulationSettings& settings = job->settings;
  const std::vector<FilterEquations>& filters = job->filters;
  const std::string& source = job->source;

  toolchain::PluginBuildOptions build_options;
  build_options.cache_dir = options.cache_dir;
  build_options.compiler = options.compiler;
  // A dense model's plugin takes the compiler tens of seconds: say so before, and how long after.
  if (talk)
    build_options.before_compile = [&](const std::string&) {
      std::cerr << "pfgen: compiling the simulation plugin (" << filters.size()
                << (filters.size() == 1 ? " filter, " : " filters, ") << source.size() / 1024 << " KiB of C++)...\n"
                << std::flush;
    };
  toolchain::PluginBuild build;
  std::optional<pfgen_runtime::SimulationPlugin> loaded;
  group.build_in_turn([&] { loaded.emplace(load_plugin(source, build_options, talk, build)); });
  const pfgen_runtime::SimulationPlugin& plugin = *loaded;

  // This process's runs (all of them but in an MPI job); the progress bar counts those, against
  // an even share of the job where the runs are handed out as the processes ask.
  // In chunks of a batch, so that a thread's batches keep their lanes full.
  std::optional<pfgen_runtime::RunShare> share = group.share(settings.runs, options.batch);
  const std::size_t own_runs = !share                ? settings.runs
                               : share->hand_out ? (settings.runs + share->processes - 1) / share->processes
                                                 : share->count;
  ProgressBar progress("simulate", speaks ? own_runs : 0, options.progress);
  std::optional<pfgen_runtime::MonteCarloResult> folded;
  group.together([&] {
    plugin.check_grid_step(settings.dt);  // a delayed filter runs only on the grid it was made for
    const std::string scheme_name = settings.scheme == "auto" ? choose_truth_scheme(model) : settings.scheme;
    const auto scheme =
        pfgen_runtime::make_scheme(pfgen_runtime::scheme_kind_from_string(scheme_name), plugin.system());

    pfgen_runtime::MonteCarloOptions mc;
    mc.grid = pfgen_runtime::TimeGrid::to_horizon(0.0, settings.T, settings.dt);
    mc.runs = settings.runs;
    mc.seed = settings.seed;
    mc.threads = thread_count(options.threads, settings.runs);
    mc.batch = options.batch;
    mc.record_points = effective_record_points(options, settings);
    mc.shown_run = settings.shown_run;
    mc.report_times = settings.report_times;
    mc.windows = settings.windows;
    mc.truth_guard = pfgen_runtime::DivergenceGuard(settings.bound);
    mc.filter_guards.estimate_guard = pfgen_runtime::DivergenceGuard(settings.bound);
    mc.filter_guards.covariance_guard =
        pfgen_runtime::DivergenceGuard(std::max(1e16, settings.bound * settings.bound));
    mc.filter_guards.stepping.adaptive = settings.refined_stepping;
    if (settings.criterion) mc.criterion = criterion_options(*settings.criterion, model.n());
    if (settings.x0_from_prior) mc.initial_prior = filters_prior(model);
    if (settings.reference_particles) {
      const std::string obstacle = reference_obstacle(model, plugin);
      if (obstacle.empty()) {
        mc.reference = reference_options(model, *settings.reference_particles);
        if (speaks) warn_fixed_x0_against_reference(model, settings);
      } else if (speaks)
        std::cerr << "pfgen: --reference: skipped, " << obstacle << "\n";
    }
    mc.on_run_finished = [&progress](std::size_t finished, std::size_t) { progress.update(finished); };
    mc.share = std::move(share);

    // With --x0 prior each run draws its own x0; the fixed one is then only a placeholder.
    const Eigen::VectorXd x0 = mc.initial_prior ? mc.initial_prior->mean : plugin.truth_initial_state();
    // The plugin's one observation (its rate, noise and timing) makes the runs' observations and
    // the filters' families take them: increments, or samples.
    folded = pfgen_runtime::run_monte_carlo(*scheme, plugin.observation(), x0, plugin.filters(), mc);
  });
  progress.finish();
  SimulationOutcome outcome{std::move(job->model), job->settings, build, job->derive_seconds, start, std::nullopt};
  if (folded->folded) outcome.result = std::move(folded);  // else another process of the job has them
  return outcome;
}

std::string simulation_report(const SimulateOptions& options, const SimulationOutcome& outcome) {
  const Model& model = outcome.model;
  // What the observation adds to the header line (a delayed one's h in steps) and after the table
  // (its signed errors at the report times); nothing for the others.
  const ObservationCommand& observation = observation_command(model.observation.kind());
  return "model: " + model.name + " (" + options.model_path + ")" +
         observation.header_note(model, outcome.settings.dt) + "\n" +
         pfgen_runtime::format_summary_table(*outcome.result, model.state_names) +
         observation.after_table(*outcome.result, model.state_names);
}

int run_simulate(const SimulateOptions& options, JobGroup& group) {
  const SimulationOutcome outcome = simulate(options, group);
  if (!outcome.result) return 0;  // another process of the job writes the outputs
  const pfgen_runtime::MonteCarloResult& result = *outcome.result;
  const Model& model = outcome.model;
  const bool talk = !options.quiet;

  // Files first, table last: a failed write must not follow a printed result.
  if (!options.csv_path.empty() || !options.plot_path.empty())
    pfgen_runtime::write_results_csv(csv_for_plot(options), result, model.state_names);
  if (!options.plot_path.empty()) {
    try {
      pfgen_runtime::write_error_plot(options.plot_path, csv_for_plot(options), result, model.state_names,
                                      model.name + ": estimation errors x - m", options.plot_ylim);
    } catch (...) {
      if (options.csv_path.empty()) std::remove(csv_for_plot(options).c_str());  // ours, not asked for
      throw;
    }
  }

  if (!options.criterion_csv_path.empty()) pfgen_runtime::write_criterion_csv(options.criterion_csv_path, result);
  if (!options.stops_csv_path.empty()) pfgen_runtime::write_stops_csv(options.stops_csv_path, result);

  // Before the table, like the other files: a failed write must not follow a printed result.
  if (!options.timing_path.empty())
    write_file_atomically("--timing", options.timing_path,
                          timing_json(result, outcome.build, outcome.derive_seconds, seconds_since(outcome.start)));

  // Timing first (stderr), so that the output ends with the table and the paths of the files.
  if (talk) std::cerr << pfgen_runtime::format_timing(result) << std::flush;
  std::cout << simulation_report(options, outcome);
  if (!options.csv_path.empty()) std::cout << "csv: " << options.csv_path << "\n";
  if (!options.criterion_csv_path.empty()) std::cout << "criterion csv: " << options.criterion_csv_path << "\n";
  if (!options.stops_csv_path.empty()) std::cout << "stops csv: " << options.stops_csv_path << "\n";
  if (!options.plot_path.empty()) {
    if (options.csv_path.empty()) std::cout << "csv: " << csv_for_plot(options) << "\n";
    std::cout << "plot: " << options.plot_path << "\n";
  }
  return 0;
}

}  // namespace pfgen::cli
