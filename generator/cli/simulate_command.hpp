#pragma once
// `pfgen simulate`: derive a model's filters, compile them with its truth into a plugin (cached),
// and run them against the simulated truth in Monte Carlo; a summary table on stdout, optionally
// a CSV of time series and a gnuplot plot.
#include <chrono>
#include <optional>
#include <string>
#include <vector>

#include "pfgen/model/model.hpp"
#include "pfgen/toolchain/plugin_compiler.hpp"
#include "pfgen_runtime/monte_carlo.hpp"
#include "progress_bar.hpp"
#include "simulation_settings.hpp"

namespace pfgen::cli {

struct SimulateOptions {
  std::string model_path;
  SimulationOverrides overrides;
  unsigned threads = 0;       // 0: every core (results do not depend on it)
  std::size_t batch = 8;      // runs a thread carries side by side (results do not depend on it)
  std::string csv_path;       // -o
  std::string plot_path;      // --plot FILE.png|svg
  double plot_ylim = 0;       // --plot-ylim Y: y range [-Y, Y]; 0 autoscales
  std::string cache_dir;      // empty: the toolchain's default
  std::string compiler;       // empty: $CXX or c++
  std::string timing_path;    // --timing FILE: phase times as JSON (for benchmarks)
  std::string criterion_csv_path;  // --criterion-csv FILE: J per filter (needs the criterion)
  std::string stops_csv_path;      // --stops-csv FILE: every run that stopped before T, with its time
  bool quiet = false;         // no compile/timing lines on stderr
  std::vector<std::string> assignments;  // --set name=value: parameter values for this job
  // The API's: a model already loaded, simulated instead of reading model_path (which then only
  // names it in the header line); and the time series recorded although no CSV or plot is
  // written, for the caller to read from the result.
  const Model* model = nullptr;
  bool keep_series = false;
  // Where the progress bar goes: the command's on a terminal, or the API caller's own, or none.
  ProgressOutput progress = ProgressOutput::terminal();
};

class JobGroup;

// What a job computed, on the process that folds the runs' results (the only one without MPI).
struct SimulationOutcome {
  Model model;  // with the job's --set values
  SimulationSettings settings;
  toolchain::PluginBuild build;
  double derive_seconds = 0;
  std::chrono::steady_clock::time_point start;
  std::optional<pfgen_runtime::MonteCarloResult> result;  // empty on the other processes of a job
};

// Reads (or takes) the model, resolves the settings, derives the filters, builds (or finds in
// the cache) and loads the plugin and runs the Monte Carlo; writes nothing but stderr's notes.
SimulationOutcome simulate(const SimulateOptions& options, JobGroup& group);

// What `pfgen simulate` prints on stdout before the paths of its files: the header line naming
// the model, the summary table, and what the observation adds after it.
std::string simulation_report(const SimulateOptions& options, const SimulationOutcome& outcome);

int run_simulate(const SimulateOptions& options);
// The same job made by several processes together (job_group.hpp): each runs this with its own
// group member; only the one that speaks() prints and writes files.
int run_simulate(const SimulateOptions& options, JobGroup& group);

}  // namespace pfgen::cli
