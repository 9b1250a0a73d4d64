// pfgen::api::Model::estimate and Model::fit: `pfgen estimate` and `pfgen fit` run in this
// process over a CSV file or a record in memory, their outputs kept in memory.
#include <cmath>

#include "api_impl.hpp"
#include "cli_options.hpp"
#include "estimate_command.hpp"
#include "fit_command.hpp"

namespace pfgen::api {
namespace {

// RecordOptions as the commands' record options, which the commands' own code then checks. The
// in-memory rows are read in place from `options`, which outlives the job.
cli::RecordJobOptions record_options(const pfgen::Model& model, const RecordOptions& options) {
  cli::RecordJobOptions out;
  out.model = &model;
  out.model_path = model.source;
  out.quiet = true;
  check_no_nul("--data", options.data_path);
  if (options.data) {
    out.data_path = options.data_path.empty() ? "<data>" : options.data_path;
    out.data_header = &options.data->columns;
    out.data_rows = &options.data->rows;
  } else if (options.data_path.empty()) {
    throw cli::CliValueError("--data: give the record: a CSV file's path, or the data in memory");
  } else {
    out.data_path = options.data_path;
  }
  check_no_nul("--time-column", options.time_column);
  for (const std::string& name : options.columns) check_no_nul("--columns", name);
  check_no_nul("--data-form", options.data_form);
  if (options.t0) check_number_option("--t0", *options.t0);
  for (const auto& [option, text] : {std::pair{"--cache-dir", &options.cache_dir}, {"--compiler", &options.compiler}})
    check_no_nul(option, *text);
  out.time_column = options.time_column;
  out.columns = options.columns;
  out.data_form = options.data_form;
  out.substeps = options.substeps;
  out.t0 = options.t0;
  out.assignments = assignment_texts(options.parameters);
  out.cache_dir = options.cache_dir;
  out.compiler = options.compiler;
  return out;
}

// A bound as `--bounds name=low:high`'s text: an infinite end (of its own side) left empty.
std::string bound_text(const Bound& bound) {
  check_no_nul("--bounds", bound.name);
  const auto end = [&](double value, double open) {
    if (value == open) return std::string();
    check_number_option("--bounds " + bound.name, value);
    return number_text(value);
  };
  return bound.name + "=" + end(bound.low, -HUGE_VAL) + ":" + end(bound.high, HUGE_VAL);
}

RecordScores scores_of(const cli::FilterScores& filter, bool continuous) {
  const pfgen_runtime::InnovationSummary& s = filter.summary;
  RecordScores out;
  out.name = filter.filter;
  out.log_likelihood = s.log_likelihood;
  out.increment_log_density = continuous ? filter.increment_log_density : std::nan("");
  out.stopped = filter.stopped;
  out.count = s.count;
  out.mean_square = s.mean_square;
  out.band_low = s.band_low;
  out.band_high = s.band_high;
  for (const pfgen_runtime::LjungBox& test : s.whiteness) {
    out.ljung_box_lags.push_back(test.lags);
    out.ljung_box_statistic.push_back(test.statistic);
    out.ljung_box_p.push_back(test.p_value);
  }
  out.consistent = s.consistent();
  out.white = s.white();
  out.verdict = s.verdict();
  return out;
}

}  // namespace

RecordData RecordData::from_arrays(const Vector& times, const Matrix& values, const std::vector<std::string>& names,
                                   const std::string& time_column) {
  if (values.size() != times.size())
    throw Error("--data: " + std::to_string(times.size()) + " times but " + std::to_string(values.size()) +
                " rows of observations");
  const std::size_t p = values.empty() ? names.size() : values.front().size();
  if (!names.empty() && names.size() != p)
    throw Error("--data: " + std::to_string(names.size()) + " names for " + std::to_string(p) + " observation columns");
  RecordData out;
  out.columns.push_back(time_column);
  for (std::size_t i = 0; i < p; ++i) out.columns.push_back(names.empty() ? "y" + std::to_string(i + 1) : names[i]);
  for (std::size_t k = 0; k < times.size(); ++k) {
    if (values[k].size() != p)
      throw Error("--data: row " + std::to_string(k + 1) + " has " + std::to_string(values[k].size()) +
                  " observations, the first row " + std::to_string(p));
    Vector row{times[k]};
    row.insert(row.end(), values[k].begin(), values[k].end());
    out.rows.push_back(std::move(row));
  }
  return out;
}

EstimateResult Model::estimate(const EstimateOptions& options) const {
  return guarded([&] {
    cli::EstimateOptions command;
    command.record = record_options(impl_->model, options.record);
    for (const std::string& name : options.filters) check_no_nul("--filters", name);
    command.record.filters = options.filters;
    command.full_covariance = options.full_covariance;
    EstimateResult out;
    if (options.series) command.csv_text = &out.csv;
    const cli::EstimateOutcome outcome = cli::estimate(command);
    out.report = outcome.report;
    const bool continuous = !impl_->model.observation.is_sampled();
    for (const cli::FilterScores& filter : outcome.scores) out.filters.push_back(scores_of(filter, continuous));
    out.time_column = outcome.time_column;
    out.observation_columns = outcome.observation_columns;
    if (options.series) {
      out.columns = outcome.columns;
      out.series = csv_series(out.csv, out.columns.size());
    }
    return out;
  });
}

FitResult Model::fit(const FitOptions& options) const {
  return guarded([&] {
    cli::FitOptions command;
    command.record = record_options(impl_->model, options.record);
    check_no_nul("--filter", options.filter);
    command.filter = options.filter;
    for (const std::string& name : options.estimate) check_no_nul("--estimate", name);
    command.estimate = options.estimate;
    for (const Bound& bound : options.bounds) command.bounds.push_back(bound_text(bound));
    command.starts = options.starts;
    command.seed = options.seed;
    command.profile = options.profile;
    const cli::FitOutcome outcome = cli::fit(command);
    FitResult out;
    out.report = outcome.report;
    out.json = outcome.json;
    const cli::FitResult& r = outcome.result;
    out.converged = r.converged;
    out.stop_reason = r.stop_reason;
    out.log_likelihood = r.log_likelihood;
    out.aic = outcome.aic;
    out.evaluations = r.evaluations;
    out.at_edge = r.at_edge;
    out.note = r.information_note;
    for (const cli::FittedParameter& p : r.parameters)
      out.parameters.push_back({p.name, p.estimate, p.std_error, p.wald_low, p.wald_high, p.profile_low,
                                p.profile_high, p.at_bound, p.profile_low_is_edge, p.profile_high_is_edge});
    return out;
  });
}

}  // namespace pfgen::api
