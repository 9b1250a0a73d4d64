#include "simulation_settings_merge.hpp"

#include <cmath>
#include <type_traits>
#include <utility>
#include <vector>

#include "cli_options.hpp"
#include "simulation_settings.hpp"
#include "pfgen_support/shortest_double.hpp"

namespace pfgen::cli {
namespace {

// Shortest round-trip text, fixed or scientific whichever is shorter ("20", not "2e+01").
std::string number_text(double value) { return pfgen_support::shortest_chars(value); }

// A default as messages write it: "0.001", "100", "auto".
template <class T>
std::string value_text(const T& value) {
  if constexpr (std::is_floating_point_v<T>) return number_text(value);
  else if constexpr (std::is_integral_v<T>) return std::to_string(value);
  else return value;
}

double parse_double(const std::string& option, const std::string& text) {
  std::size_t used = 0;
  double value = 0;
  try {
    value = std::stod(text, &used);
  } catch (const std::exception&) {
    used = 0;
  }
  if (used == 0 || used != text.size() || !std::isfinite(value))
    throw CliValueError(option + ": '" + text + "' is not a finite number");
  return value;
}

// The model file's report times and windows are defaults for its own horizon: with a shorter
// --T, those beyond it are left out (said on stderr) rather than refused, so that a quick
// `--T 1` run of any model just works. Within one source (the file alone) they stay errors.
// Returns the note on what was left out.
template <class Item, class End, class Text>
std::string drop_beyond_horizon(std::vector<Item>& items, double T, bool T_from_command_line, const std::string& field,
                                End end, Text text) {
  if (!T_from_command_line) return {};
  std::vector<Item> kept;
  std::string dropped;
  for (const Item& item : items) {
    if (end(item) <= T) kept.push_back(item);
    else dropped += (dropped.empty() ? "" : ", ") + text(item);
  }
  items = std::move(kept);
  if (dropped.empty()) return {};
  return "pfgen: note: simulation." + field + " " + dropped + " beyond --T " + number_text(T) + " left out\n";
}

// Where a value came from, for the merge to record.
enum class Origin { command_line, model_file, pfgen_default };

// Writes the merged values and their places, one field at a time.
class Merge {
 public:
  Merge(const SimulationSection& file, MergedSimulation& out) : file_(file), out_(out) {}

  // The command line's value, else the file's, else pfgen's default.
  template <class T>
  void take(const std::string& field, const std::string& option, std::optional<T> SimulationSection::*member,
            const std::optional<T>& command_line, const T& fallback) {
    if (pick(field, option, member, command_line)) return;
    out_.values.*member = fallback;
    place(field, option, Origin::pfgen_default, value_text(fallback));
  }

  // For a field pfgen has no default for: unset when neither gives it, `absent` in messages.
  template <class T>
  void take_given(const std::string& field, const std::string& option, std::optional<T> SimulationSection::*member,
                  const std::optional<T>& command_line, const std::string& absent) {
    if (!pick(field, option, member, command_line)) place(field, option, Origin::pfgen_default, absent);
  }

  void place(const std::string& field, const std::string& option, Origin origin, const std::string& default_text) {
    switch (origin) {
      case Origin::command_line: out_.places[field] = option; break;
      case Origin::model_file: out_.places[field] = file_.location_of(field) + ": simulation." + field; break;
      case Origin::pfgen_default: out_.places[field] = option + " (default " + default_text + ")"; break;
    }
  }

 private:
  // The command line's value, else the file's; false when neither gives one.
  template <class T>
  bool pick(const std::string& field, const std::string& option, std::optional<T> SimulationSection::*member,
            const std::optional<T>& command_line) {
    if (!command_line && !(file_.*member)) return false;
    out_.values.*member = command_line ? command_line : file_.*member;
    place(field, option, command_line ? Origin::command_line : Origin::model_file, {});
    return true;
  }

  const SimulationSection& file_;
  MergedSimulation& out_;
};

// A list the command line gives as text, or the file as a list (empty: not given).
template <class Item>
Origin list_origin(const std::optional<std::string>& command_line, const std::vector<Item>& file) {
  if (command_line) return Origin::command_line;
  return file.empty() ? Origin::pfgen_default : Origin::model_file;
}

}  // namespace

MergedSimulation merge_simulation_settings(const Model& model, const SimulationOverrides& cli) {
  const SimulationSection& file = model.simulation;
  if (!cli.T && !file.T) throw CliValueError("--T: no horizon; give --T or simulation.T in " + model.source);
  MergedSimulation out;
  SimulationSection& s = out.values;
  Merge merge(file, out);
  merge.take_given<double>("T", "--T", &SimulationSection::T, cli.T, "none");  // given: refused above if not
  // pfgen's defaults (main.cpp's help texts name them too).
  merge.take<double>("dt", "--dt", &SimulationSection::dt, cli.dt, 1e-3);
  merge.take<std::size_t>("runs", "--runs", &SimulationSection::runs, cli.runs, 100);
  merge.take<std::uint64_t>("seed", "--seed", &SimulationSection::seed, cli.seed, 1);
  merge.take<std::string>("scheme", "--scheme", &SimulationSection::scheme, cli.scheme, "auto");
  merge.take<std::size_t>("record_points", "--record-points", &SimulationSection::record_points, cli.record_points,
                          1000);
  merge.take<double>("bound", "--bound", &SimulationSection::bound, cli.bound, 1e8);
  merge.take<std::size_t>("shown_run", "--shown-run", &SimulationSection::shown_run, cli.shown_run, 0);
  std::optional<std::vector<std::string>> filters;
  if (cli.filters) filters = parse_filter_list("--filters", *cli.filters, model);
  merge.take_given<std::vector<std::string>>("filters", "--filters", &SimulationSection::filters, filters,
                                             "every filter");

  const double T = *s.T;
  merge.place("report_times", "--report-times", list_origin(cli.report_times, file.report_times), "none");
  if (cli.report_times) {
    for (const auto& part : split(*cli.report_times, ',')) s.report_times.push_back(parse_double("--report-times", part));
  } else {
    s.report_times = file.report_times;
    out.notes += drop_beyond_horizon(
        s.report_times, T, cli.T.has_value(), "report_times", [](double t) { return t; },
        [](double t) { return number_text(t); });
  }
  merge.place("windows", "--windows", list_origin(cli.windows, file.windows), "none");
  if (cli.windows) {
    for (const auto& part : split(*cli.windows, ',')) {
      const auto ends = split(part, ':');
      if (ends.size() != 2) throw CliValueError("--windows: '" + part + "' is not a:b");
      s.windows.emplace_back(parse_double("--windows", ends[0]), parse_double("--windows", ends[1]));
    }
  } else {
    s.windows = file.windows;
    out.notes += drop_beyond_horizon(
        s.windows, T, cli.T.has_value(), "windows", [](const std::pair<double, double>& w) { return w.second; },
        [](const std::pair<double, double>& w) {
          return "[" + number_text(w.first) + ", " + number_text(w.second) + "]";
        });
  }
  return out;
}

}  // namespace pfgen::cli
