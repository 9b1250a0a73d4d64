#include "fit_command.hpp"

#include <algorithm>
#include <cerrno>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <iostream>
#include <stdexcept>

#include "cli_options.hpp"
#include "output_paths.hpp"
#include "pfgen/model/model_filters.hpp"
#include "pfgen/printing/json_writer.hpp"
#include "pfgen/model/yaml_model_loader.hpp"
#include "pfgen_support/atomic_file.hpp"
#include "pfgen_support/quoted_text.hpp"
#include "pfgen_support/shortest_double.hpp"

namespace pfgen::cli {
namespace {

using pfgen_support::quoted;

double bound_number(const std::string& entry, const std::string& text, double infinite) {
  if (text.empty()) return infinite;
  errno = 0;
  char* end = nullptr;
  const double value = std::strtod(text.c_str(), &end);
  if (end != text.c_str() + text.size() || errno == ERANGE || !std::isfinite(value))
    throw CliValueError("--bounds: " + quoted(entry) + ": " + quoted(text) + " is not a finite number");
  return value;
}

// The log-likelihood of one filter over the record at `values`: sampled, the sum of log N(y; yhat,
// S); continuous, the increments' Gaussian log-density (which, unlike the Girsanov form, compares
// values of B's parameters too).
double record_log_likelihood(const pfgen_runtime::RecordFilter& filter, const RecordJob& job, const Record& record,
                             double t0, std::vector<double> values, const std::vector<double>& initial,
                             std::string& why) {
  pfgen_runtime::RecordRun run(filter, std::move(values), t0, job.run_options, initial);
  for (std::size_t row = 0; row < record.times.size(); ++row) {
    bool ok = false;
    try {
      ok = run.advance(record.times[row], record.values.data() + row * record.p);
    } catch (const std::invalid_argument& e) {
      // Placed as estimate places it ("uneven.csv:5", "<data> row 3"), as the filter's failures are.
      throw CliValueError(record.place(row) + ": " + e.what());
    }
    if (!ok) {
      why = record.place(row) + ": the filter '" + run.filter_name() + "' failed: " + run.failure();
      return std::nan("");
    }
  }
  return run.log_likelihood();
}

std::string json_number(double value) {
  return std::isfinite(value) ? pfgen_support::shortest_double(value) : "null";
}

std::string cell(double value) {
  if (std::isnan(value)) return "-";
  char text[40];
  std::snprintf(text, sizeof text, "%.6g", value);
  return text;
}

}  // namespace

FitOutcome fit(const FitOptions& options) {
  RecordJobOptions record = options.record;
  const Model model = record.model ? *record.model : load_model_file(record.model_path);
  record.model = &model;
  if (options.estimate.empty()) throw CliValueError("--estimate: name at least one parameter");
  record.filters = {options.filter.empty() ? default_filter_names(model).front() : options.filter};
  if (!options.json_path.empty()) {
    check_distinct_outputs({{"the model file", options.record.model_path}, {"--data", record.data_path}},
                           {{"-o", options.json_path}});
    check_output_file({"-o", options.json_path});
  }
  if (options.starts < 1 || options.starts > 1000)
    throw CliValueError("--starts: " + std::to_string(options.starts) + " is not between 1 and 1000");

  RecordJob job = prepare_record_job(record);
  const pfgen_runtime::RecordFilter& filter = job.filters.front();
  // The prior's state (m0, then P0's upper triangle) as the model gives it: m0.X estimates
  // replace its entry X.
  std::vector<double> prior(filter.full_state_size());
  filter.initial_state(prior.data());
  std::vector<std::size_t> index, parameter_of;  // parameters: theta position, and into job.values
  std::vector<std::pair<std::size_t, std::size_t>> prior_means;  // m0.X: (theta position, state)
  FitProblem problem;
  for (const std::string& name : options.estimate) {
    if (name.rfind("m0.", 0) == 0) {
      const std::string state = name.substr(3);
      const auto& states = job.model.state_names;
      const auto at = std::find(states.begin(), states.end(), state);
      if (at == states.end())
        throw CliValueError("--estimate: " + quoted(name) + ": " + quoted(state) + " is not a state of " + model.source +
                            " (its states: " + join(states, ", ") + ")");
      const auto i = static_cast<std::size_t>(at - states.begin());
      for (const auto& [position, seen] : prior_means)
        if (seen == i) throw CliValueError("--estimate: " + quoted(name) + " is named twice");
      if (filter.timing->keeps_history())
        throw CliValueError("--estimate: " + quoted(name) + ": the filter '" + filter.name +
                            "' keeps a history that starts from the model's m0, so its prior mean is not estimated");
      prior_means.push_back({problem.names.size(), i});
      problem.names.push_back(name);
      problem.start.push_back(prior[i]);
      problem.lower.push_back(-HUGE_VAL);
      problem.upper.push_back(HUGE_VAL);
      continue;
    }
    std::size_t k = 0;
    while (k < job.parameter_names.size() && job.parameter_names[k] != name) ++k;
    if (k == job.parameter_names.size())
      throw CliValueError("--estimate: " + quoted(name) + " is not a parameter of " + model.source +
                          (job.parameter_names.empty() ? " (it has none)" : " (its parameters: " + join(job.parameter_names, ", ") + ")"));
    for (std::size_t seen : parameter_of)
      if (seen == k) throw CliValueError("--estimate: " + quoted(name) + " is named twice");
    index.push_back(problem.names.size());
    parameter_of.push_back(k);
    problem.names.push_back(name);
    problem.start.push_back(job.values[k]);
    problem.lower.push_back(-HUGE_VAL);
    problem.upper.push_back(HUGE_VAL);
    // The model file's bounds: first; --bounds replaces them.
    for (const ParameterBound& bound : model.bounds)
      if (bound.name == name) {
        if (bound.low) problem.lower.back() = bound.low->to_double();
        if (bound.high) problem.upper.back() = bound.high->to_double();
      }
  }
  std::vector<bool> bounded(problem.names.size(), false);  // by --bounds, which names each parameter once
  for (const std::string& entry : options.bounds) {
    const std::size_t equals = entry.find('='), colon = entry.find(':', equals == std::string::npos ? 0 : equals);
    if (equals == std::string::npos || colon == std::string::npos)
      throw CliValueError("--bounds: " + quoted(entry) + " is not name=low:high (either end may be empty)");
    const std::string name = entry.substr(0, equals);
    std::size_t k = 0;
    while (k < problem.names.size() && problem.names[k] != name) ++k;
    if (k == problem.names.size())
      throw CliValueError("--bounds: " + quoted(name) + " is not among the estimated parameters (--estimate " +
                          join(problem.names, ",") + ")");
    if (bounded[k]) throw CliValueError("--bounds: " + quoted(name) + " is given bounds twice");
    bounded[k] = true;
    problem.lower[k] = bound_number(entry, entry.substr(equals + 1, colon - equals - 1), -HUGE_VAL);
    problem.upper[k] = bound_number(entry, entry.substr(colon + 1), HUGE_VAL);
    if (!(problem.lower[k] < problem.upper[k]))
      throw CliValueError("--bounds: " + quoted(entry) + ": the low end is not below the high end");
  }
  for (std::size_t i = 0; i < problem.names.size(); ++i)
    if (!(problem.start[i] >= problem.lower[i] && problem.start[i] <= problem.upper[i]))
      throw CliValueError("--bounds: " + problem.names[i] + "'s bounds exclude its start " +
                          pfgen_support::shortest_chars(problem.start[i]) + " (the model's value, or --set's)");
  if (options.starts > 1)
    for (std::size_t i = 0; i < problem.names.size(); ++i)
      if (!std::isfinite(problem.lower[i]) || !std::isfinite(problem.upper[i]))
        throw CliValueError("--starts: further starts are drawn within the bounds; give " + problem.names[i] +
                            " both ends in --bounds");
  problem.starts = options.starts;
  problem.seed = options.seed;
  problem.profile = options.profile;
  problem.filter_can_stop = static_cast<bool>(filter.realisability.margins);

  const Record data = read_record(record, job);
  // Samples all missing leave the likelihood at 0 whatever the parameters: say so, rather than
  // that each parameter does not enter the filter.
  if (std::all_of(data.values.begin(), data.values.end(), [](double v) { return std::isnan(v); }))
    throw CliValueError(data.path + ": every observation is missing: the record has no sample to fit");
  const double t0 = prior_time(record, data.times.front(), record.data_path);
  const LogLikelihood log_likelihood = [&](const std::vector<double>& theta, std::string& why) {
    std::vector<double> values = job.values;
    for (std::size_t i = 0; i < index.size(); ++i) values[parameter_of[i]] = theta[index[i]];
    std::vector<double> initial;  // empty: the filter's own initial state
    if (!prior_means.empty()) initial = prior;
    for (const auto& [position, state] : prior_means) initial[state] = theta[position];
    return record_log_likelihood(filter, job, data, t0, std::move(values), initial, why);
  };

  FitOutcome outcome;
  // A parameter the filter's likelihood does not read (one of the additive kinds' noise for the
  // optimal filter, the risk criterion's epsilon, a parameter of another filter's equations) would
  // leave the fit flat in it: refused, each tried by a small step from the start.
  {
    std::string why;
    const double at_start = log_likelihood(problem.start, why);
    for (std::size_t i = 0; std::isfinite(at_start) && i < problem.names.size(); ++i) {
      std::vector<double> moved = problem.start;
      const double step = 1e-3 * std::max(1.0, std::abs(moved[i]));
      moved[i] = moved[i] + step <= problem.upper[i] ? moved[i] + step : moved[i] - step;
      if (log_likelihood(moved, why) == at_start)
        throw CliValueError("--estimate: " + pfgen_support::quoted(problem.names[i]) + " does not change the log-likelihood of the filter '" +
                            filter.name + "' on this record (it does not enter that filter's equations)");
    }
  }
  outcome.result = maximise_likelihood(problem, log_likelihood);
  const FitResult& r = outcome.result;
  const double k = static_cast<double>(problem.names.size());
  const double aic = outcome.aic = 2 * k - 2 * r.log_likelihood;

  std::string& out = outcome.report;
  out = "Fit of " + model.name + " by " + filter.name + " to " + record.data_path + " (" +
        std::to_string(data.times.size()) + " rows): " + r.stop_reason + "; " + std::to_string(r.evaluations) +
        " log-likelihood evaluations, NLopt L-BFGS, " + std::to_string(problem.starts) +
        (problem.starts == 1 ? " start\n" : " starts\n");
  if (!r.converged) {
    out += "The optimiser did not converge: no estimates. Last point:";
    for (const FittedParameter& p : r.parameters) out += " " + p.name + " = " + cell(p.estimate);
    out += " (log-likelihood " + cell(r.log_likelihood) + ")\n";
  } else {
    char line[300];
    std::snprintf(line, sizeof line, "\n%-12s %14s %14s %29s%s\n", "parameter", "estimate", "std. error",
                  "95 % Wald interval", options.profile ? "        95 % profile interval" : "");
    out += line;
    for (const FittedParameter& p : r.parameters) {
      const std::string wald = "[" + cell(p.wald_low) + ", " + cell(p.wald_high) + "]";
      auto end_note = [](bool is_bound, bool is_edge) {
        return std::string(is_bound ? " (bound)" : is_edge ? " (the filter fails beyond)" : "");
      };
      const std::string profile = "[" + cell(p.profile_low) + end_note(p.profile_low_is_bound, p.profile_low_is_edge) +
                                  ", " + cell(p.profile_high) +
                                  end_note(p.profile_high_is_bound, p.profile_high_is_edge) + "]";
      std::snprintf(line, sizeof line, "%-12s %14s %14s %29s%s%s\n", p.name.c_str(), cell(p.estimate).c_str(),
                    cell(p.std_error).c_str(), wald.c_str(),
                    options.profile ? ("  " + std::string(29 - std::min<std::size_t>(29, profile.size()), ' ') + profile).c_str() : "",
                    p.at_bound ? "  (at its bound)" : "");
      out += line;
    }
    std::snprintf(line, sizeof line, "\nlog-likelihood %.6f, AIC %.6f (%zu parameter%s estimated)\n", r.log_likelihood,
                  aic, problem.names.size(), problem.names.size() == 1 ? "" : "s");
    out += line;
    if (!r.information_note.empty()) out += r.information_note + "\n";
  }

  std::string& json = outcome.json;
  json = "{\n  \"model\": " + json_quote(model.name) + ",\n  \"filter\": " +
         json_quote(filter.name) + ",\n  \"rows\": " + std::to_string(data.times.size()) +
         ",\n  \"converged\": " + (r.converged ? "true" : "false") + ",\n  \"stop_reason\": " +
         json_quote(r.stop_reason) + ",\n  \"evaluations\": " + std::to_string(r.evaluations) +
         ",\n  \"log_likelihood\": " + json_number(r.log_likelihood) + ",\n  \"aic\": " + json_number(aic) +
         ",\n  \"parameters\": [";
  for (std::size_t i = 0; i < r.parameters.size(); ++i) {
    const FittedParameter& p = r.parameters[i];
    json += std::string(i ? "," : "") + "\n    {\"name\": " + json_quote(p.name) +
            ", \"estimate\": " + json_number(p.estimate) + ", \"std_error\": " + json_number(p.std_error) +
            ", \"wald\": [" + json_number(p.wald_low) + ", " + json_number(p.wald_high) + "], \"profile\": [" +
            json_number(p.profile_low) + ", " + json_number(p.profile_high) + "], \"profile_at_bound\": [" +
            (p.profile_low_is_bound ? "true" : "false") + ", " + (p.profile_high_is_bound ? "true" : "false") + "]" +
            // Only where an end is an edge of the filter's region, so that other fits' files are as before.
            (p.profile_low_is_edge || p.profile_high_is_edge
                 ? std::string(", \"profile_filter_fails_beyond\": [") + (p.profile_low_is_edge ? "true" : "false") +
                       ", " + (p.profile_high_is_edge ? "true" : "false") + "]"
                 : std::string()) +
            ", \"at_bound\": " + (p.at_bound ? "true" : "false") + "}";
  }
  json += "\n  ]";
  if (r.at_edge) json += ",\n  \"at_edge_of_filter\": true,\n  \"note\": " + json_quote(r.information_note);
  json += "\n}\n";
  return outcome;
}

int run_fit(const FitOptions& options) {
  const FitOutcome outcome = fit(options);
  std::cout << outcome.report;
  if (!options.json_path.empty()) {
    pfgen_support::write_file_atomically(options.json_path, outcome.json);
    std::cout << "Wrote " << options.json_path << "\n";
  }
  return outcome.result.converged ? 0 : 1;
}

}  // namespace pfgen::cli
