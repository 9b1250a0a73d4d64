#pragma once
// What `estimate` and `fit` share: the model, its filters compiled into the simulation plugin (the
// same source and cache as `simulate`'s, the model's defaults compiled in, so that every parameter
// value is a runtime argument and a new value needs no compiler), the parameter values of the job
// (the model's defaults with --set's), and the record read in full or row by row.
#include <memory>
#include <optional>
#include <string>
#include <vector>

#include "pfgen/model/model.hpp"
#include "pfgen/toolchain/plugin_compiler.hpp"
#include "pfgen_runtime/record_filter.hpp"
#include "pfgen_runtime/record_source.hpp"
#include "pfgen_runtime/record_run.hpp"
#include "pfgen_runtime/simulation_plugin.hpp"

namespace pfgen::cli {

struct RecordJobOptions {
  std::string model_path;
  const Model* model = nullptr;  // the API's: a model already loaded
  std::string data_path;
  // The API's: the record in memory (a header naming the columns, and the rows), read instead of
  // a file; data_path then names it in messages and reports. Read in place: they outlive the job.
  const std::vector<std::string>* data_header = nullptr;
  const std::vector<std::vector<double>>* data_rows = nullptr;
  std::string time_column = "t";
  std::vector<std::string> columns;       // observation columns in the model's order; empty: all others
  std::vector<std::string> filters;       // empty: the model's defaults
  std::string data_form = "increments";   // continuous data: increments | rates
  std::size_t substeps = 1;               // continuous data: filter steps per data interval
  std::optional<double> t0;               // where the prior holds; default: the first row's time
  std::vector<std::string> assignments;   // --set name=value
  std::string cache_dir, compiler;
  bool quiet = false;
};

struct RecordJob {
  Model model;
  std::optional<pfgen_runtime::SimulationPlugin> plugin;
  std::vector<pfgen_runtime::RecordFilter> filters;  // in the order asked for
  std::vector<std::string> parameter_names;
  std::vector<double> values;  // the job's parameter values, in the model's order
  pfgen_runtime::RecordRunOptions run_options;
  // Delayed observations: the grid step the filters were generated for (the record's first
  // interval over --substeps); empty otherwise.
  std::optional<double> grid_step;
};

// Loads the model, derives the filters, builds or finds the plugin and loads it (for delayed
// observations, generated for the record's step, read from its first rows). CliValueError for a
// bad option, or a delayed model whose record's step does not divide the delay.
RecordJob prepare_record_job(const RecordJobOptions& options);

// The record's rows, from the file or from memory, its columns checked against the model.
std::unique_ptr<pfgen_runtime::RecordSource> open_record(const RecordJobOptions& options, const RecordJob& job);

// Every row of a record in memory (fit evaluates the likelihood many times over it).
struct Record {
  std::vector<double> times;
  std::vector<double> values;  // row-major, p per row
  std::vector<std::size_t> lines;  // each row's line in the file, or its number among the rows in memory
  std::string line_word = "line";  // what `lines` counts, in messages: "line" or "row"
  std::string path;                // the record's name in messages: the file's path, or the arrays' name
  // Row `row` as a message places it, as the record's source does: "nile.csv:12", "<data> row 3".
  std::string place(std::size_t row) const { return pfgen_runtime::record_place(path, line_word, lines[row]); }
  std::size_t p = 0;
};
Record read_record(const RecordJobOptions& options, const RecordJob& job);

// The prior's time: --t0, else the first row's time (which must not come before it).
double prior_time(const RecordJobOptions& options, double first_time, const std::string& data_path);

}  // namespace pfgen::cli
