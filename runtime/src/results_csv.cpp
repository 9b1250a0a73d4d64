#include "pfgen_runtime/results_csv.hpp"

#include <cmath>
#include <functional>
#include <memory>
#include <stdexcept>

#include "pfgen_runtime/statistics.hpp"
#include "pfgen_support/atomic_file.hpp"
#include "pfgen_support/shortest_double.hpp"

namespace pfgen_runtime {

namespace {

struct Column {
  std::string name;
  std::function<double(Eigen::Index row)> value;  // NaN: an empty cell
};

// Header and cells come from one list, so they cannot disagree.
std::vector<Column> make_columns(const MonteCarloResult& result, const std::vector<std::string>& state_names) {
  if (state_names.size() != result.n) throw std::invalid_argument("results CSV: need one name per state component");
  const MonteCarloSeries& series = result.series;
  const auto n = static_cast<Eigen::Index>(result.n);
  std::vector<Column> columns;
  columns.push_back({"t", [&series](Eigen::Index r) { return series.t[static_cast<std::size_t>(r)]; }});
  for (Eigen::Index i = 0; i < n; ++i)
    columns.push_back({"truth_" + state_names[i], [&series, i](Eigen::Index r) { return series.truth(r, i); }});
  for (std::size_t f = 0; f < result.filters.size(); ++f) {
    const std::string& name = result.filters[f].name;
    const FilterSeries& filter = series.filters[f];
    for (Eigen::Index i = 0; i < n; ++i)
      columns.push_back({name + "_m_" + state_names[i], [&filter, i](Eigen::Index r) { return filter.m(r, i); }});
    for (Eigen::Index i = 0; i < n; ++i)
      columns.push_back(
          {name + "_P_" + state_names[i], [&filter, i](Eigen::Index r) { return filter.P_diagonal(r, i); }});
    for (Eigen::Index i = 0; i < n; ++i)
      columns.push_back({name + "_err_" + state_names[i],
                         [&series, &filter, i](Eigen::Index r) { return series.truth(r, i) - filter.m(r, i); }});
  }
  auto add_statistics = [&columns, n, &state_names](const std::string& prefix, const SeriesStatistics& s) {
    for (Eigen::Index i = 0; i < n; ++i) {
      const std::string stem = prefix + state_names[i];
      columns.push_back({stem + "_mean", [&s, i](Eigen::Index r) { return s.mean(r, i); }});
      columns.push_back({stem + "_q05", [&s, i](Eigen::Index r) { return s.q05(r, i); }});
      columns.push_back({stem + "_q50", [&s, i](Eigen::Index r) { return s.q50(r, i); }});
      columns.push_back({stem + "_q95", [&s, i](Eigen::Index r) { return s.q95(r, i); }});
    }
  };
  auto add_alive = [&columns](const std::string& name, const std::vector<std::size_t>& alive) {
    columns.push_back({name, [&alive](Eigen::Index r) { return static_cast<double>(alive[static_cast<std::size_t>(r)]); }});
  };
  add_statistics("truth_", series.truth_statistics);
  add_alive("truth_alive", series.truth_alive);
  for (std::size_t f = 0; f < result.filters.size(); ++f) {
    add_statistics(result.filters[f].name + "_err_", series.filters[f].error);
    add_alive(result.filters[f].name + "_alive", series.filters[f].alive);
  }
  // The particle reference, after every other column (their positions stay): the shown run's
  // m_ref and x - m_ref, the RMS of x - m_ref over the runs; per filter the shown run's m - m_ref
  // and its RMS over the runs.
  if (result.reference) {
    for (Eigen::Index i = 0; i < n; ++i) {
      const std::string& x = state_names[static_cast<std::size_t>(i)];
      columns.push_back({"reference_m_" + x, [&series, i](Eigen::Index r) { return series.reference_m(r, i); }});
      columns.push_back({"reference_err_" + x,
                         [&series, i](Eigen::Index r) { return series.truth(r, i) - series.reference_m(r, i); }});
      columns.push_back(
          {"reference_err_" + x + "_rms", [&series, i](Eigen::Index r) { return series.reference_error_rms(r, i); }});
    }
    for (std::size_t f = 0; f < result.filters.size(); ++f) {
      const FilterSeries& filter = series.filters[f];
      for (Eigen::Index i = 0; i < n; ++i) {
        const std::string stem = result.filters[f].name + "_dref_" + state_names[static_cast<std::size_t>(i)];
        columns.push_back({stem, [&filter, i](Eigen::Index r) { return filter.reference_distance(r, i); }});
        columns.push_back({stem + "_rms", [&filter, i](Eigen::Index r) { return filter.reference_distance_rms(r, i); }});
      }
    }
  }
  // Last, so that every column before keeps its position: per filter the RMS of its error over the
  // runs alive, and its mean NEES per state dimension with the 95 % band for the runs it is over.
  for (std::size_t f = 0; f < result.filters.size(); ++f) {
    const FilterSeries& filter = series.filters[f];
    const std::string& name = result.filters[f].name;
    for (Eigen::Index i = 0; i < n; ++i)
      columns.push_back({name + "_err_" + state_names[static_cast<std::size_t>(i)] + "_rms",
                         [&filter, i](Eigen::Index r) { return filter.error_rms(r, i); }});
    columns.push_back({name + "_nees", [&filter](Eigen::Index r) { return filter.nees(r, 0); }});
    // The band changes only with the count of runs: computed once per count.
    auto bands = std::make_shared<std::vector<NeesBand>>();
    NeesBand last{0, 0};
    std::size_t last_runs = 0;
    for (std::size_t r = 0; r < filter.nees_runs.size(); ++r) {
      if (r == 0 || filter.nees_runs[r] != last_runs) last = nees_band(filter.nees_runs[r], result.n);
      last_runs = filter.nees_runs[r];
      bands->push_back(last);
    }
    columns.push_back({name + "_nees_low", [bands](Eigen::Index r) { return (*bands)[static_cast<std::size_t>(r)].low; }});
    columns.push_back(
        {name + "_nees_high", [bands](Eigen::Index r) { return (*bands)[static_cast<std::size_t>(r)].high; }});
  }
  return columns;
}

// Shortest decimal that reads back to the same double (std::to_chars); empty for NaN and inf.
void append_number(std::string& out, double value) {
  if (std::isfinite(value)) out += pfgen_support::shortest_chars(value);
}

void append_field(std::string& out, const std::string& field) {
  if (field.find_first_of(",\"\r\n") == std::string::npos) {
    out += field;
    return;
  }
  out += '"';
  for (char c : field) {
    if (c == '"') out += '"';
    out += c;
  }
  out += '"';
}

}  // namespace

std::vector<std::string> results_csv_columns(const MonteCarloResult& result,
                                             const std::vector<std::string>& state_names) {
  std::vector<std::string> names;
  for (const Column& column : make_columns(result, state_names)) names.push_back(column.name);
  return names;
}

std::string format_results_csv(const MonteCarloResult& result, const std::vector<std::string>& state_names) {
  const std::vector<Column> columns = make_columns(result, state_names);
  std::string out;
  for (std::size_t c = 0; c < columns.size(); ++c) {
    if (c > 0) out += ',';
    append_field(out, columns[c].name);
  }
  out += '\n';
  const auto rows = static_cast<Eigen::Index>(result.series.t.size());
  for (Eigen::Index r = 0; r < rows; ++r) {
    for (std::size_t c = 0; c < columns.size(); ++c) {
      if (c > 0) out += ',';
      append_number(out, columns[c].value(r));
    }
    out += '\n';
  }
  return out;
}

namespace {

void write_csv(const std::string& what, const std::string& path, const std::string& text) {
  try {
    pfgen_support::write_file_atomically(path, text);
  } catch (const pfgen_support::AtomicWriteError& e) {
    if (e.stage() == pfgen_support::AtomicWriteError::Stage::write)
      throw std::runtime_error("cannot write the " + what + " '" + path + "'");
    throw std::runtime_error("cannot write the " + what + " '" + path + "' (renaming " + e.temporary() + " failed)");
  }
}

// A criterion value: "inf" where J is infinite on purpose, else as append_number.
void append_criterion_number(std::string& out, double value) {
  if (std::isinf(value) && value > 0) out += "inf";
  else append_number(out, value);
}

}  // namespace

void write_results_csv(const std::string& path, const MonteCarloResult& result,
                       const std::vector<std::string>& state_names) {
  write_csv("results CSV", path, format_results_csv(result, state_names));
}

std::string format_criterion_csv(const MonteCarloResult& result) {
  if (!result.criterion) throw std::invalid_argument("criterion CSV: the result has no criterion");
  std::string out =
      "filter,epsilon,runs,completed,J,J_se,ess,mean_integral,mean_integral_se,stopped,first_stop_t,completed_J,"
      "completed_J_se,completed_ess,completed_mean_integral,completed_mean_integral_se\n";
  for (const FilterStatistics& filter : result.filters) {
    const CriterionStatistics& c = *filter.criterion;
    append_field(out, filter.name);
    const double cells[] = {c.epsilon,
                            static_cast<double>(c.all.runs),
                            static_cast<double>(c.completed.runs),
                            c.all.J,
                            c.all.J_se,
                            c.all.ess,
                            c.all.mean_integral,
                            c.all.mean_integral_se,
                            static_cast<double>(c.stopped.count()),
                            c.stopped.earliest(),
                            c.completed.J,
                            c.completed.J_se,
                            c.completed.ess,
                            c.completed.mean_integral,
                            c.completed.mean_integral_se};
    for (double value : cells) {
      out += ',';
      append_criterion_number(out, value);
    }
    out += '\n';
  }
  return out;
}

void write_criterion_csv(const std::string& path, const MonteCarloResult& result) {
  write_csv("criterion CSV", path, format_criterion_csv(result));
}

namespace {

// The runs of a run-ordered event list, asked in increasing run order beside another such list.
class RunMarks {
 public:
  explicit RunMarks(const std::vector<RunEvent>& marked) : marked_(marked) {}
  bool has(std::size_t run) {
    while (next_ < marked_.size() && marked_[next_].run < run) ++next_;
    return next_ < marked_.size() && marked_[next_].run == run;
  }

 private:
  const std::vector<RunEvent>& marked_;
  std::size_t next_ = 0;
};

}  // namespace

std::string format_stops_csv(const MonteCarloResult& result) {
  std::string out = "source,event,run,t\n";
  auto row = [&out](const std::string& source, const char* event, const RunEvent& e) {
    append_field(out, source);
    out += std::string(",") + event + "," + std::to_string(e.run) + ",";
    append_number(out, e.t);
    out += '\n';
  };
  // A truth whose G lost definiteness is also among the truth's divergences: one row, named so.
  RunMarks covariance(result.truth_covariance_losses.events);
  for (const RunEvent& e : result.truth_divergences.events)
    row("truth", covariance.has(e.run) ? "covariance" : "diverged", e);
  for (const FilterStatistics& filter : result.filters) {
    // A moment filter's stop where its moments left the realisable set is named so.
    RunMarks unrealisable(filter.unrealisable.events);
    for (const RunEvent& e : filter.divergences.events)
      row(filter.name, unrealisable.has(e.run) ? "unrealisable" : "diverged", e);
    for (const RunEvent& e : filter.psd_losses.events) row(filter.name, "psd_loss", e);
  }
  // The particle reference: runs where every particle diverged (source "reference").
  if (result.reference)
    for (const RunEvent& e : result.reference->stopped.events) row("reference", "stopped", e);
  return out;
}

void write_stops_csv(const std::string& path, const MonteCarloResult& result) {
  write_csv("stops CSV", path, format_stops_csv(result));
}

}  // namespace pfgen_runtime
