// pfgen::api::Model::simulate: `pfgen simulate` run in this process, its results kept in memory.
#include <iostream>
#include <sstream>

#include "api_impl.hpp"
#include "cli_options.hpp"
#include "job_group.hpp"
#include "redirected_stderr.hpp"
#include "pfgen_runtime/results_csv.hpp"
#include "simulate_command.hpp"

namespace pfgen::api {
namespace {

std::string joined(const std::vector<std::string>& parts) {
  std::string text;
  for (const std::string& part : parts) text += (text.empty() ? "" : ",") + part;
  return text;
}

// SimulationOptions as `pfgen simulate`'s options, which the command's own code then checks.
cli::SimulateOptions command_options(const pfgen::Model& model, const SimulationOptions& options) {
  for (const auto& [option, value] : {std::pair{"--T", options.T}, {"--dt", options.dt}, {"--bound", options.bound},
                                     {"--risk-epsilon", options.risk_epsilon}})
    if (value) check_number_option(option, *value);
  for (const std::string& name : options.filters) check_no_nul("--filters", name);
  for (const auto& [option, text] : {std::pair{"--cache-dir", &options.cache_dir}, {"--compiler", &options.compiler}})
    check_no_nul(option, *text);
  if (options.scheme) check_no_nul("--scheme", *options.scheme);
  if (options.x0) check_no_nul("--x0", *options.x0);
  if (options.stepping) check_no_nul("--stepping", *options.stepping);
  cli::SimulateOptions out;
  out.model = &model;
  out.model_path = model.source;
  out.quiet = true;
  out.keep_series = true;
  if (options.batch < 1 || options.batch > 1024)
    throw cli::CliValueError("--batch: Value " + std::to_string(options.batch) + " not in range 1 to 1024");
  out.threads = options.threads;
  out.batch = options.batch;
  out.cache_dir = options.cache_dir;
  out.compiler = options.compiler;
  out.progress = options.progress ? cli::ProgressOutput::to(options.progress) : cli::ProgressOutput::none();
  out.assignments = assignment_texts(options.parameters);
  cli::SimulationOverrides& o = out.overrides;
  o.T = options.T;
  o.dt = options.dt;
  o.bound = options.bound;
  o.runs = options.runs;
  o.record_points = options.record_points;
  o.shown_run = options.shown_run;
  o.seed = options.seed;
  if (!options.filters.empty()) o.filters = joined(options.filters);
  o.scheme = options.scheme;
  o.x0 = options.x0;
  o.stepping = options.stepping;
  o.risk_epsilon = options.risk_epsilon;
  if (options.reference) o.reference = "particles:" + std::to_string(*options.reference);
  if (!options.report_times.empty()) {
    std::vector<std::string> times;
    for (double t : options.report_times) times.push_back(number_text(t));
    o.report_times = joined(times);
  }
  if (!options.windows.empty()) {
    std::vector<std::string> windows;
    for (const auto& [a, b] : options.windows) windows.push_back(number_text(a) + ":" + number_text(b));
    o.windows = joined(windows);
  }
  return out;
}

FilterSummary summary_of(const std::string& name, const pfgen_runtime::WindowStatistics& horizon) {
  FilterSummary out;
  out.name = name;
  out.completed = horizon.runs;
  out.rms = horizon.rms;
  out.rms_se = horizon.rms_se;
  return out;
}

}  // namespace

SimulationResult Model::simulate(const SimulationOptions& options) const {
  return guarded([&] {
    const cli::SimulateOptions command = command_options(impl_->model, options);
    // What the command says on stderr while the job runs (its notes), kept for the result instead.
    std::ostringstream notes;
    const cli::RedirectedStderr captured(notes.rdbuf());
    cli::LocalJob alone;
    const cli::SimulationOutcome outcome = cli::simulate(command, alone);
    const pfgen_runtime::MonteCarloResult& result = *outcome.result;
    const std::vector<std::string>& states = outcome.model.state_names;

    SimulationResult out;
    out.report = cli::simulation_report(command, outcome);
    out.notes = notes.str();
    out.csv = pfgen_runtime::format_results_csv(result, states);
    out.columns = pfgen_runtime::results_csv_columns(result, states);
    out.series = csv_series(out.csv, out.columns.size());
    out.runs = result.runs;
    out.steps = result.grid.steps;
    out.shown_run = result.series.shown_run;
    if (result.reference) out.reference_particles = result.reference->particles;
    for (const pfgen_runtime::FilterStatistics& filter : result.filters) {
      FilterSummary summary = summary_of(filter.name, filter.horizon);
      summary.diverged = filter.divergences.count();
      summary.psd_losses = filter.psd_losses.count();
      summary.unrealisable = filter.unrealisable.count();
      summary.too_stiff = filter.too_stiff_runs;
      summary.undefined = filter.undefined_runs;
      summary.peak_median = filter.peak_median;
      summary.peak_q95 = filter.peak_q95;
      if (filter.reference) {
        summary.reference_distance = filter.reference->distance;
        summary.reference_distance_se = filter.reference->distance_se;
      }
      out.filters.push_back(std::move(summary));
    }
    if (result.reference) {  // the particle reference itself, as a filter of the table
      FilterSummary summary = summary_of("reference", result.reference->horizon);
      summary.diverged = result.reference->stopped.count();
      summary.own_error = result.reference->error;
      out.filters.push_back(std::move(summary));
    }
    return out;
  });
}

}  // namespace pfgen::api
