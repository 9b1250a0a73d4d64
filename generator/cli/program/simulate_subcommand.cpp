// pfgen simulate's command line.
#include <cstddef>
#include <memory>
#include <string>

#include "cli_options.hpp"
#include "simulate_command.hpp"
#include "subcommands.hpp"
#ifdef PFGEN_WITH_MPI
#include "mpi_runs.hpp"
#endif
#include "pfgen/model/model.hpp"

namespace pfgen::cli {

Subcommand add_simulate_subcommand(CLI::App& app, const OptionChecks& checks, [[maybe_unused]] int argc,
                                   [[maybe_unused]] char** argv) {
  // The scheme option's text lists the truth schemes, so that the help never disagrees with what
  // it accepts.
  const std::string scheme_help = "Truth scheme: " + join(pfgen::simulation_schemes(), " | ");
  auto simulate = std::make_shared<SimulateOptions>();
  SimulationOverrides& so = simulate->overrides;
  CLI::App* simulate_cmd = app.add_subcommand(
      "simulate", "Compile a model's filters and run them against a simulated truth (Monte Carlo)");
  simulate_cmd->add_option("MODEL", simulate->model_path, "Model file (YAML)")->required();
  simulate_cmd->add_option("--filters", so.filters,
                           "Comma-separated filters, built-in kinds or the model's own (default: simulation.filters, "
                           "else every filter of the model but the opt-in ukf)")
      ->check(checks.named_filters);
  simulate_cmd->add_option("--T", so.T, "Horizon (default: simulation.T)")->check(checks.double_number);
  simulate_cmd->add_option("--dt", so.dt, "Time step of the truth and the filters (default: simulation.dt, else 1e-3)")
      ->check(checks.double_number);
  simulate_cmd->add_option("--runs", so.runs, "Monte Carlo runs (default: simulation.runs, else 100)")
      ->check(checks.whole_number);
  simulate_cmd->add_option("--seed", so.seed, "Seed; run r uses streams derived from (seed, r) (default 1)")
      ->check(checks.whole_number);
  simulate_cmd->add_option("--threads", simulate->threads, "Worker threads, 0 = every core; results do not depend on it")
      ->check(checks.whole_number)
      ->capture_default_str();
  simulate_cmd->add_option("--batch", simulate->batch,
                           "Runs each thread steps side by side, >= 1; results do not depend on it")
      ->check(CLI::Range(std::size_t(1), std::size_t(1024)))
      ->capture_default_str();
  simulate_cmd->add_option("--scheme", so.scheme,
                           scheme_help);
  simulate_cmd->add_option("--report-times", so.report_times, "Times for the error columns, e.g. 5,6,6.5");
  simulate_cmd->add_option("--windows", so.windows, "RMS windows a:b, comma-separated, e.g. 0:4,4:9.2");
  simulate_cmd->add_option("--record-points", so.record_points, "Points of the time series (CSV, plot); default 1000")
      ->check(checks.whole_number);
  simulate_cmd->add_option("--shown-run", so.shown_run, "The run whose path goes into the CSV and plot (default 0)")
      ->check(checks.whole_number);
  simulate_cmd->add_option("--bound", so.bound, "A run stops when |x|, |m| exceed this (default 1e8)")
      ->check(checks.double_number);
  simulate_cmd->add_option("-o,--output", simulate->csv_path, "CSV of time series")->check(checks.named_file);
  simulate_cmd->add_option("--plot", simulate->plot_path, "Plot of the errors, FILE.png or FILE.svg (gnuplot)")
      ->check(checks.named_file);
  simulate_cmd->add_option("--plot-ylim", simulate->plot_ylim,
                           "Fix the plot's y range to [-Y, Y] so one diverging filter does not flatten the rest")
      ->check(checks.double_number);
  simulate_cmd->add_option("--cache-dir", simulate->cache_dir,
                           "Compiled plugins (default: $PFGEN_CACHE_DIR, $XDG_CACHE_HOME/pfgen, ~/.cache/pfgen)")
      ->check(checks.named_file);
  simulate_cmd->add_option("--compiler", simulate->compiler, "C++ compiler for the plugin (default: $CXX, else c++)")
      ->check(checks.named_file);
  simulate_cmd->add_option("--timing", simulate->timing_path, "Write phase times as JSON to FILE")->check(checks.named_file);
  simulate_cmd->add_option("--set", simulate->assignments, "Parameter value for this job, name=value (repeatable)");
  simulate_cmd->add_option("--risk-epsilon", so.risk_epsilon,
                           "Report the exponential criterion J = eps log E[exp(int L dt / eps)] of every filter with "
                           "this eps (default: the model's risk.epsilon; without either, no J)")
      ->check(checks.double_number);
  simulate_cmd->add_option("--reference", so.reference,
                           "particles:N: on each run a bootstrap particle filter with N particles estimates the true "
                           "conditional mean; the table adds each filter's RMS distance from it (not for delayed "
                           "observations or a truth without noise)");
  simulate_cmd->add_option("--x0", so.x0,
                           "prior: each run's truth starts from a draw of N(m0, P0), the filters' prior (as the "
                           "particle reference assumes); model: the model's x0 (default: the model's initial: x0)");
  simulate_cmd->add_option("--stepping", so.stepping,
                           "refined: split a filter's grid step where one step would change P too fast (default); "
                           "generated: one step() per grid step, as the generated code runs");
  simulate_cmd->add_option("--criterion-csv", simulate->criterion_csv_path,
                           "Write J per filter as CSV to FILE (needs --risk-epsilon or a risk: section)")
      ->check(checks.named_file);
  simulate_cmd->add_option("--stops-csv", simulate->stops_csv_path,
                           "Write every run that stopped before T (truth or filter, event, run, t) as CSV to FILE")
      ->check(checks.named_file);
  simulate_cmd->add_flag("-q,--quiet", simulate->quiet, "No plugin and timing lines on stderr");
#ifdef PFGEN_WITH_MPI
  // Started by mpirun: the ranks share the runs, rank 0 writes (mpi_runs.hpp).
  return {simulate_cmd, [simulate, argc, argv]() mutable {  // MPI_Init may change argc, argv
            if (!launched_by_mpi()) return run_simulate(*simulate);
            MpiJob job(argc, argv);
            return run_simulate(*simulate, job);
          }};
#else
  return {simulate_cmd, [simulate] { return run_simulate(*simulate); }};
#endif
}

}  // namespace pfgen::cli
