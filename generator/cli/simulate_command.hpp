#pragma once
// `pfgen simulate`: derive a model's filters, compile them with its truth into a plugin (cached),
// and run them against the simulated truth in Monte Carlo; a summary table on stdout, optionally
// a CSV of time series and a gnuplot plot.
#include <string>
#include <vector>

#include "simulation_settings.hpp"

namespace pfgen::cli {

struct SimulateOptions {
  std::string model_path;
  SimulationOverrides overrides;
  unsigned threads = 0;       // 0: every core (results do not depend on it)
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
};

int run_simulate(const SimulateOptions& options);

}  // namespace pfgen::cli
