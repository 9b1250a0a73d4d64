#include "simulation_settings.hpp"

#include <cmath>
#include <iostream>

#include "cli_options.hpp"
#include "simulation_settings_merge.hpp"
#include "pfgen/algebra/numeric_value.hpp"
#include "pfgen/algebra/polynomial.hpp"
#include "pfgen/model/model.hpp"
#include "pfgen/model/simulation_rules.hpp"
#include "pfgen_support/quoted_text.hpp"
#include "pfgen_support/shortest_double.hpp"

namespace pfgen::cli {
namespace {

// Shortest round-trip text, fixed or scientific whichever is shorter ("20", not "2e+01").
std::string number_text(double value) { return pfgen_support::shortest_chars(value); }

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

// The particle reference's steps per run, N particles of each set over every grid step, under the
// budget of one run as the truth's and each filter's steps are: particles:1000000 over 10^4 steps
// (2 x 10^10 particle steps) ran for minutes a run before it was refused.
void check_reference_budget(std::size_t particles, const SimulationSettings& s) {
  const double steps = std::round(s.T / s.dt);
  const double particle_steps = static_cast<double>(kReferenceParticleSets) * static_cast<double>(particles) * steps;
  if (particle_steps > kMaxStepsPerRun)
    throw CliValueError("--reference: particles:" + std::to_string(particles) + " over " + number_text(steps) +
                        " steps of dt = " + number_text(s.dt) + " would take " + number_text(particle_steps) +
                        " particle steps per run (" + std::to_string(kReferenceParticleSets) +
                        " sets of N particles, the second for the reference's own error); the budget of one run is "
                        "1e9 steps: lower N or the steps T / dt");
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
  // Merged once, checked once: the rules name a broken one where its value came from.
  const MergedSimulation merged = merge_simulation_settings(model, cli);
  const SimulationSection& job = merged.values;
  if (auto breach = check_simulation_job(model, job)) {
    const std::string place =
        breach->model_field.empty() ? merged.places.at(breach->field) : model.source + ": " + breach->model_field;
    throw CliValueError(place + ": " + breach->message);
  }
  SimulationSettings s;
  s.T = *job.T;
  s.dt = *job.dt;
  s.runs = *job.runs;
  s.seed = *job.seed;
  if (job.filters) s.filters = *job.filters;
  s.scheme = *job.scheme;
  s.report_times = job.report_times;
  s.windows = job.windows;
  s.record_points = *job.record_points;
  s.bound = *job.bound;
  s.shown_run = *job.shown_run;
  s.criterion = resolve_criterion(model, cli);
  if (cli.reference) {
    s.reference_particles = parse_reference(*cli.reference);
    check_reference_budget(*s.reference_particles, s);
  }
  s.x0_from_prior = model.initial && model.initial->x0_from_prior;
  if (cli.x0) {
    if (*cli.x0 != "prior" && *cli.x0 != "model")
      throw CliValueError("--x0: " + pfgen_support::quoted(*cli.x0) +
                          " is neither prior (each run's truth drawn from N(m0, P0)) nor model (the model's x0)");
    s.x0_from_prior = *cli.x0 == "prior";
  }
  if (cli.stepping) {
    if (*cli.stepping != "generated" && *cli.stepping != "refined")
      throw CliValueError("--stepping: " + pfgen_support::quoted(*cli.stepping) +
                          " is neither generated (one step() per grid step, as the generated code runs) nor refined "
                          "(a grid step split where P would change too fast; the default)");
    s.refined_stepping = *cli.stepping == "refined";
  }
  if (s.x0_from_prior && !model.initial)
    throw CliValueError("--x0 prior: " + model.source + " gives no initial: m0 and P0 to draw from");
  std::cerr << merged.notes;
  return s;
}

}  // namespace pfgen::cli
