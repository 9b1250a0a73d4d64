// Drives the generated optimal filter of Basin, Perez & Skliar 2006's example (dx = 0.1 x^2 dt + 0.1 x^2 dW1,
// dy = x dt + dW2) against a simulated truth with pfgen's runtime (pfgen::runtime), without the
// `pfgen simulate` command: the truth by the adaptive Euler scheme, its observations, seeded
// Monte Carlo runs with guards. A trivial estimate runs beside the filter on the same runs: m
// stays at the filter's initial m0, as if no observation arrived. The filter must beat it;
// tests/consumer_project.cmake checks that from the printed lines.
#include <cstdio>
#include <vector>

#include <Eigen/Core>
#include <pfgen_runtime/monte_carlo.hpp>
#include <pfgen_runtime/observation.hpp>
#include <pfgen_runtime/schemes.hpp>
#include <pfgen_runtime/sde_system.hpp>
#include <pfgen_runtime/simulation.hpp>

#include "basin2006_quadratic/optimal.hpp"  // generated at build time by pfgen_add_filter

namespace filter = pfgen_models::basin2006_quadratic::optimal;
namespace rt = pfgen_runtime;

int main() {
  // The truth: the model's SDE as callbacks (pfgen simulate compiles them from the model file).
  rt::SdeSystem system;
  system.n = 1;
  system.q = 1;
  system.drift = [](double, const double* x, double* f) { f[0] = 0.1 * x[0] * x[0]; };
  system.diffusion = [](double, const double* x, double* g) { g[0] = 0.1 * x[0] * x[0]; };
  const rt::AdaptiveEuler truth(system);  // superlinear coefficients: see runtime/README.md
  const rt::Observation observation(Eigen::VectorXd::Zero(1), Eigen::MatrixXd::Identity(1, 1),
                                          Eigen::MatrixXd::Identity(1, 1));
  const Eigen::VectorXd x0 = Eigen::VectorXd::Constant(1, 1.1);

  // The generated filter, and the trivial estimate: the same initial state, never updated.
  const rt::FilterModel optimal =
      rt::make_filter_model("optimal", filter::n, filter::p, &filter::initial_state, &filter::step);
  rt::FilterModel prior = optimal;
  prior.name = "prior";
  prior.timing = std::make_unique<rt::GridSteps>([](double*, double, double, const double*) {});

  rt::MonteCarloOptions options;
  options.grid = rt::TimeGrid::to_horizon(0.0, 4.0, 1e-3);
  options.runs = 100;
  options.seed = 2006;
  options.threads = 2;  // the results do not depend on it
  const rt::MonteCarloResult result = rt::run_monte_carlo(truth, observation, x0, {optimal, prior}, options);

  std::printf("runs %zu t %g dt %g scheme %s\n", result.runs, result.grid.end(), result.grid.dt,
              result.scheme.c_str());
  for (const rt::FilterStatistics& f : result.filters)
    std::printf("rms_%s %.6g completed %zu diverged %zu\n", f.name.c_str(), f.horizon.rms[0], f.horizon.runs,
                f.divergences.count());
  std::printf("rms_ratio %.4g\n", result.filters[0].horizon.rms[0] / result.filters[1].horizon.rms[0]);
  // Run 0's filter state at the end (the last record time).
  const Eigen::Index last = static_cast<Eigen::Index>(result.series.t.size()) - 1;
  std::printf("x %.9g\n", result.series.truth(last, 0));
  std::printf("m1 %.9g\n", result.series.filters[0].m(last, 0));
  std::printf("P11 %.9g\n", result.series.filters[0].P_diagonal(last, 0));
  return 0;
}
