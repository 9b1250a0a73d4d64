#include "simulation_settings.hpp"

#include <cmath>
#include <iostream>
#include <sstream>

#include "cli_options.hpp"
#include "pfgen/algebra/polynomial.hpp"
#include "pfgen/model/model.hpp"
#include "pfgen_support/shortest_double.hpp"

namespace pfgen::cli {
namespace {

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

// Shortest round-trip text, fixed or scientific whichever is shorter ("20", not "2e+01").
std::string number_text(double value) { return pfgen_support::shortest_chars(value); }

// Where a setting came from, for error messages. A setting neither the command line nor the
// model file gave is pfgen's default: name the option, not a place in a file that lacks it
// (`--T 1e-6` alone used to blame "<model>: simulation.dt" for the default dt).
std::string origin(bool from_command_line, bool from_file, const std::string& option, const Model& model,
                   const std::string& field) {
  if (from_command_line) return option;
  if (!from_file) return option + " (default)";
  return model.simulation.location_of(field) + ": simulation." + field;
}

// The command line's value, else the model file's, else `value` keeps pfgen's default.
template <class T>
void take(T& value, const std::optional<T>& command_line, const std::optional<T>& file) {
  if (command_line) value = *command_line;
  else if (file) value = *file;
}

// Whether the model's diffusion is identically zero (a deterministic truth).
bool noise_free(const Model& model) {
  for (const auto& row : model.diffusion.G)
    for (const auto& entry : row)
      if (!entry.expand().is_zero()) return false;
  return true;
}

// The model file's report times and windows are defaults for its own horizon: with a shorter
// --T, those beyond it are left out (said on stderr) rather than refused, so that a quick
// `--T 1` run of any model just works. Within one source (the file alone) they stay errors.
template <class Item, class End, class Text>
void drop_beyond_horizon(std::vector<Item>& items, double T, bool T_from_command_line, const std::string& field,
                         End end, Text text) {
  if (!T_from_command_line) return;
  std::vector<Item> kept;
  std::string dropped;
  for (const Item& item : items) {
    if (end(item) <= T) kept.push_back(item);
    else dropped += (dropped.empty() ? "" : ", ") + text(item);
  }
  if (!dropped.empty())
    std::cerr << "pfgen: note: simulation." << field << " " << dropped << " beyond --T " << number_text(T)
              << " left out\n";
  items = std::move(kept);
}

}  // namespace

SimulationSettings resolve_simulation_settings(const Model& model, const SimulationOverrides& cli) {
  const auto& file = model.simulation;
  SimulationSettings s;
  auto origin_of = [&model](bool from_command_line, bool from_file, const char* option, const char* field) {
    return origin(from_command_line, from_file, option, model, field);
  };
  const std::string runs_origin = origin_of(cli.runs.has_value(), file.runs.has_value(), "--runs", "runs");
  const std::string scheme_origin = origin_of(cli.scheme.has_value(), file.scheme.has_value(), "--scheme", "scheme");
  const std::string report_times_origin =
      origin_of(cli.report_times.has_value(), !file.report_times.empty(), "--report-times", "report_times");
  const std::string windows_origin = origin_of(cli.windows.has_value(), !file.windows.empty(), "--windows", "windows");
  const std::string record_points_origin =
      origin_of(cli.record_points.has_value(), file.record_points.has_value(), "--record-points", "record_points");
  const std::string bound_origin = origin_of(cli.bound.has_value(), file.bound.has_value(), "--bound", "bound");
  const std::string shown_run_origin =
      origin_of(cli.shown_run.has_value(), file.shown_run.has_value(), "--shown-run", "shown_run");

  if (cli.T) s.T = *cli.T;
  else if (file.T) s.T = *file.T;
  else throw CliValueError("--T: no horizon; give --T or simulation.T in " + model.source);
  const std::string T_origin = origin(cli.T.has_value(), file.T.has_value(), "--T", model, "T");
  if (!(s.T > 0) || !std::isfinite(s.T)) throw CliValueError(T_origin + ": the horizon must be a positive number");

  take(s.dt, cli.dt, file.dt);
  const std::string dt_origin = cli.dt || file.dt ? origin(cli.dt.has_value(), file.dt.has_value(), "--dt", model, "dt")
                                                  : "--dt (default " + number_text(s.dt) + ")";
  if (!(s.dt > 0) || !(s.dt < s.T)) throw CliValueError(dt_origin + ": the step must be positive and below T = " + number_text(s.T));
  if (s.T / s.dt > 1e9) throw CliValueError(dt_origin + ": more than 1e9 steps to T = " + number_text(s.T));
  // The grid has round(T / dt) steps of dt: a T that is not a whole number of steps would
  // silently become another horizon (T = 1, dt = 0.7 ran to t = 0.7 and labelled it [0, 0.7]).
  // The slack covers the rounding of a decimal T and dt (9.2 / 1e-4 = 91999.99999999999).
  const double steps = s.T / s.dt;
  if (std::abs(steps - std::round(steps)) > 1e-6 + 1e-12 * steps)
    throw CliValueError(dt_origin + ": T = " + number_text(s.T) + " is not a whole number of steps of " +
                        number_text(s.dt) + " (T / dt = " + number_text(steps) + "); choose a dt that divides T");

  take(s.runs, cli.runs, file.runs);
  if (s.runs == 0) throw CliValueError(runs_origin + ": at least one run");

  take(s.seed, cli.seed, file.seed);

  if (cli.filters) {
    s.filters = parse_filter_list("--filters", *cli.filters, model);
    // A filter named twice used to fail in code generation ("given twice for one plugin"),
    // without naming the option.
    for (std::size_t k = 0; k < s.filters.size(); ++k)
      for (std::size_t j = 0; j < k; ++j)
        if (s.filters[j] == s.filters[k]) throw CliValueError("--filters: '" + s.filters[k] + "' is given twice");
  }
  else if (file.filters) s.filters = *file.filters;

  take(s.scheme, cli.scheme, file.scheme);
  bool known = false;
  std::string known_list;
  for (const std::string& name : simulation_schemes()) {
    known = known || s.scheme == name;
    known_list += (known_list.empty() ? "" : ", ") + name;
  }
  if (!known)
    throw CliValueError(scheme_origin + ": unknown scheme '" + s.scheme +
                        "' (" + known_list + ")");
  // What the schemes need of the model, checked here, before anything is compiled (the runtime
  // used to refuse these only after the plugin was built, without naming the option).
  if (s.scheme == "rk4" && !noise_free(model))
    throw CliValueError(scheme_origin +
                        ": rk4 is for deterministic truths only, and this model's diffusion is not zero");
  if (s.scheme == "milstein" && !noise_free(model) && !model.diffusion.g)
    throw CliValueError(scheme_origin +
                        ": milstein needs the diffusion g, and this model gives diffusion_covariance; use "
                        "derivative-free-milstein");

  if (cli.report_times) {
    for (const auto& part : split(*cli.report_times, ',')) s.report_times.push_back(parse_double("--report-times", part));
  } else {
    s.report_times = file.report_times;
    drop_beyond_horizon(s.report_times, s.T, cli.T.has_value(), "report_times",
                        [](double t) { return t; }, [](double t) { return number_text(t); });
  }
  for (double t : s.report_times)
    if (!(t >= 0 && t <= s.T))
      throw CliValueError(report_times_origin + ": " +
                          number_text(t) + " is outside [0, T = " + number_text(s.T) + "]");

  if (cli.windows) {
    for (const auto& part : split(*cli.windows, ',')) {
      const auto ends = split(part, ':');
      if (ends.size() != 2) throw CliValueError("--windows: '" + part + "' is not a:b");
      s.windows.emplace_back(parse_double("--windows", ends[0]), parse_double("--windows", ends[1]));
    }
  } else {
    s.windows = file.windows;
    drop_beyond_horizon(s.windows, s.T, cli.T.has_value(), "windows",
                        [](const std::pair<double, double>& w) { return w.second; },
                        [](const std::pair<double, double>& w) {
                          return "[" + number_text(w.first) + ", " + number_text(w.second) + "]";
                        });
  }
  for (const auto& [a, b] : s.windows) {
    if (!(a >= 0 && a < b && b <= s.T))
      throw CliValueError(windows_origin + ": [" + number_text(a) + ", " +
                          number_text(b) + "] is not a window a < b within [0, T = " + number_text(s.T) + "]");
    // The Monte Carlo snaps both ends to the nearest grid point (as it does); a window whose ends
    // snap to the same one used to fail after the build with "monte carlo: a window is shorter
    // than a grid step", naming neither the option nor the window.
    if (std::llround(a / s.dt) == std::llround(b / s.dt))
      throw CliValueError(windows_origin + ": [" + number_text(a) + ", " +
                          number_text(b) + "] is shorter than a step dt = " + number_text(s.dt));
  }

  take(s.record_points, cli.record_points, file.record_points);
  if (s.record_points < 2)
    throw CliValueError(record_points_origin +
                        ": at least 2 points");

  take(s.bound, cli.bound, file.bound);
  if (!(s.bound > 0)) throw CliValueError(bound_origin + ": must be positive");

  take(s.shown_run, cli.shown_run, file.shown_run);
  if (s.shown_run >= s.runs)
    throw CliValueError(shown_run_origin + ": run " +
                        std::to_string(s.shown_run) + " does not exist with " + std::to_string(s.runs) + " runs");
  return s;
}

std::string choose_truth_scheme(const Model& model) {
  const std::vector<GiNaC::symbol>& x = model.states;
  auto degree = [&x](const GiNaC::ex& e) { return Polynomial::from_ex(e.expand(), x).degree(); };
  if (noise_free(model)) return "rk4";
  std::uint32_t drift_degree = 0, diffusion_degree = 0;
  for (const auto& f : model.drift) drift_degree = std::max(drift_degree, degree(f));
  // G = g g^T has twice g's degree, and is given whichever form the model file uses.
  for (const auto& row : model.diffusion.G)
    for (const auto& entry : row)
      if (!entry.expand().is_zero()) diffusion_degree = std::max(diffusion_degree, (degree(entry) + 1) / 2);
  if (drift_degree > 1 || diffusion_degree > 1) return "adaptive-euler";
  if (diffusion_degree == 1) return model.diffusion.g ? "milstein" : "derivative-free-milstein";
  return "euler-maruyama";
}

}  // namespace pfgen::cli
