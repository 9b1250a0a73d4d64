#pragma once
// The settings of one `pfgen simulate` job: the command line overrides the model file's
// `simulation:` section, which overrides pfgen's defaults (merged once, in
// simulation_settings_merge), checked once by the model's simulation rules; then the options
// that are the command line's alone (J's criterion, --reference, --x0).
#include <cstddef>
#include <cstdint>
#include <optional>
#include <string>
#include <utility>
#include <vector>

namespace pfgen {
struct Model;
}

namespace pfgen::cli {

// What the command line gave; unset fields fall back to the model file, then to defaults.
struct SimulationOverrides {
  std::optional<double> T, dt, bound;
  std::optional<std::size_t> runs, record_points, shown_run;
  std::optional<std::uint64_t> seed;
  std::optional<std::string> filters;       // comma-separated names
  std::optional<std::string> scheme;
  std::optional<std::string> report_times;  // "5,6,6.5"
  std::optional<std::string> windows;       // "0:4,4:9.2"
  std::optional<double> risk_epsilon;       // --risk-epsilon: J's eps, over the model's risk.epsilon
  std::optional<std::string> reference;     // --reference particles:N
  std::optional<std::string> x0;            // --x0 prior | model
  std::optional<std::string> stepping;      // --stepping generated | refined
};

// The most particles --reference accepts (the runtime's kMaxParticles; simulate_command checks
// that they agree): N doubles of n states per thread, so a typo cannot ask for terabytes.
inline constexpr std::size_t kMaxReferenceParticles = 1000000;

// The particle reference runs two independent sets of N particles on every run (the second one
// only to estimate the first's Monte Carlo error; pfgen_runtime::ParticleReferenceOptions).
inline constexpr std::size_t kReferenceParticleSets = 2;

// --reference's text "particles:N" -> N, a whole number 1 .. kMaxReferenceParticles; anything
// else is a CliValueError naming --reference.
std::size_t parse_reference(const std::string& text);

// The exponential criterion J of every filter (docs/theory.md, "The exponential criterion J"),
// asked for by the model's `risk:` section or --risk-epsilon.
struct CriterionSettings {
  double epsilon = 1;          // finite, > 0
  std::vector<double> weight;  // M, n x n row-major; empty: the identity
};

// The `simulation:` fields as checked; pfgen's defaults are the merge's, not these zeros.
struct SimulationSettings {
  double T = 0;
  double dt = 0;
  std::size_t runs = 0;
  std::uint64_t seed = 0;
  std::vector<std::string> filters;  // empty: every filter of the model
  std::string scheme;
  std::vector<double> report_times;
  std::vector<std::pair<double, double>> windows;
  std::size_t record_points = 0;
  double bound = 0;
  std::size_t shown_run = 0;
  std::optional<CriterionSettings> criterion;  // unset: J is not computed, the output is as before
  // --reference particles:N: the bootstrap particle filter's N (docs/theory.md §7.4); unset: no
  // reference, the output as before.
  std::optional<std::size_t> reference_particles;
  // Each run's truth from a draw of N(m0, P0) (--x0 prior, or the model's `x0: prior`), instead of
  // the model's fixed x0.
  bool x0_from_prior = false;
  // --stepping: refined (the default) splits a continuous filter's grid step where one step() would
  // change P too fast (pfgen_runtime::FilterStepper); generated takes one step() per grid step, as
  // the generated code a user deploys does.
  bool refined_stepping = true;
};

// Throws CliValueError naming the option (or the model file's field) and what is wrong.
SimulationSettings resolve_simulation_settings(const Model& model, const SimulationOverrides& overrides);

}  // namespace pfgen::cli
