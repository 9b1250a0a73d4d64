// pfgen estimate's and fit's command lines: the filters over a record of observations
// (record_job.hpp), and maximum likelihood of some parameters over one (likelihood_fit.hpp).
#include <memory>

#include "estimate_command.hpp"
#include "fit_command.hpp"
#include "subcommands.hpp"

namespace pfgen::cli {
namespace {

// What both read: the model, the record and how its columns are read, the plugin's settings.
void add_record_options(CLI::App* command, RecordJobOptions& r, const OptionChecks& checks) {
  command->add_option("MODEL", r.model_path, "Model file (YAML)")->required()->check(checks.named_file);
  command->add_option("--data", r.data_path, "Record: CSV with a header naming the time and observation columns")
      ->required()
      ->check(checks.named_file);
  command->add_option("--time-column", r.time_column, "The record's time column (default t)");
  command->add_option("--columns", r.columns, "The observation columns in the model's order (default: all others)")
      ->delimiter(',');
  command->add_option("--data-form", r.data_form,
                      "Continuous observations: increments (dy over each interval, default) or rates (dy/dt)");
  command->add_option("--substeps", r.substeps, "Continuous observations: filter steps per data interval (default 1)");
  command->add_option("--t0", r.t0, "Time of the prior m0, P0 (default: the first row's time)")->check(checks.double_number);
  command->add_option("--set", r.assignments, "Parameter value, name=value (repeatable)");
  command->add_option("--cache-dir", r.cache_dir, "Compiled plugins (default as simulate's)")->check(checks.named_file);
  command->add_option("--compiler", r.compiler, "C++ compiler for the plugin (default: $CXX, else c++)");
  command->add_flag("-q,--quiet", r.quiet, "No plugin lines on stderr");
}

}  // namespace

Subcommand add_estimate_subcommand(CLI::App& app, const OptionChecks& checks) {
  auto estimate = std::make_shared<EstimateOptions>();
  RecordJobOptions& ro = estimate->record;
  CLI::App* estimate_cmd = app.add_subcommand(
      "estimate", "Run a model's filters over recorded observations: estimates, innovations and scores");
  add_record_options(estimate_cmd, ro, checks);
  estimate_cmd->add_option("--filters", ro.filters, "Filters, comma-separated (default: the model's defaults)")
      ->delimiter(',');
  estimate_cmd->add_option("-o,--output", estimate->csv_path, "CSV: per data time each filter's estimates and innovations")
      ->check(checks.named_file);
  estimate_cmd->add_option("--plot", estimate->plot_path, "Plot of the estimates with 2-sigma bands, FILE.png or FILE.svg")
      ->check(checks.named_file);
  estimate_cmd->add_flag("--full-covariance", estimate->full_covariance, "Write every entry of P to the CSV");
  return {estimate_cmd, [estimate] { return run_estimate(*estimate); }};
}

Subcommand add_fit_subcommand(CLI::App& app, const OptionChecks& checks) {
  auto fit = std::make_shared<FitOptions>();
  CLI::App* fit_cmd = app.add_subcommand("fit", "Fit a model's parameters to recorded observations by maximum likelihood");
  add_record_options(fit_cmd, fit->record, checks);
  fit_cmd->add_option("--estimate", fit->estimate, "Parameters to estimate, comma-separated; m0.X: the prior mean of state X")
      ->required()
      ->delimiter(',');
  fit_cmd->add_option("--bounds", fit->bounds, "Bounds name=low:high, comma-separated (an end may be empty)")
      ->delimiter(',');
  fit_cmd->add_option("--filter", fit->filter, "The filter whose likelihood is maximised (default: the model's first)");
  fit_cmd->add_option("--starts", fit->starts, "Starting points: the model's values, then draws within the bounds");
  fit_cmd->add_option("--seed", fit->seed, "Seed of the further starting points (default 1)");
  fit_cmd->add_flag("--profile", fit->profile, "Profile-likelihood intervals too");
  fit_cmd->add_option("-o,--output", fit->json_path, "The fit as JSON")->check(checks.named_file);
  return {fit_cmd, [fit] { return run_fit(*fit); }};
}

}  // namespace pfgen::cli
