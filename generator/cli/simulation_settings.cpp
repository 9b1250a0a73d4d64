#include "simulation_settings.hpp"

#include <cmath>
#include <iostream>
#include <map>
#include <sstream>

#include "cli_options.hpp"
#include "pfgen/algebra/numeric_value.hpp"
#include "pfgen/algebra/polynomial.hpp"
#include "pfgen/model/model.hpp"
#include "pfgen/model/simulation_rules.hpp"
#include "pfgen_support/quoted_text.hpp"
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

// The command line's value, else the model file's, else `value` keeps pfgen's default.
template <class T>
void take(T& value, const std::optional<T>& command_line, const std::optional<T>& file) {
  if (command_line) value = *command_line;
  else if (file) value = *file;
}

// The model file's report times and windows are defaults for its own horizon: with a shorter
// --T, those beyond it are left out (said on stderr) rather than refused, so that a quick
// `--T 1` run of any model just works. Within one source (the file alone) they stay errors.
// Returns the note to print once every setting has passed its checks (an error line is the only
// line a refused job prints).
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

// Where a setting's value came from, for messages: the option when the command line gave it, the
// field's place when the model file did, else the option with pfgen's default.
std::string place_of(const std::string& field, const SimulationOverrides& cli, const SimulationSection& file,
                     const SimulationSettings& s) {
  struct Source {
    std::string option;
    bool on_command_line, in_file;
    std::string default_value;
  };
  const std::map<std::string, Source> sources = {
      {"T", {"--T", cli.T.has_value(), file.T.has_value(), number_text(s.T)}},
      {"dt", {"--dt", cli.dt.has_value(), file.dt.has_value(), number_text(s.dt)}},
      {"runs", {"--runs", cli.runs.has_value(), file.runs.has_value(), std::to_string(s.runs)}},
      {"record_points",
       {"--record-points", cli.record_points.has_value(), file.record_points.has_value(),
        std::to_string(s.record_points)}},
      {"bound", {"--bound", cli.bound.has_value(), file.bound.has_value(), number_text(s.bound)}},
      {"shown_run", {"--shown-run", cli.shown_run.has_value(), file.shown_run.has_value(), std::to_string(s.shown_run)}},
      {"scheme", {"--scheme", cli.scheme.has_value(), file.scheme.has_value(), s.scheme}},
      {"filters", {"--filters", cli.filters.has_value(), file.filters.has_value(), "every filter"}},
      {"report_times", {"--report-times", cli.report_times.has_value(), !file.report_times.empty(), "none"}},
      {"windows", {"--windows", cli.windows.has_value(), !file.windows.empty(), "none"}},
  };
  const auto found = sources.find(field);
  if (found == sources.end()) return "simulation." + field;
  const Source& source = found->second;
  if (source.on_command_line) return source.option;
  if (source.in_file) return file.location_of(field) + ": simulation." + field;
  return source.option + " (default " + source.default_value + ")";
}

// A `risk:` entry at this job's parameter values (the model's defaults after --set): the
// validator has checked that it is a real number of parameters alone.
double risk_value(const Model& model, const GiNaC::ex& e, const std::string& field) {
  GiNaC::exmap values;
  for (const Parameter& parameter : model.parameters) values[parameter.symbol] = parameter.default_value;
  const GiNaC::ex value = pfgen::numeric_value(e, values).evalf();
  if (!GiNaC::is_a<GiNaC::numeric>(value) || !GiNaC::ex_to<GiNaC::numeric>(value).is_real())
    throw CliValueError(model.source + ": " + field + ": not a real number at this job's parameter values");
  return GiNaC::ex_to<GiNaC::numeric>(value).to_double();
}

// J's eps and M: --risk-epsilon over the model's risk.epsilon (a parameter expression, at the
// job's parameter values, so --set changes it); M from risk.weight, the identity when not given.
std::optional<CriterionSettings> resolve_criterion(const Model& model, const SimulationOverrides& cli) {
  if (cli.risk_epsilon && (!(*cli.risk_epsilon > 0) || !std::isfinite(*cli.risk_epsilon)))
    throw CliValueError("--risk-epsilon: '" + number_text(*cli.risk_epsilon) + "' is not a finite number > 0");
  if (!cli.risk_epsilon && !model.risk) return std::nullopt;
  CriterionSettings criterion;
  if (cli.risk_epsilon) criterion.epsilon = *cli.risk_epsilon;
  else criterion.epsilon = risk_value(model, model.risk->epsilon, "risk.epsilon");
  if (!(criterion.epsilon > 0) || !std::isfinite(criterion.epsilon))
    throw CliValueError(model.source + ": risk.epsilon: " + number_text(criterion.epsilon) +
                        " at this job's parameter values is not a finite number > 0");
  if (model.risk && !model.risk->weight.empty())
    for (std::size_t i = 0; i < model.n(); ++i)
      for (std::size_t j = 0; j < model.n(); ++j)
        criterion.weight.push_back(risk_value(model, model.risk->weight[i][j],
                                              "risk.weight, row " + std::to_string(i + 1) + ", column " +
                                                  std::to_string(j + 1)));
  return criterion;
}

}  // namespace

std::size_t parse_reference(const std::string& text) {
  const std::string prefix = "particles:";
  const std::string usage = "; write particles:N, N the number of particles (1 to " +
                            std::to_string(kMaxReferenceParticles) + ")";
  if (text.compare(0, prefix.size(), prefix) != 0)
    throw CliValueError("--reference: '" + text + "' is not a known reference" + usage);
  const std::string digits = text.substr(prefix.size());
  if (digits.empty() || digits.find_first_not_of("0123456789") != std::string::npos)
    throw CliValueError("--reference: '" + digits + "' in '" + text + "' is not a whole number" + usage);
  // Length first: no overflow, whatever the digits.
  const std::size_t significant = digits.find_first_not_of('0');
  if (significant == std::string::npos)
    throw CliValueError("--reference: '" + text + "' asks for no particles" + usage);
  const std::string value = digits.substr(significant);
  if (value.size() > std::to_string(kMaxReferenceParticles).size() || std::stoull(value) > kMaxReferenceParticles)
    throw CliValueError("--reference: " + digits + " particles are more than the " +
                        std::to_string(kMaxReferenceParticles) + " allowed" + usage);
  return static_cast<std::size_t>(std::stoull(value));
}

SimulationSettings resolve_simulation_settings(const Model& model, const SimulationOverrides& cli) {
  const SimulationSection& file = model.simulation;
  SimulationSettings s;
  if (cli.T) s.T = *cli.T;
  else if (file.T) s.T = *file.T;
  else throw CliValueError("--T: no horizon; give --T or simulation.T in " + model.source);
  take(s.dt, cli.dt, file.dt);
  take(s.runs, cli.runs, file.runs);
  take(s.seed, cli.seed, file.seed);
  take(s.scheme, cli.scheme, file.scheme);
  take(s.record_points, cli.record_points, file.record_points);
  take(s.bound, cli.bound, file.bound);
  take(s.shown_run, cli.shown_run, file.shown_run);
  if (cli.filters) s.filters = parse_filter_list("--filters", *cli.filters, model);
  else if (file.filters) s.filters = *file.filters;

  std::string notes;
  if (cli.report_times) {
    for (const auto& part : split(*cli.report_times, ',')) s.report_times.push_back(parse_double("--report-times", part));
  } else {
    s.report_times = file.report_times;
    notes += drop_beyond_horizon(s.report_times, s.T, cli.T.has_value(), "report_times",
                        [](double t) { return t; }, [](double t) { return number_text(t); });
  }
  if (cli.windows) {
    for (const auto& part : split(*cli.windows, ',')) {
      const auto ends = split(part, ':');
      if (ends.size() != 2) throw CliValueError("--windows: '" + part + "' is not a:b");
      s.windows.emplace_back(parse_double("--windows", ends[0]), parse_double("--windows", ends[1]));
    }
  } else {
    s.windows = file.windows;
    notes += drop_beyond_horizon(s.windows, s.T, cli.T.has_value(), "windows",
                        [](const std::pair<double, double>& w) { return w.second; },
                        [](const std::pair<double, double>& w) {
                          return "[" + number_text(w.first) + ", " + number_text(w.second) + "]";
                        });
  }

  // The combined settings obey the same rules as a model file's section (simulation_rules.cpp);
  // a broken rule names where its value came from.
  SimulationSection combined;
  combined.T = s.T;
  combined.dt = s.dt;
  combined.runs = s.runs;
  combined.seed = s.seed;
  if (cli.filters || file.filters) combined.filters = s.filters;
  combined.scheme = s.scheme;
  combined.report_times = s.report_times;
  combined.windows = s.windows;
  combined.record_points = s.record_points;
  combined.bound = s.bound;
  combined.shown_run = s.shown_run;
  if (auto breach = check_simulation_job(model, combined))
    throw CliValueError((breach->model_field.empty() ? place_of(breach->field, cli, file, s)
                                                     : model.source + ": " + breach->model_field) +
                        ": " + breach->message);
  s.criterion = resolve_criterion(model, cli);
  if (cli.reference) s.reference_particles = parse_reference(*cli.reference);
  s.x0_from_prior = model.initial && model.initial->x0_from_prior;
  if (cli.x0) {
    if (*cli.x0 != "prior" && *cli.x0 != "model")
      throw CliValueError("--x0: " + pfgen_support::quoted(*cli.x0) +
                          " is neither prior (each run's truth drawn from N(m0, P0)) nor model (the model's x0)");
    s.x0_from_prior = *cli.x0 == "prior";
  }
  if (s.x0_from_prior && !model.initial)
    throw CliValueError("--x0 prior: " + model.source + " gives no initial: m0 and P0 to draw from");
  std::cerr << notes;
  return s;
}

}  // namespace pfgen::cli
