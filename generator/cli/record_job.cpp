#include "record_job.hpp"

#include <iostream>

#include "cli_options.hpp"
#include "plugin_loading.hpp"
#include "pfgen/codegen/backends/cpp/simulation_plugin.hpp"
#include "pfgen/derivation/filter_equations.hpp"
#include "pfgen/model/model_filters.hpp"
#include "pfgen/model/yaml_model_loader.hpp"
#include "pfgen_runtime/record_arrays.hpp"
#include "pfgen_runtime/record_reader.hpp"

namespace pfgen::cli {

RecordJob prepare_record_job(const RecordJobOptions& options) {
  RecordJob job;
  job.model = options.model ? *options.model : load_model_file(options.model_path);
  const Model& model = job.model;
  if (model.observation.is_delayed())
    throw CliValueError(model.source + ": observation.delay: a record is not read with delayed observations yet");
  if (options.data_form != "increments" && options.data_form != "rates")
    throw CliValueError("--data-form: '" + options.data_form + "' is neither increments nor rates");
  if (options.substeps < 1 || options.substeps > 1000000)
    throw CliValueError("--substeps: " + std::to_string(options.substeps) + " is not between 1 and 1000000");
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
  const std::string source = codegen::generate_simulation_plugin(model, filters, std::nullopt);
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
