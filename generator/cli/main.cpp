// pfgen: derive, print and evaluate optimal filters for polynomial stochastic systems.
#include <CLI/CLI.hpp>

#include <cerrno>
#include <charconv>
#include <cstdio>
#include <cmath>
#include <cstdlib>
#include <cstring>
#include <cstdint>
#include <iostream>
#include <stdexcept>
#include <string>

#include "cli_options.hpp"
#include "commands.hpp"
#include "huge_page_heap.hpp"
#include "job_group.hpp"
#include "estimate_command.hpp"
#include "fit_command.hpp"
#include "simulate_command.hpp"
#ifdef PFGEN_WITH_MPI
#include "mpi_runs.hpp"
#endif
#include "pfgen/evaluation/point_evaluator.hpp"
#include "pfgen/kinds/filter_kinds.hpp"
#include "pfgen/codegen/backend.hpp"
#include "pfgen/model/model.hpp"
#include "pfgen/model/model_error.hpp"
#include "pfgen_support/quoted_text.hpp"

namespace {

// Every error is reported on exactly one line of stderr.
using pfgen_support::one_line;

// A report that did not reach standard output (`pfgen derive m.yaml > /dev/full`: ENOSPC) is a
// failure, not a success with nothing printed.
void check_standard_output_written() {
  std::cout.flush();
  // errno as the failed write left it (a later successful call does not reset it).
  if (!std::cout || std::fflush(stdout) != 0 || std::ferror(stdout))
    throw std::runtime_error(std::string("cannot write standard output: ") +
                             (errno ? std::strerror(errno) : "write error"));
}

// CLI11 reads "--filter=" (nothing after '=') as "--filter" without its value and takes the next
// argument as the value: `eval --filter= --m 0.5` reported "--m is required". A long option
// written with '=' and nothing after it is refused here, named, before CLI11 parses.
void refuse_empty_equals_values(int argc, char** argv) {
  for (int k = 1; k < argc; ++k) {
    const std::string argument = argv[k];
    if (argument == "--") return;  // what follows is positional
    if (argument.size() > 3 && argument.compare(0, 2, "--") == 0 && argument.back() == '=' &&
        argument.find('=') == argument.size() - 1)
      throw std::runtime_error(argument.substr(0, argument.size() - 1) + ": no value after '='");
  }
}

}  // namespace

int main(int argc, char** argv) {
  using namespace pfgen::cli;
  use_huge_page_heap(argv);  // first: it may execute pfgen again (huge_page_heap.hpp)
  CLI::App app{"pfgen " PFGEN_VERSION ": optimal filters for polynomial stochastic systems"};
  app.require_subcommand(1);
  app.failure_message([](const CLI::App*, const CLI::Error& e) {
    return "pfgen: error: " + one_line(e.what()) + " (see pfgen --help)\n";
  });
  app.set_version_flag("--version", "pfgen " PFGEN_VERSION);

  // Option texts list the registries' names (kinds/filter_kinds.hpp, the truth schemes), so that
  // the help never disagrees with what the options accept.
  const std::string one_filter_help = join(pfgen::filter_kind_names(), " | ") + " | a filter of the model's filters: section";
  const std::string scheme_help = "Truth scheme: " + join(pfgen::simulation_schemes(), " | ");

  // A number option's text itself, before CLI11 converts it: strtod turns 1e-9999 into 0 and 1e400
  // into infinity, and the message then quoted what the conversion made of it.
  const CLI::Validator double_number(
      [](std::string& text) -> std::string {
        errno = 0;
        char* end = nullptr;
        const double value = std::strtod(text.c_str(), &end);
        if (text.empty() || end != text.c_str() + text.size()) return pfgen_support::quoted(text) + " is not a number";
        if (errno == ERANGE || !std::isfinite(value))
          return pfgen_support::quoted(text) +
                 " is outside the range of a double (magnitudes from about 2.2e-308 to 1.8e308)";
        return std::string();
      },
      "NUMBER");

  // An empty file name is refused wherever a file is named: simulate and derive used to skip an
  // output given as "" without a word, while codegen and latex refused it.
  const CLI::Validator named_file(
      [](std::string& text) -> std::string { return text.empty() ? "the file name is empty" : std::string(); },
      "FILE");

  // An empty filter list is no list: derive --filter "" printed the default filter without a word.
  const CLI::Validator named_filters(
      [](std::string& text) -> std::string {
        return text.empty() ? "the list is empty; name filters, or leave the option out for the default" : std::string();
      },
      "FILTERS");

  DeriveOptions derive;
  CLI::App* derive_cmd = app.add_subcommand("derive", "Print the closed filter equations of a model");
  derive_cmd->add_option("MODEL", derive.model_path, "Model file (YAML)")->required();
  derive_cmd->add_option("--filter", derive.filter,
                         one_filter_help + " (default: the model's first, optimal for continuous observations)")
      ->check(named_filters);
  derive_cmd->add_option("--format", derive.format, "text | latex | json")
      ->check(CLI::IsMember({"text", "latex", "json"}))
      ->capture_default_str();
  derive_cmd->add_flag("--coefficients", derive.coefficients,
                       "Print the model's coefficient form instead of a filter: f = A + A1 x + A2 x x + A3 x x x, "
                       "observation rate E + E1 x (drift of degree <= 3)");
  derive_cmd->add_option("--timing", derive.timing_path,
                         "Write the seconds spent reading the model, deriving and printing as JSON to FILE")
      ->check(named_file);

  LatexOptions latex;
  CLI::App* latex_cmd = app.add_subcommand("latex", "Write a standalone LaTeX document of the model and its filters");
  latex_cmd->add_option("MODEL", latex.model_path, "Model file (YAML)")->required();
  latex_cmd->add_option("-o,--output", latex.output_path, "Output .tex file")->required()->check(named_file);
  latex_cmd->add_option("--filter", latex.filters, "Comma-separated filters: built-in kinds or the model's own (default: every kind the model supports except the opt-in ukf, then its own)")
      ->check(named_filters);
  latex_cmd->add_flag("--coefficients", latex.coefficients,
                      "Add a section with the model's coefficient form A..A3, E, E1 (drift of degree <= 3)");

  EvalOptions eval;
  CLI::App* eval_cmd = app.add_subcommand("eval", "Evaluate a filter's m drift, gain and P drift at one point (JSON)");
  eval_cmd->add_option("MODEL", eval.model_path, "Model file (YAML)")->required();
  eval_cmd->add_option("--filter", eval.filter, one_filter_help)->required();
  eval_cmd->add_option("--t", eval.t, "Time")->capture_default_str();
  eval_cmd->add_option("--m", eval.m, "Estimate, comma-separated: --m=-1.5,2")->required();
  eval_cmd->add_option("--P", eval.P, "Covariance, rows separated by ';': --P '1,0;0,1'")->required();
  eval_cmd->add_option("--set", eval.assignments, "Parameter value, name=value (repeatable)");
  // Delayed observations: what the filter's history holds at t (docs/theory.md §2.6).
  eval_cmd->add_option("--m-delayed", eval.m_delayed,
                       "Delayed filters: the estimate m(t-h) the innovation uses (default: --m)");
  eval_cmd->add_option("--x-star", eval.x_star, "delay-optimal: the noise-free solution x*(t) (default: --m)");
  eval_cmd->add_option("--x-star-delayed", eval.x_star_delayed,
                       "delay-optimal: x*(t-h) (default: --x-star); phi_i = x*_i(t-h)/x*_i(t) for t >= h, "
                       "0 where x*_i(t) = 0, 0 for t < h (1 when h = 0)");
  eval_cmd->add_option("--phi", eval.phi,
                       "delay-optimal: the diagonal of Phi* itself, used as given (instead of --x-star-delayed)");

  CodegenCliOptions codegen;
  CLI::App* codegen_cmd = app.add_subcommand("codegen", "Write a model's filters as C++ headers or C99 .h/.c pairs");
  codegen_cmd->add_option("MODEL", codegen.model_path, "Model file (YAML)")->required();
  codegen_cmd->add_option("-o,--output", codegen.output_dir, "Output directory; files go to DIR/<model>/<filter>.hpp (C: .h and .c)")
      ->check(named_file);
  codegen_cmd->add_option("--filter", codegen.filters, "Comma-separated filters: built-in kinds or the model's own (default: every kind the model supports except the opt-in ukf, then its own)")
      ->check(named_filters);
  // --language's names and help from the registry of backends: "cpp | c: header-only C++, or C99 .h/.c pairs".
  std::vector<std::string> language_names;
  std::string language_names_text, language_summaries;
  const auto& backends = pfgen::codegen::backends();
  for (std::size_t k = 0; k < backends.size(); ++k) {
    language_names.push_back(backends[k]->name());
    language_names_text += (k ? " | " : "") + backends[k]->name();
    language_summaries += std::string(k == 0 ? "" : k + 1 < backends.size() ? ", " : ", or ") + backends[k]->summary();
  }
  codegen_cmd->add_option("--language", codegen.language, language_names_text + ": " + language_summaries)
      ->check(CLI::IsMember(language_names))
      ->capture_default_str();
  CLI::Option* scalar_option = codegen_cmd->add_option("--scalar", codegen.scalar, "float | double | template (C: float | double, default double)")
      ->check(CLI::IsMember({"float", "double", "template"}))
      ->capture_default_str();
  codegen_cmd->add_option("--namespace", codegen.name_space, "Outer C++ namespace (C: the names' prefix, :: written _)")
      ->capture_default_str();
  codegen_cmd->add_flag("--stats", codegen.stats, "Print operation counts as JSON, one line per filter kind");
  codegen_cmd->add_flag("--eigen", codegen.eigen,
                        "Also write DIR/<model>/<filter>_eigen.hpp: wrappers taking m and P as Eigen matrices");
  codegen_cmd->add_option("--dt", codegen.dt,
                          "Delayed observations: the grid step of the filters, a divisor of the delay (default: "
                          "simulation.dt)")
      ->check(double_number);
  codegen_cmd->add_flag("--no-cse", codegen.no_cse, "Emit without common-subexpression elimination (benchmark baseline)");

  // CLI11 reads unsigned options with strtoull, which takes "-1" as 2^64 - 1 and saturates an
  // overflow at 2^64 - 1 without a word (--seed -1 and --seed 18446744073709551616 both ran with
  // seed 18446744073709551615; --runs -1 asked for 1.8e19 runs). Only plain digits that fit pass.
  const CLI::Validator whole_number(
      [](std::string& text) -> std::string {
        std::uint64_t value = 0;
        const char* end = text.data() + text.size();
        const auto [stop, error] = std::from_chars(text.data(), end, value);
        if (text.empty() || error != std::errc() || stop != end)
          return "'" + text + "' is not a whole number from 0 to 18446744073709551615";
        return std::string();
      },
      "UINT");
  codegen_cmd->add_option("--max-function-ops", codegen.max_function_ops,
                          "Write a function of more operations (after CSE) in parts of at most this many, each its "
                          "own function, to bound compile time (default 500; 0: never split)")
      ->check(whole_number);

  SimulateOptions simulate;
  SimulationOverrides& so = simulate.overrides;
  CLI::App* simulate_cmd = app.add_subcommand(
      "simulate", "Compile a model's filters and run them against a simulated truth (Monte Carlo)");
  simulate_cmd->add_option("MODEL", simulate.model_path, "Model file (YAML)")->required();
  simulate_cmd->add_option("--filters", so.filters,
                           "Comma-separated filters, built-in kinds or the model's own (default: simulation.filters, "
                           "else every filter of the model but the opt-in ukf)")
      ->check(named_filters);
  simulate_cmd->add_option("--T", so.T, "Horizon (default: simulation.T)")->check(double_number);
  simulate_cmd->add_option("--dt", so.dt, "Time step of the truth and the filters (default: simulation.dt, else 1e-3)")
      ->check(double_number);
  simulate_cmd->add_option("--runs", so.runs, "Monte Carlo runs (default: simulation.runs, else 100)")
      ->check(whole_number);
  simulate_cmd->add_option("--seed", so.seed, "Seed; run r uses streams derived from (seed, r) (default 1)")
      ->check(whole_number);
  simulate_cmd->add_option("--threads", simulate.threads, "Worker threads, 0 = every core; results do not depend on it")
      ->check(whole_number)
      ->capture_default_str();
  simulate_cmd->add_option("--batch", simulate.batch,
                           "Runs each thread steps side by side, >= 1; results do not depend on it")
      ->check(CLI::Range(std::size_t(1), std::size_t(1024)))
      ->capture_default_str();
  simulate_cmd->add_option("--scheme", so.scheme,
                           scheme_help);
  simulate_cmd->add_option("--report-times", so.report_times, "Times for the error columns, e.g. 5,6,6.5");
  simulate_cmd->add_option("--windows", so.windows, "RMS windows a:b, comma-separated, e.g. 0:4,4:9.2");
  simulate_cmd->add_option("--record-points", so.record_points, "Points of the time series (CSV, plot); default 1000")
      ->check(whole_number);
  simulate_cmd->add_option("--shown-run", so.shown_run, "The run whose path goes into the CSV and plot (default 0)")
      ->check(whole_number);
  simulate_cmd->add_option("--bound", so.bound, "A run stops when |x|, |m| exceed this (default 1e8)")
      ->check(double_number);
  simulate_cmd->add_option("-o,--output", simulate.csv_path, "CSV of time series")->check(named_file);
  simulate_cmd->add_option("--plot", simulate.plot_path, "Plot of the errors, FILE.png or FILE.svg (gnuplot)")
      ->check(named_file);
  simulate_cmd->add_option("--plot-ylim", simulate.plot_ylim,
                           "Fix the plot's y range to [-Y, Y] so one diverging filter does not flatten the rest")
      ->check(double_number);
  simulate_cmd->add_option("--cache-dir", simulate.cache_dir,
                           "Compiled plugins (default: $PFGEN_CACHE_DIR, $XDG_CACHE_HOME/pfgen, ~/.cache/pfgen)")
      ->check(named_file);
  simulate_cmd->add_option("--compiler", simulate.compiler, "C++ compiler for the plugin (default: $CXX, else c++)")
      ->check(named_file);
  simulate_cmd->add_option("--timing", simulate.timing_path, "Write phase times as JSON to FILE")->check(named_file);
  simulate_cmd->add_option("--set", simulate.assignments, "Parameter value for this job, name=value (repeatable)");
  simulate_cmd->add_option("--risk-epsilon", so.risk_epsilon,
                           "Report the exponential criterion J = eps log E[exp(int L dt / eps)] of every filter with "
                           "this eps (default: the model's risk.epsilon; without either, no J)")
      ->check(double_number);
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
  simulate_cmd->add_option("--criterion-csv", simulate.criterion_csv_path,
                           "Write J per filter as CSV to FILE (needs --risk-epsilon or a risk: section)")
      ->check(named_file);
  simulate_cmd->add_option("--stops-csv", simulate.stops_csv_path,
                           "Write every run that stopped before T (truth or filter, event, run, t) as CSV to FILE")
      ->check(named_file);
  simulate_cmd->add_flag("-q,--quiet", simulate.quiet, "No plugin and timing lines on stderr");

  // estimate: the filters over a record of observations (record_job.hpp).
  EstimateOptions estimate;
  RecordJobOptions& ro = estimate.record;
  CLI::App* estimate_cmd = app.add_subcommand(
      "estimate", "Run a model's filters over recorded observations: estimates, innovations and scores");
  const auto add_record_options = [&](CLI::App* command, RecordJobOptions& r) {
    command->add_option("MODEL", r.model_path, "Model file (YAML)")->required()->check(named_file);
    command->add_option("--data", r.data_path, "Record: CSV with a header naming the time and observation columns")
        ->required()
        ->check(named_file);
    command->add_option("--time-column", r.time_column, "The record's time column (default t)");
    command->add_option("--columns", r.columns, "The observation columns in the model's order (default: all others)")
        ->delimiter(',');
    command->add_option("--data-form", r.data_form,
                        "Continuous observations: increments (dy over each interval, default) or rates (dy/dt)");
    command->add_option("--substeps", r.substeps, "Continuous observations: filter steps per data interval (default 1)");
    command->add_option("--t0", r.t0, "Time of the prior m0, P0 (default: the first row's time)")->check(double_number);
    command->add_option("--set", r.assignments, "Parameter value, name=value (repeatable)");
    command->add_option("--cache-dir", r.cache_dir, "Compiled plugins (default as simulate's)")->check(named_file);
    command->add_option("--compiler", r.compiler, "C++ compiler for the plugin (default: $CXX, else c++)");
    command->add_flag("-q,--quiet", r.quiet, "No plugin lines on stderr");
  };
  add_record_options(estimate_cmd, ro);
  estimate_cmd->add_option("--filters", ro.filters, "Filters, comma-separated (default: the model's defaults)")
      ->delimiter(',');
  estimate_cmd->add_option("-o,--output", estimate.csv_path, "CSV: per data time each filter's estimates and innovations")
      ->check(named_file);
  estimate_cmd->add_option("--plot", estimate.plot_path, "Plot of the estimates with 2-sigma bands, FILE.png or FILE.svg")
      ->check(named_file);
  estimate_cmd->add_flag("--full-covariance", estimate.full_covariance, "Write every entry of P to the CSV");

  // fit: maximum likelihood of some parameters over a record (likelihood_fit.hpp).
  FitOptions fit;
  CLI::App* fit_cmd = app.add_subcommand("fit", "Fit a model's parameters to recorded observations by maximum likelihood");
  add_record_options(fit_cmd, fit.record);
  fit_cmd->add_option("--estimate", fit.estimate, "Parameters to estimate, comma-separated; m0.X: the prior mean of state X")
      ->required()
      ->delimiter(',');
  fit_cmd->add_option("--bounds", fit.bounds, "Bounds name=low:high, comma-separated (an end may be empty)")
      ->delimiter(',');
  fit_cmd->add_option("--filter", fit.filter, "The filter whose likelihood is maximised (default: the model's first)");
  fit_cmd->add_option("--starts", fit.starts, "Starting points: the model's values, then draws within the bounds");
  fit_cmd->add_option("--seed", fit.seed, "Seed of the further starting points (default 1)");
  fit_cmd->add_flag("--profile", fit.profile, "Profile-likelihood intervals too");
  fit_cmd->add_option("-o,--output", fit.json_path, "The fit as JSON")->check(named_file);

  try {
    refuse_empty_equals_values(argc, argv);
    app.parse(argc, argv);
  } catch (const CLI::ParseError& e) {
    // --help and --version end here with status 0. A parse error exits 1, as every other error
    // does (docs/guide/commands.md), not with CLI11's own codes (105 for a value a check refuses,
    // 106 for a missing option, 109 for an unknown one).
    return app.exit(e) == 0 ? 0 : 1;
  } catch (const std::exception& e) {
    std::cerr << "pfgen: error: " << one_line(e.what()) << " (see pfgen --help)\n";
    return 1;
  }
  try {
    int status = 1;
    if (*derive_cmd) status = run_derive(derive);
    if (*codegen_cmd) {
      codegen.scalar_given = scalar_option->count() > 0;
      status = run_codegen(codegen);
    }
    if (*latex_cmd) status = run_latex(latex);
    if (*eval_cmd) status = run_eval(eval);
    if (*estimate_cmd) status = run_estimate(estimate);
    if (*fit_cmd) status = run_fit(fit);
    if (*simulate_cmd) {
#ifdef PFGEN_WITH_MPI
      // Started by mpirun: the ranks share the runs, rank 0 writes (mpi_runs.hpp).
      if (launched_by_mpi()) {
        MpiJob job(argc, argv);
        status = run_simulate(simulate, job);
      } else
#endif
        status = run_simulate(simulate);
    }
    check_standard_output_written();
    return status;
  } catch (const pfgen_support::Error& e) {
    // Every error pfgen reports (pfgen_support/error.hpp) says its one line itself; an empty one
    // means another process of the job failed and said why (FailedElsewhere).
    const std::string line = e.report();
    if (!line.empty()) std::cerr << "pfgen: " << one_line(line) << "\n";
  } catch (const std::exception& e) {
    // Not one of pfgen's: out of memory, or a library's error no room turned into its own.
    std::cerr << "pfgen: error: " << one_line(e.what()) << "\n";
  }
  return 1;
}
