#include "pfgen/model/simulation_rules.hpp"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <set>

#include "pfgen/algebra/polynomial.hpp"
#include "pfgen/model/delay_grid.hpp"
#include "pfgen/model/model_filters.hpp"
#include "pfgen_support/shortest_double.hpp"
#include "pfgen_support/whole_steps.hpp"

namespace pfgen {
namespace {

// Shortest round-trip text ("20", "9.2", "1e-06").
std::string number_text(double value) { return pfgen_support::shortest_chars(value); }

std::string window_text(const std::pair<double, double>& w) {
  return "window [" + number_text(w.first) + ", " + number_text(w.second) + "]";
}

using Breach = std::optional<SimulationRuleBreach>;

Breach breach(const std::string& field, const std::string& message, std::optional<std::size_t> entry = {}) {
  return SimulationRuleBreach{field, entry, message, {}};
}

Breach positive(const std::optional<double>& value, const std::string& field, const std::string& what) {
  if (value && !(std::isfinite(*value) && *value > 0))
    return breach(field, what + " must be a number greater than 0, found " + number_text(*value));
  return {};
}

Breach check_grid(const SimulationSection& s) {
  if (auto b = positive(s.T, "T", "the horizon T (the simulation starts at t = 0)")) return b;
  if (auto b = positive(s.dt, "dt", "the step dt")) return b;
  if (!s.T || !s.dt) return {};
  const double T = *s.T, dt = *s.dt;
  if (!(dt < T)) return breach("dt", "the step dt = " + number_text(dt) + " must be smaller than T = " + number_text(T));
  const double steps = T / dt;
  if (steps > kMaxStepsPerRun)
    return breach("dt", "more than 1e9 steps of dt = " + number_text(dt) + " to T = " + number_text(T) +
                            " (the budget of one run, the truth's steps and each filter's sub-steps alike)");
  // The grid has round(T / dt) steps of dt: a T that is not a whole number of steps would
  // silently become another horizon (T = 1, dt = 0.7 ran to t = 0.7 and labelled it [0, 0.7]).
  // The slack covers the rounding of a decimal T and dt (9.2 / 1e-4 = 91999.99999999999).
  if (std::abs(steps - std::round(steps)) > 1e-6 + 1e-12 * steps)
    return breach("dt", "T = " + number_text(T) + " is not a whole number of steps of " + number_text(dt) +
                            " (T / dt = " + number_text(steps) + "); choose a dt that divides T");
  return {};
}

// Delayed filters run on the fixed grid t_k = k dt and read their history D = h / dt steps back,
// as the truth's dy reads x: h must be a whole number of steps (model/delay_grid.hpp), the file's
// dt and the command line's alike. An observation without a delay has h = 0, always whole.
Breach check_delay(const Model& model, const SimulationSection& s) {
  if (!s.dt || !(*s.dt > 0)) return {};
  const DelaySteps steps = delay_steps(model.observation.delay(), *s.dt);
  if (!steps.problem.empty()) return breach("dt", "observation.delay: " + steps.problem);
  return {};
}

Breach check_counts(const SimulationSection& s) {
  if (s.runs && *s.runs < 1) return breach("runs", "at least 1 run is required");
  if (s.record_points && *s.record_points < 2)
    return breach("record_points", "at least 2 record points are required, found " + std::to_string(*s.record_points));
  if (auto b = positive(s.bound, "bound", "the divergence bound")) return b;
  if (s.shown_run && s.runs && !(*s.shown_run < *s.runs))
    return breach("shown_run", "run " + std::to_string(*s.shown_run) + " is not among the " + std::to_string(*s.runs) +
                                   " runs (numbered from 0)");
  return {};
}

Breach check_scheme(const Model& model, const SimulationSection& s) {
  if (!s.scheme) return {};
  const auto& schemes = simulation_schemes();
  if (std::find(schemes.begin(), schemes.end(), *s.scheme) == schemes.end()) {
    std::string known;
    for (const auto& scheme : schemes) known += (known.empty() ? "" : ", ") + scheme;
    return breach("scheme", "unknown scheme '" + *s.scheme + "' (known: " + known + ")");
  }
  // What the schemes need of the model, so that a job is refused before anything is compiled.
  if (*s.scheme == "rk4" && !diffusion_is_zero(model))
    return breach("scheme", "rk4 is for deterministic truths only, and this model's diffusion is not zero");
  if (*s.scheme == "milstein" && !diffusion_is_zero(model) && !model.diffusion.g)
    return breach("scheme",
                  "milstein needs the diffusion g, and this model gives diffusion_covariance; use "
                  "derivative-free-milstein");
  return {};
}

Breach check_filters(const Model& model, const SimulationSection& s) {
  if (!s.filters) return {};
  if (s.filters->empty()) return breach("filters", "give at least one filter, or leave the field out for every filter");
  std::set<std::string> seen;
  for (std::size_t k = 0; k < s.filters->size(); ++k) {
    const std::string& name = (*s.filters)[k];
    if (auto problem = filter_name_problem(model, name)) return breach("filters", *problem, k);
    if (!seen.insert(name).second) return breach("filters", "filter '" + name + "' is listed twice", k);
  }
  return {};
}

// A sampled filter predicts in `substeps` sub-steps per period (the model's, or S of a KIND@S
// name): (T / period) x substeps of them per run, under the same budget as the truth's steps.
// Sub-steps the derivation chooses (the model gives none) are checked by the command once derived.
Breach check_substeps(const Model& model, const SimulationSection& s) {
  const std::optional<SampleTimes>& samples = model.observation.samples();
  if (!samples || !s.T) return {};
  const std::vector<std::string> names = s.filters ? *s.filters : default_filter_names(model);
  for (std::size_t k = 0; k < names.size(); ++k) {
    const auto split = split_substeps(names[k]);
    const std::optional<std::size_t> substeps = split ? split->second : samples->substeps;
    if (!substeps) continue;
    if (auto problem = substep_budget_problem(names[k], *s.T, samples->period.to_double(),
                                              static_cast<double>(*substeps)))
      return breach(s.filters ? "filters" : "T", *problem, s.filters ? std::optional<std::size_t>(k) : std::nullopt);
  }
  return {};
}

Breach check_times(const SimulationSection& s) {
  for (std::size_t k = 0; k < s.report_times.size(); ++k) {
    const double time = s.report_times[k];
    if (!(std::isfinite(time) && time > 0))
      return breach("report_times", "report time " + number_text(time) + " must be greater than 0", k);
    if (s.T && time > *s.T)
      return breach("report_times",
                    "report time " + number_text(time) + " is after the horizon T = " + number_text(*s.T), k);
    // The table has one column per report time, in order: a repeated or earlier time is a slip.
    if (k > 0 && !(time > s.report_times[k - 1]))
      return breach("report_times", "report time " + number_text(time) + " is not after the previous one, " +
                                        number_text(s.report_times[k - 1]) + "; give them in increasing order",
                    k);
  }
  for (std::size_t k = 0; k < s.windows.size(); ++k) {
    const auto [a, b] = s.windows[k];
    const std::string window = window_text(s.windows[k]);
    if (!(std::isfinite(a) && std::isfinite(b) && a < b))
      return breach("windows", window + ": the start must be before the end", k);
    if (a < 0) return breach("windows", window + " starts before t = 0", k);
    if (s.T && b > *s.T) return breach("windows", window + " ends after the horizon T = " + number_text(*s.T), k);
    // The Monte Carlo snaps both ends to the nearest grid point; a window whose ends snap to the
    // same one has no step in it.
    if (s.dt && std::llround(a / *s.dt) == std::llround(b / *s.dt))
      return breach("windows", window + " is shorter than a step dt = " + number_text(*s.dt), k);
    for (std::size_t j = 0; j < k; ++j)
      if (s.windows[j] == s.windows[k]) return breach("windows", window + " is given twice", k);
  }
  return {};
}

// Samples fall at t_k = k T (T the period) on the truth's grid: T must be a whole number of steps
// dt, by the one rule the runtime's guard also applies (pfgen_support::whole_steps). Its numbers
// are written in full (%.17g), not in the other rules' shortest form: the message has read so
// since before the rules were gathered here.
Breach check_sampling_period(const Model& model, const SimulationSection& s) {
  const std::optional<SampleTimes>& samples = model.observation.samples();
  if (!samples || !s.dt) return {};
  const double period = samples->period.to_double(), dt = *s.dt;
  const std::optional<double> steps = pfgen_support::whole_steps(period, dt);
  if (steps && *steps >= 1) return {};
  char text[200];
  std::snprintf(text, sizeof text, "the sampling period %.17g is not a whole number of steps dt = %.17g (T/dt = %.17g)",
                period, dt, period / dt);
  Breach out = breach("dt", std::string(text) + "; choose --dt = T/N");
  out->model_field = "observation.sampled.period";
  return out;
}

}  // namespace

std::optional<std::string> substep_budget_problem(const std::string& filter, double T, double period, double substeps) {
  const double samples = std::floor(T / period);
  if (!(samples * substeps > kMaxStepsPerRun)) return std::nullopt;
  return "filter '" + filter + "' would take " + number_text(samples * substeps) + " prediction sub-steps per run (" +
         number_text(samples) + " periods to T = " + number_text(T) + ", " + number_text(substeps) +
         " sub-steps each); the budget of one run is 1e9 steps, the truth's and each filter's alike";
}

std::optional<SimulationRuleBreach> check_simulation_settings(const Model& model, const SimulationSection& settings) {
  if (auto b = check_grid(settings)) return b;
  if (auto b = check_delay(model, settings)) return b;
  if (auto b = check_counts(settings)) return b;
  if (auto b = check_scheme(model, settings)) return b;
  if (auto b = check_filters(model, settings)) return b;
  if (auto b = check_substeps(model, settings)) return b;
  return check_times(settings);
}

std::optional<SimulationRuleBreach> check_simulation_job(const Model& model, const SimulationSection& job) {
  if (auto b = check_simulation_settings(model, job)) return b;
  return check_sampling_period(model, job);
}

bool diffusion_is_zero(const Model& model) {
  // g when the model gives it: the validator runs before ModelBuilder computes G = g g^T.
  const ExMatrix& diffusion = model.diffusion.g ? *model.diffusion.g : model.diffusion.G;
  for (const auto& row : diffusion)
    for (const auto& entry : row)
      if (!entry.expand().is_zero()) return false;
  return true;
}

std::string choose_truth_scheme(const Model& model) {
  const std::vector<GiNaC::symbol>& x = model.states;
  auto degree = [&x](const GiNaC::ex& e) { return Polynomial::from_ex(e.expand(), x).degree(); };
  if (diffusion_is_zero(model)) return "rk4";
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

}  // namespace pfgen
