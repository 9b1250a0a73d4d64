#include "estimate_command.hpp"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <iostream>
#include <optional>

#include "cli_options.hpp"
#include "output_paths.hpp"
#include "streamed_file.hpp"
#include "pfgen_runtime/gnuplot_plot.hpp"
#include "pfgen_support/shortest_double.hpp"

namespace pfgen::cli {
namespace {

using pfgen_runtime::RecordFilter;
using pfgen_runtime::RecordRun;

// Each number as the shortest text that reads back to it (to_chars), a missing one as an empty cell.
std::string number(double value) { return std::isnan(value) ? "" : pfgen_support::shortest_chars(value); }

// Per observation entry, the state it measures directly (a row e_i of C or A with no offset), for
// the plot; nothing for any other row. Samples, and continuous data given as rates (dy/dt, whose
// noise is B/sqrt(dt) about the state); increments are in other units.
std::vector<std::optional<std::size_t>> directly_observed(const Model& model, bool rates) {
  std::vector<std::optional<std::size_t>> out(model.p());
  // The rate as written C0 + C x or A0 + A x, undelayed (a delayed row sees the state h ago).
  const ObservationModel& observation = model.observation;
  if (!observation.rate().written_affine() || observation.delay_h() || !(observation.samples() || rates)) return out;
  const ExVector* offset = &observation.rate().affine()->A0;
  const ExMatrix* rows = &observation.rate().affine()->A;
  for (std::size_t i = 0; i < model.p(); ++i) {
    if (!offset->empty() && !(*offset)[i].is_zero()) continue;
    std::optional<std::size_t> state;
    bool unit = true;
    for (std::size_t j = 0; j < model.n() && unit; ++j) {
      const GiNaC::ex& c = (*rows)[i][j];
      if (c.is_zero()) continue;
      if (c.is_equal(GiNaC::ex(1)) && !state)
        state = j;
      else
        unit = false;
    }
    if (unit) out[i] = state;
  }
  return out;
}

std::vector<std::string> csv_columns(const RecordJob& job, const std::string& time, const std::vector<std::string>& observed,
                                     bool full) {
  std::vector<std::string> columns{time};
  for (const auto& y : observed) columns.push_back(y);
  const auto& states = job.model.state_names;
  for (const RecordFilter& filter : job.filters) {
    const std::string& f = filter.name;
    for (const auto& x : states) columns.push_back(f + "_m_" + x);
    for (const auto& x : states) columns.push_back(f + "_sd_" + x);
    if (full)
      for (std::size_t i = 0; i < states.size(); ++i)
        for (std::size_t j = i; j < states.size(); ++j) columns.push_back(f + "_P_" + states[i] + "_" + states[j]);
    for (const auto& y : observed) columns.push_back(f + "_predicted_" + y);
    for (const auto& y : observed) columns.push_back(f + "_innovation_" + y);
    for (const auto& y : observed) columns.push_back(f + "_normalized_" + y);
  }
  return columns;
}

void append_row(std::string& out, double t, const std::vector<double>& y, const std::vector<RecordRun>& runs,
                std::size_t n, bool full) {
  const std::size_t m_and_P = pfgen_runtime::filter_state_size(n);  // a delayed filter's x* and history follow
  out += number(t);
  for (double v : y) out += "," + number(v);
  for (const RecordRun& run : runs) {
    if (run.failed()) {  // stopped: no estimate from its row on
      const std::size_t cells = 2 * n + (full ? m_and_P - n : 0) + 3 * y.size();
      out.append(cells, ',');
      continue;
    }
    const std::vector<double>& s = run.state();
    for (std::size_t i = 0; i < n; ++i) out += "," + number(s[i]);
    for (std::size_t i = 0; i < n; ++i)
      out += "," + number(std::sqrt(std::max(0.0, s[n + pfgen_runtime::packed_diagonal(n, i)])));
    if (full)
      for (std::size_t k = n; k < m_and_P; ++k) out += "," + number(s[k]);
    for (double v : run.predicted()) out += "," + number(v);
    for (double v : run.innovation()) out += "," + number(v);
    for (double v : run.normalized()) out += "," + number(v);
  }
  out += "\n";
}

std::string plot_script(const std::string& plot_path, const std::string& csv_path, const RecordJob& job,
                        const std::vector<std::string>& columns, const std::vector<std::string>& observed) {
  const auto& states = job.model.state_names;
  const auto direct = directly_observed(job.model, job.run_options.continuous == pfgen_runtime::ContinuousData::Rates);
  auto column = [&](const std::string& name) {
    return std::to_string(std::find(columns.begin(), columns.end(), name) - columns.begin() + 1);
  };
  const int height = 260 * static_cast<int>(states.size()) + 40;
  std::string s = "set terminal " + pfgen_runtime::gnuplot_terminal(plot_path, 900, height) + "\nset output " +
                  pfgen_runtime::gnuplot_string(plot_path) +
                  "\nset datafile separator ','\nset datafile missing ''\nset key outside below\nset grid\n"
                  "set multiplot layout " + std::to_string(states.size()) + ",1 title " +
                  pfgen_runtime::gnuplot_string(job.model.name + ": estimates with 2-sigma bands") + "\n";
  const char* const colours[] = {"#1f77b4", "#d62728", "#2ca02c", "#9467bd", "#ff7f0e", "#8c564b"};
  for (std::size_t i = 0; i < states.size(); ++i) {
    s += "set xlabel 't'\nset ylabel " + pfgen_runtime::gnuplot_string(states[i]) + "\nplot ";
    std::string parts;
    for (std::size_t f = 0; f < job.filters.size(); ++f) {
      const std::string& name = job.filters[f].name;
      const std::string m = column(name + "_m_" + states[i]), sd = column(name + "_sd_" + states[i]);
      const std::string colour = colours[f % 6];
      parts += std::string(parts.empty() ? "" : ", ") + pfgen_runtime::gnuplot_string(csv_path) + " every ::1 using 1:($" +
               m + "-2*$" + sd + "):($" + m + "+2*$" + sd + ") with filledcurves fc rgb '" + colour +
               "' fs transparent solid 0.15 noborder notitle, " + pfgen_runtime::gnuplot_string(csv_path) +
               " every ::1 using 1:" + m + " with lines lc rgb '" + colour + "' lw 1.5 title " +
               pfgen_runtime::gnuplot_string(name);
    }
    for (std::size_t k = 0; k < observed.size(); ++k)
      if (direct[k] == i)
        parts += ", " + pfgen_runtime::gnuplot_string(csv_path) + " every ::1 using 1:" + column(observed[k]) +
                 " with points pt 7 ps 0.5 lc rgb 'black' title " + pfgen_runtime::gnuplot_string(observed[k]);
    s += parts + "\n";
  }
  return s + "unset multiplot\n";
}

std::string pad_to(const std::string& text, std::size_t width) {
  return text.size() >= width ? text : text + std::string(width - text.size(), ' ');
}

std::string scores_table(const std::vector<FilterScores>& scores, bool continuous) {
  std::string out;
  char line[400];
  std::snprintf(line, sizeof line, "%-16s %16s%s %11s %11s %18s %11s  %s\n", "filter", "log-likelihood",
                continuous ? "  log-density (increments)" : "", "innovations", "mean square", "95 % band",
                "Ljung-Box p", "verdict");
  out += line;
  for (const FilterScores& f : scores) {
    if (!f.stopped.empty()) {
      out += pad_to(f.filter, 16) + " stopped at " + f.stopped + "\n";
      continue;
    }
    const auto& s = f.summary;
    double p_value = 1;
    for (const auto& test : s.whiteness) p_value = std::min(p_value, test.p_value);
    char band[64], density[48] = "", ljung[32], likelihood[48];
    std::snprintf(band, sizeof band, "[%.4g, %.4g]", s.band_low, s.band_high);
    // Six decimals, as always, unless the value would print dozens of digits (a model far off its data).
    if (continuous)
      std::snprintf(density, sizeof density, " %25s", pfgen_support::fixed_unless_huge(f.increment_log_density).c_str());
    if (s.whiteness.empty())
      std::snprintf(ljung, sizeof ljung, "-");
    else
      std::snprintf(ljung, sizeof ljung, "%.3g", p_value);
    std::snprintf(likelihood, sizeof likelihood, "%16s", pfgen_support::fixed_unless_huge(s.log_likelihood).c_str());
    std::snprintf(line, sizeof line, "%-16s %s%s %11zu %11.4g %18s %11s  ", f.filter.c_str(), likelihood, density,
                  s.count, s.mean_square, band, ljung);
    out += line + s.verdict() + "\n";
  }
  return out;
}

}  // namespace

EstimateOutcome estimate(const EstimateOptions& options) {
  const RecordJobOptions& record = options.record;
  std::vector<NamedPath> inputs{{"the model file", record.model_path}};
  if (!record.data_rows) inputs.push_back({"--data", record.data_path});
  std::vector<NamedPath> outputs;
  if (!options.csv_path.empty()) outputs.push_back({"-o", options.csv_path});
  if (!options.plot_path.empty()) {
    if (options.csv_path.empty()) throw CliValueError("--plot: the plot reads the CSV; give -o FILE.csv too");
    outputs.push_back({"--plot", options.plot_path});
    outputs.push_back({"--plot's gnuplot script", pfgen_runtime::gnuplot_script_path(options.plot_path)});
    pfgen_runtime::gnuplot_terminal(options.plot_path, 1, 1);  // .png or .svg, before any work
    require_plotter();
  }
  if (record.model) inputs.erase(inputs.begin());
  check_distinct_outputs(inputs, outputs);
  for (const NamedPath& output : outputs) check_output_file(output);

  RecordJob job = prepare_record_job(record);
  const std::unique_ptr<pfgen_runtime::RecordSource> source = open_record(record, job);
  pfgen_runtime::RecordSource& reader = *source;
  const std::vector<std::string> observed = reader.observation_columns();
  const bool sampled = job.model.observation.is_sampled();
  const std::size_t n = job.model.n();

  std::optional<StreamedFile> csv;
  if (!options.csv_path.empty()) csv.emplace(options.csv_path);
  const bool writes_csv = csv || options.csv_text;
  const auto write_csv = [&](const std::string& text) {
    if (csv) csv->write(text);
    if (options.csv_text) *options.csv_text += text;
  };
  const std::vector<std::string> columns = csv_columns(job, reader.time_column(), observed, options.full_covariance);
  if (writes_csv) {
    std::string header;
    for (const auto& c : columns) header += (header.empty() ? "" : ",") + c;
    write_csv(header + "\n");
  }

  std::vector<double> y(observed.size());
  double t = 0, first = 0, last = 0;
  std::size_t rows = 0;
  std::vector<RecordRun> runs;
  std::vector<std::string> stopped;  // per run: where and why it failed, once it has
  std::string buffer;
  while (reader.next(t, y.data())) {
    const bool first_row = rows++ == 0;
    if (first_row) {
      first = t;
      const double t0 = prior_time(record, t, reader.path());
      runs.reserve(job.filters.size());
      for (const RecordFilter& filter : job.filters) runs.emplace_back(filter, job.values, t0, job.run_options);
      stopped.assign(runs.size(), "");
    }
    std::string row_failure;  // the first filter to fail at this row, which names the row's failure
    for (std::size_t k = 0; k < runs.size(); ++k) {
      RecordRun& run = runs[k];
      if (run.failed()) continue;
      const std::string where = reader.place() + ": ";
      bool ok = false;
      try {
        ok = run.advance(t, y.data());
      } catch (const std::invalid_argument& e) {
        throw CliValueError(where + e.what());
      }
      if (ok) continue;
      if (row_failure.empty()) row_failure = where + "the filter '" + run.filter_name() + "' failed: " + run.failure();
      // The last filter still running fails the command, as a lone filter always has; where every
      // filter fails at one row (a value too far off to score), the first one names it.
      if (std::all_of(runs.begin(), runs.end(), [](const RecordRun& r) { return r.failed(); }))
        throw CliValueError(row_failure);
      stopped[k] = reader.place() + ": " + run.failure();
    }
    last = t;
    if (writes_csv) {
      append_row(buffer, t, y, runs, n, options.full_covariance);
      if (buffer.size() > (1u << 20)) {
        write_csv(buffer);
        buffer.clear();
      }
    }
  }
  if (rows == 0) throw CliValueError(record.data_path + ": the record has a header but no rows");
  write_csv(buffer);
  if (csv) csv->finish();
  if (!options.plot_path.empty())
    pfgen_runtime::write_gnuplot_plot(options.plot_path, [&](const std::string& drawn) {
      return plot_script(drawn, options.csv_path, job, columns, observed);
    });

  EstimateOutcome outcome;
  outcome.time_column = reader.time_column();
  outcome.observation_columns = observed;
  outcome.columns = columns;
  for (std::size_t k = 0; k < runs.size(); ++k)
    outcome.scores.push_back(
        {runs[k].filter_name(), runs[k].scores().summary(), runs[k].increment_log_density(), stopped[k]});
  char line[300];
  std::string values;
  for (std::size_t k = 0; k < job.parameter_names.size(); ++k)
    values += (k ? ", " : "") + job.parameter_names[k] + " = " + pfgen_support::shortest_chars(job.values[k]);
  // Delayed observations: the delay, and the grid step the filters were generated for.
  const std::string delayed =
      job.grid_step ? " delayed by h = " + pfgen_support::shortest_double(job.model.observation.delay().to_double()) +
                          ", filter step " + pfgen_support::shortest_double(*job.grid_step)
                    : "";
  std::snprintf(line, sizeof line, "Record %s: %zu rows, t = %s to %s, %s observations", record.data_path.c_str(), rows,
                pfgen_support::shortest_chars(first).c_str(), pfgen_support::shortest_chars(last).c_str(),
                sampled ? "sampled" : record.data_form == "rates" ? "continuous (rates)" : "continuous (increments)");
  outcome.report = "Model " + job.model.name + (values.empty() ? "" : " at " + values) + "\n" + line + delayed + "\n\n" +
                   scores_table(outcome.scores, !sampled);
  return outcome;
}

int run_estimate(const EstimateOptions& options) {
  const EstimateOutcome outcome = estimate(options);
  std::cout << outcome.report;
  if (!options.csv_path.empty()) std::cout << "Wrote " << options.csv_path << "\n";
  if (!options.plot_path.empty()) std::cout << "Wrote " << options.plot_path << "\n";
  return 0;
}

}  // namespace pfgen::cli
