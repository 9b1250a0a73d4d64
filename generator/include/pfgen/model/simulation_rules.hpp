#pragma once
// The rules of `pfgen simulate`'s settings, in one place. The model file's `simulation:` section
// (validate_model, check_simulation_settings) and a job's settings, the command line over the
// file over pfgen's defaults merged once (cli/simulation_settings_merge, check_simulation_job),
// are checked here, so both say the same words; only where a value came from, which the caller
// puts in front, differs. A rule applies when the values it needs are known: a file that gives dt
// but no T is checked for dt > 0, and for dt < T only once the command line gives T. The
// runtime's own checks are preconditions for library users; the command line never reaches them
// with settings these rules refuse.
#include <cstddef>
#include <optional>
#include <string>

#include "pfgen/model/model.hpp"

namespace pfgen {

struct SimulationRuleBreach {
  std::string field;                 // the setting, as the model file names it: "dt", "windows", ...
  std::optional<std::size_t> entry;  // 0-based entry of a list setting
  std::string message;               // what is wrong, without the place
  // Set when the breach is named at a field of the model rather than at the setting: the job's dt
  // against the sampling period is "observation.sampled.period", whichever place gave dt.
  std::string model_field;
};

// The budget of one run, the truth's grid steps T / dt and each sampled filter's prediction
// sub-steps (T / period) x substeps alike: beyond it a run takes hours, or its step count no longer
// fits the counters the runtime keeps exact.
inline constexpr double kMaxStepsPerRun = 1e9;

// Why a sampled filter's (T / period) x substeps prediction sub-steps are beyond kMaxStepsPerRun,
// or nothing: the rule below for a model's own substeps, and simulate's for those a filter chose.
std::optional<std::string> substep_budget_problem(const std::string& filter, double T, double period, double substeps);

// The first rule the settings break, in a fixed order (T, dt, the observation delay against dt,
// runs, record points, bound, shown run, scheme, filters, the sampled filters' sub-steps against
// kMaxStepsPerRun, report times, windows), or nothing.
std::optional<SimulationRuleBreach> check_simulation_settings(const Model& model, const SimulationSection& settings);

// The rules of one simulate job's merged settings (every field known but filters): those above,
// then the job's dt against a sampled model's period, which must be a whole number (at least 1)
// of steps dt for the samples to fall on the truth's grid. That one is the job's alone: a model
// file's dt that does not divide the period is no error at load (derive and codegen do not use
// dt, and simulate --dt may replace it). Checked last, after every rule the file shares.
std::optional<SimulationRuleBreach> check_simulation_job(const Model& model, const SimulationSection& job);

// Whether the model's diffusion is identically zero (a deterministic truth).
bool diffusion_is_zero(const Model& model);

// The truth scheme `auto` stands for: rk4 for a deterministic truth (g identically zero);
// adaptive-euler when the drift or the diffusion is superlinear in the states (Euler-Maruyama and
// Milstein overshoot and overflow there where the true process does not: docs/theory.md §6);
// milstein when g depends on the states linearly; euler-maruyama for additive noise (then it has
// strong order 1).
std::string choose_truth_scheme(const Model& model);

}  // namespace pfgen
