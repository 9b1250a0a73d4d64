#include "record_job.hpp"

#include <iostream>

#include "cli_options.hpp"
#include "plugin_loading.hpp"
#include "pfgen/codegen/backends/cpp/simulation_plugin.hpp"
#include "pfgen/derivation/filter_equations.hpp"
#include "pfgen/model/delay_grid.hpp"
#include "pfgen/model/model_filters.hpp"
#include "pfgen/model/yaml_model_loader.hpp"
#include "pfgen_runtime/record_arrays.hpp"
#include "pfgen_runtime/record_reader.hpp"
#include "pfgen_support/shortest_double.hpp"

namespace pfgen::cli {
namespace {

bool has_time(const std::vector<Polynomial>& polynomials, const GiNaC::symbol& t) {
  for (const Polynomial& polynomial : polynomials)
    for (const auto& term : polynomial.terms())
      if (term.second.has(t)) return true;
  return false;
}

// Whether a filter's equations (or the observation noise B, which the scores read) depend on t.
bool depends_on_time(const Model& model, const FilterEquations& eq) {
  const GiNaC::symbol& t = model.time;
  for (const auto* rows : {&eq.gain, &eq.P_gain})
    for (const auto& row : *rows)
      if (has_time(row, t)) return true;
  for (const auto* part : {&eq.m_drift, &eq.predicted_observation, &eq.P_moment, &eq.P_diffusion, &eq.P_correction,
                           &eq.P_euler, &eq.x_star_drift})
    if (has_time(*part, t)) return true;
  for (const FilterDefinition& definition : eq.definitions)
    if (definition.value.has(t)) return true;
  for (const auto& row : model.observation.rate().noise())
    for (const GiNaC::ex& entry : row)
      if (entry.has(t)) return true;
  return false;
}

// A delayed model's filters are generated for one grid step, the record's: its first interval
// (from the prior's time to the first row, or between the first two rows) over --substeps. The
// delay must be a whole number of such steps, and, since a delayed filter counts its own grid
// from the prior (tau_k = k dt, its pre-history before), coefficients that depend on t need the
// prior at t = 0. RecordRun checks that every later interval equals the first.
double delayed_grid_step(const RecordJobOptions& options, const RecordJob& job,
                         const std::vector<FilterEquations>& filters) {
  const Model& model = job.model;
  const std::unique_ptr<pfgen_runtime::RecordSource> source = open_record(options, job);
  std::vector<double> row(source->observation_columns().size());
  double first = 0, second = 0;
  if (!source->next(first, row.data())) throw CliValueError(options.data_path + ": the record has a header but no rows");
  const double t0 = prior_time(options, first, source->path());
  double interval = first - t0;
  if (!(interval > 0)) {
    if (!source->next(second, row.data()))
      throw CliValueError(source->place() +
                          ": delayed observations need the record's step, and the record has one row, at the prior's "
                          "time");
    interval = second - first;
  }
  const double step = interval / static_cast<double>(options.substeps);
  const DelaySteps steps = delay_steps(model.observation.delay(), step);
  // The first interval from the prior's time is --t0's when given: the message says so.
  const std::string from = first > t0 && options.t0 ? ", from the prior's time (--t0) to the first row" : "";
  if (!steps.problem.empty())
    throw CliValueError(source->place() + ": the record's step " + pfgen_support::shortest_double(interval) +
                        (options.substeps > 1 ? " over --substeps " + std::to_string(options.substeps) : "") +
                        " (the delayed filters' grid step)" + from + ": " + steps.problem);
  // The grid step is h / D exactly (the interval's decimals, 3.01 - 3, are not): so the same step
  // in any record gives the same plugin, and every interval is compared with it.
  const double dt =
      steps.steps > 0 ? (model.observation.delay() / GiNaC::numeric(static_cast<long>(steps.steps))).to_double() : step;
  if (t0 != 0)
    for (const FilterEquations& eq : filters)
      if (depends_on_time(model, eq))
        throw CliValueError(source_place(model) + "the filter '" + eq.name +
                            "' depends on t, and a delayed filter counts its grid from the prior's time as t = 0: "
                            "start the record at t = 0 (the prior's time is " +
                            pfgen_support::shortest_double(t0) + (options.t0 ? ", --t0" : ", the first row's") + ")");
  return dt;
}

}  // namespace

RecordJob prepare_record_job(const RecordJobOptions& options) {
  RecordJob job;
  job.model = options.model ? *options.model : load_model_file(options.model_path);
  const Model& model = job.model;
  if (options.data_form != "increments" && options.data_form != "rates")
    throw CliValueError("--data-form: '" + options.data_form + "' is neither increments nor rates");
  if (options.substeps < 1 || options.substeps > pfgen_runtime::kMaxRowSubsteps)
    throw CliValueError("--substeps: " + std::to_string(options.substeps) + " is not between 1 and " +
                        std::to_string(pfgen_runtime::kMaxRowSubsteps));
  // Samples are rows y_k, predicted between in the model's own sub-steps: the continuous data's
  // options would be ignored, so they are refused rather than accepted for nothing.
  if (model.observation.is_sampled() && options.substeps != 1)
    throw CliValueError("--substeps: sampled observations are predicted in the model's sub-steps "
                        "(observation.sampled.substeps per period); --substeps is for continuous data");
  if (model.observation.is_sampled() && options.data_form != "increments")
    throw CliValueError("--data-form: sampled observations are read as samples y_k; --data-form " + options.data_form +
                        " is for continuous data");
  job.run_options.continuous =
      options.data_form == "rates" ? pfgen_runtime::ContinuousData::Rates : pfgen_runtime::ContinuousData::Increments;
  job.run_options.substeps = options.substeps;

  // --set: checked as simulate checks it, on a copy; the plugin keeps the model's own defaults, so
  // that any values reuse it.
  Model with_values = model;
  apply_parameter_assignments(with_values, options.assignments);
  for (const Parameter& parameter : with_values.parameters) {
    job.parameter_names.push_back(parameter.name);
    job.values.push_back(parameter.default_value.to_double());
  }

  std::vector<FilterEquations> filters;
  for (const std::string& name : options.filters.empty() ? default_filter_names(model) : options.filters)
    filters.push_back(derive_named_filter(model, name));
  if (model.observation.is_delayed()) job.grid_step = delayed_grid_step(options, job, filters);
  const std::string source = codegen::generate_simulation_plugin(model, filters, job.grid_step);
  toolchain::PluginBuildOptions build_options;
  build_options.cache_dir = options.cache_dir;
  build_options.compiler = options.compiler;
  if (!options.quiet)
    build_options.before_compile = [&](const std::string&) {
      std::cerr << "pfgen: compiling the filters (" << filters.size() << ")\n";
    };
  toolchain::PluginBuild build;
  job.plugin.emplace(load_plugin(source, build_options, !options.quiet, build));
  job.filters = job.plugin->record_filters();
  return job;
}

std::unique_ptr<pfgen_runtime::RecordSource> open_record(const RecordJobOptions& options, const RecordJob& job) {
  if (options.data_rows)
    return std::make_unique<pfgen_runtime::RecordArrays>(options.data_path, *options.data_header, *options.data_rows,
                                                         options.time_column, options.columns, job.model.p());
  return std::make_unique<pfgen_runtime::RecordReader>(options.data_path, options.time_column, options.columns,
                                                       job.model.p());
}

double prior_time(const RecordJobOptions& options, double first_time, const std::string& data_path) {
  if (!options.t0) return first_time;
  if (!(*options.t0 <= first_time))
    throw CliValueError("--t0: " + std::to_string(*options.t0) + " comes after the first row of " + data_path +
                        " (t = " + std::to_string(first_time) + ")");
  return *options.t0;
}

Record read_record(const RecordJobOptions& options, const RecordJob& job) {
  const std::unique_ptr<pfgen_runtime::RecordSource> source = open_record(options, job);
  Record record;
  record.p = source->observation_columns().size();
  record.line_word = source->line_word();
  record.path = source->path();
  std::vector<double> row(record.p);
  double t = 0;
  while (source->next(t, row.data())) {
    record.times.push_back(t);
    record.values.insert(record.values.end(), row.begin(), row.end());
    record.lines.push_back(source->line());
  }
  if (record.times.empty()) throw CliValueError(options.data_path + ": the record has a header but no rows");
  return record;
}

}  // namespace pfgen::cli
