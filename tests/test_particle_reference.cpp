// The particle reference (runtime/include/pfgen_runtime/particle_reference.hpp, docs/theory.md
// §7.4): on a linear Gaussian model the Kalman-Bucy filter is the true conditional mean, so the
// particle mean's RMS distance from it must shrink like 1/sqrt(N); the reference's numbers are
// the same for any thread count and after travelling between processes (run_codec); inputs it
// cannot handle are refused; without it nothing changes.
#include <catch2/catch.hpp>

#include <cmath>
#include <cstring>
#include <optional>
#include <regex>
#include <stdexcept>
#include <string>
#include <vector>

#include <Eigen/Core>

#include "pfgen_runtime/monte_carlo.hpp"
#include "pfgen_runtime/particle_reference.hpp"
#include "pfgen_runtime/results_csv.hpp"
#include "pfgen_runtime/schemes.hpp"
#include "pfgen_runtime/summary_table.hpp"
#include "support/scalar_linear_system.hpp"
#include "support/shared_runs.hpp"

using namespace pfgen_runtime;
using pfgen_test::ScalarLinear;
using pfgen_test::scalar_linear_system;
using pfgen_test::scalar_observation;

namespace {

// Kalman-Bucy for dx = -a x dt + s dW1, dy = x dt + r dW2, in the generated calling convention:
// the exact conditional mean for the Gaussian prior N(m0, P0) (up to the O(dt) of its explicit
// step, far below the Monte Carlo distances measured here).
FilterModel kalman_bucy(const ScalarLinear& model) {
  FilterModel filter;
  filter.name = "kalman-bucy";
  filter.n = 1;
  filter.p = 1;
  filter.initial_state = [model](double* state) {
    state[0] = model.m0;
    state[1] = model.P0;
  };
  filter.timing = std::make_unique<GridSteps>([model](double* state, double, double dt, const double* dy) {
    const double m = state[0], P = state[1], K = P / (model.r * model.r);
    state[0] = m - model.a * m * dt + K * (dy[0] - m * dt);
    state[1] = P + (-2 * model.a * P + model.s * model.s - P * P / (model.r * model.r)) * dt;
  });
  return filter;
}

ParticleReferenceOptions prior(const ScalarLinear& model, std::size_t particles) {
  ParticleReferenceOptions options;
  options.particles = particles;
  options.m0 = Eigen::VectorXd::Constant(1, model.m0);
  options.P0 = Eigen::MatrixXd::Constant(1, 1, model.P0);
  return options;
}

bool same_bits(const Eigen::MatrixXd& a, const Eigen::MatrixXd& b) {
  return a.rows() == b.rows() && a.cols() == b.cols() &&
         (a.size() == 0 || std::memcmp(a.data(), b.data(), sizeof(double) * static_cast<std::size_t>(a.size())) == 0);
}

bool same_bits(const std::vector<double>& a, const std::vector<double>& b) {
  return a.size() == b.size() && (a.empty() || std::memcmp(a.data(), b.data(), sizeof(double) * a.size()) == 0);
}

// The distances RMS(m - m_ref) for N = 100, 400, 1600 particles shrink like 1/sqrt(N): each fourfold
// N halves them (within Monte Carlo scatter), and at N = 1600 the reference is far closer to the
// exact filter than the filter is to the truth.
void check_shrinks_like_inverse_root(const std::vector<double>& distance, double filter_rms) {
  REQUIRE(distance.size() == 3);
  INFO("RMS(m - m_ref) for N = 100, 400, 1600: " << distance[0] << ", " << distance[1] << ", " << distance[2]);
  CHECK(distance[0] / distance[1] >= 1.4);
  CHECK(distance[0] / distance[1] <= 2.9);
  CHECK(distance[1] / distance[2] >= 1.4);
  CHECK(distance[1] / distance[2] <= 2.9);
  CHECK(distance[2] < 0.1 * filter_rms);
}

}  // namespace

TEST_CASE("particle reference: its distance from Kalman-Bucy shrinks like 1/sqrt(N) on a linear Gaussian model",
          "[particles][runtime][statistical]") {
  ScalarLinear model;
  model.m0 = 0.5;
  model.P0 = 0.8;
  EulerMaruyama scheme(scalar_linear_system(model));
  const Observation observation = scalar_observation(model.r);
  const Eigen::VectorXd x0 = Eigen::VectorXd::Constant(1, 0.2);
  MonteCarloOptions options;
  options.grid = TimeGrid::to_horizon(0.0, 3.0, 0.005);
  options.runs = 40;
  options.seed = 2026;
  options.threads = 2;
  options.record_points = 10;

  std::vector<double> distance;
  double filter_rms = 0;
  for (std::size_t particles : {100, 400, 1600}) {
    options.reference = prior(model, particles);
    const MonteCarloResult result = run_monte_carlo(scheme, observation, x0, {kalman_bucy(model)}, options);
    REQUIRE(result.reference);
    REQUIRE(result.filters[0].reference);
    const ReferenceComparison& c = *result.filters[0].reference;
    CHECK(c.runs == options.runs);
    CHECK(result.reference->stopped.count() == 0);
    CHECK(result.reference->mean_resamplings > 0);  // the weights degenerate and are renewed
    distance.push_back(c.distance[0]);
    filter_rms = c.filter_rms[0];
    // The reference is (nearly) the conditional mean, so its error is the filter's: both close to
    // sqrt(P_inf) = 0.47 here.
    CHECK(c.reference_rms[0] == Approx(c.filter_rms[0]).epsilon(0.1));
    // Orthogonality of the conditional mean, here Kalman-Bucy's m: the particle mean's error
    // splits as |x - m_ref|^2 = |x - m|^2 + |m - m_ref|^2 in the mean.
    CHECK(c.reference_rms[0] * c.reference_rms[0] ==
          Approx(c.filter_rms[0] * c.filter_rms[0] + c.distance[0] * c.distance[0]).epsilon(0.05));
    // Kalman-Bucy is the conditional mean, so its distance from m_ref is the reference's own
    // Monte Carlo error, which the second particle set estimates without knowing it.
    INFO("N = " << particles << ": own error " << result.reference->error[0] << ", distance " << c.distance[0]);
    CHECK(result.reference->error_runs == options.runs);
    CHECK(result.reference->error[0] == Approx(c.distance[0]).epsilon(0.2));
  }
  check_shrinks_like_inverse_root(distance, filter_rms);
}

// Samples y_k = x(t_k) + r v_k every `period` of the scalar OU truth.
Observation scalar_samples(double period, double r) {
  return Observation::sampled(1, 1, 1, period, [r](double, double* C0, double* C, double* Uv) {
    C0[0] = 0;
    C[0] = 1;
    Uv[0] = r;
  });
}

// The Kalman filter of the Euler-Maruyama chain x' = (1 - a h) x + s dW on the grid step h,
// sampled every period: the exact conditional mean of the truth the particles simulate. One
// prediction per grid step (substeps = grid steps per period), so that between samples its m is
// the predicted mean at every grid point, not one held from the last sample.
FilterModel sampled_kalman(const ScalarLinear& model, double h, double r, std::size_t steps_per_sample) {
  FilterModel filter;
  filter.name = "kalman";
  filter.n = 1;
  filter.p = 1;
  filter.initial_state = [model](double* state) {
    state[0] = model.m0;
    state[1] = model.P0;
  };
  filter.timing = std::make_unique<SampledSteps>(
      steps_per_sample,
      [model, h](double* state, double, double dt) {
        const long steps = std::lround(dt / h);
        for (long k = 0; k < steps; ++k) {
          state[0] *= 1 - model.a * h;
          state[1] = (1 - model.a * h) * (1 - model.a * h) * state[1] + model.s * model.s * h;
        }
      },
      [r](double* state, double, const double* y) {
        const double S = state[1] + r * r, K = state[1] / S;
        state[0] += K * (y[0] - state[0]);
        state[1] *= 1 - K;
        return true;
      });
  return filter;
}

TEST_CASE("particle reference: with sampled observations it approaches the exact Kalman filter like 1/sqrt(N)",
          "[particles][runtime][statistical]") {
  ScalarLinear model;
  model.m0 = 0.5;
  model.P0 = 0.8;
  const double r = 0.4, dt = 0.01;
  EulerMaruyama scheme(scalar_linear_system(model));
  const Observation samples = scalar_samples(0.1, r);
  MonteCarloOptions options;
  options.grid = TimeGrid::to_horizon(0.0, 3.0, dt);
  options.runs = 40;
  options.seed = 99;
  options.threads = 2;
  options.record_points = 10;
  std::vector<double> distance;
  double filter_rms = 0;
  for (std::size_t particles : {100, 400, 1600}) {
    options.reference = prior(model, particles);
    const MonteCarloResult result =
        run_monte_carlo(scheme, samples, Eigen::VectorXd::Constant(1, 0.2), {sampled_kalman(model, dt, r, 10)}, options);
    REQUIRE(result.filters[0].reference);
    const ReferenceComparison& c = *result.filters[0].reference;
    CHECK(c.runs == options.runs);
    CHECK(result.reference->mean_resamplings > 0);
    distance.push_back(c.distance[0]);
    filter_rms = c.filter_rms[0];
    CHECK(c.reference_rms[0] * c.reference_rms[0] ==
          Approx(c.filter_rms[0] * c.filter_rms[0] + c.distance[0] * c.distance[0]).epsilon(0.05));
  }
  check_shrinks_like_inverse_root(distance, filter_rms);
}

TEST_CASE("particle reference: identical for 1, 2 and 3 threads and after travelling between processes",
          "[particles][runtime][unit]") {
  ScalarLinear model;
  EulerMaruyama scheme(scalar_linear_system(model));
  const Observation observation = scalar_observation(model.r);
  const Eigen::VectorXd x0 = Eigen::VectorXd::Constant(1, 0.3);
  MonteCarloOptions options;
  options.grid = TimeGrid::to_horizon(0.0, 2.0, 0.01);
  options.runs = 9;
  options.seed = 5;
  options.record_points = 20;
  options.shown_run = 3;
  options.truth_guard = DivergenceGuard(1.2);  // some truths (and particles) stop: partial runs are covered
  options.reference = prior(model, 64);
  const std::vector<FilterModel> filters{kalman_bucy(model)};

  std::string table, csv;
  MonteCarloResult first;
  for (unsigned threads : {1u, 2u, 3u}) {
    options.threads = threads;
    const MonteCarloResult result = run_monte_carlo(scheme, observation, x0, filters, options);
    if (threads == 1) {
      table = format_summary_table(result, {"x"});
      csv = format_results_csv(result, {"x"});
      first = result;
      CHECK(result.truth_divergences.count() > 0);
      CHECK(result.truth_divergences.count() < result.runs);
      CHECK(table.find("Distance to the particle reference (N = 64 particles") != std::string::npos);
      CHECK(csv.find(",reference_m_x,reference_err_x,reference_err_x_rms,kalman-bucy_dref_x,kalman-bucy_dref_x_rms,"
                   "kalman-bucy_err_x_rms,kalman-bucy_nees,kalman-bucy_nees_low,kalman-bucy_nees_high\n") !=
            std::string::npos);
      CHECK(result.timing.reference_steps > 0);
      continue;
    }
    INFO("threads = " << threads);
    CHECK(format_summary_table(result, {"x"}) == table);
    CHECK(format_results_csv(result, {"x"}) == csv);
    CHECK(same_bits(result.series.reference_m, first.series.reference_m));
    CHECK(same_bits(result.filters[0].reference->distance, first.filters[0].reference->distance));
    CHECK(result.timing.reference_steps == first.timing.reference_steps);
  }

  // Shared among "processes" (MonteCarloOptions::share): the reference's per-run results and
  // record series are exchanged and gathered with the rest, and fold to the same table and CSV.
  const std::vector<MonteCarloResult> shared = pfgen_test::SharedRuns(2).run({4, 5}, [&](RunShare share) {
    MonteCarloOptions part = options;
    part.threads = 1;
    part.share = std::move(share);
    return run_monte_carlo(scheme, observation, x0, filters, part);
  });
  const MonteCarloResult& folded = shared[0];
  REQUIRE(folded.folded);
  CHECK(format_summary_table(folded, {"x"}) == table);
  CHECK(format_results_csv(folded, {"x"}) == csv);
  CHECK(folded.timing.reference_steps == first.timing.reference_steps);
}

TEST_CASE("particle reference: a run's reference depends on (seed, run, N) only, and N = 1 follows one particle",
          "[particles][runtime][unit]") {
  ScalarLinear model;
  EulerMaruyama scheme(scalar_linear_system(model));
  Observation observation = scalar_observation(model.r);
  const TimeGrid grid = TimeGrid::to_horizon(0.0, 1.0, 0.01);
  TruthRun truth = simulate_truth(scheme, observation, Eigen::VectorXd::Constant(1, 0.3), grid, 11, 2);
  REQUIRE(truth.completed_steps == grid.steps);

  Eigen::MatrixXd a(1, grid.steps + 1), b(1, grid.steps + 1);
  ParticleReference one(scheme, observation, prior(model, 50), 1e8), two(scheme, observation, prior(model, 50), 1e8);
  const ParticleReferenceRun ra = one.run(grid, truth.dy, static_cast<std::ptrdiff_t>(grid.steps), 11, 2, a);
  (void)one.run(grid, truth.dy, static_cast<std::ptrdiff_t>(grid.steps), 11, 3, b);  // another run between
  const ParticleReferenceRun rb = two.run(grid, truth.dy, static_cast<std::ptrdiff_t>(grid.steps), 11, 2, b);
  CHECK(ra.last == static_cast<std::ptrdiff_t>(grid.steps));
  CHECK_FALSE(ra.stopped);
  CHECK(same_bits(a, b));
  CHECK(ra.resamplings == rb.resamplings);
  CHECK(ra.particle_steps == 50 * grid.steps);

  // One particle: weights cannot change a single particle's mean, so it is the prior draw
  // propagated by the scheme with the stream's increments, the path of an Euler-Maruyama truth.
  ParticleReference single(scheme, observation, prior(model, 1), 1e8);
  const ParticleReferenceRun rs = single.run(grid, truth.dy, static_cast<std::ptrdiff_t>(grid.steps), 11, 2, a);
  CHECK(rs.last == static_cast<std::ptrdiff_t>(grid.steps));
  RandomStream stream(11, 2, substream::particle_reference);
  double x = model.m0 + std::sqrt(model.P0) * stream.normal();
  CHECK(a(0, 0) == x);
  Eigen::VectorXd dW(1), state(1);
  state[0] = x;
  EulerMaruyama replay(scalar_linear_system(model));
  for (std::size_t k = 0; k < grid.steps; ++k) {
    stream.wiener_increment(grid.dt, dW);
    replay.step(grid.time(k), state, grid.dt, dW);
    // One particle: the ESS is always 1 >= N/2, no resampling, no uniforms drawn.
  }
  CHECK(a(0, static_cast<Eigen::Index>(grid.steps)) == state[0]);
  CHECK(rs.resamplings == 0);
}

TEST_CASE("particle reference: particles beyond the bound die, and when all have the reference stops and is counted",
          "[particles][runtime][unit]") {
  // A prior far from the truth's small bound: every particle starts beyond it.
  ScalarLinear model;
  model.m0 = 5.0;
  model.P0 = 0.01;
  EulerMaruyama scheme(scalar_linear_system(model));
  const Observation observation = scalar_observation(model.r);
  MonteCarloOptions options;
  options.grid = TimeGrid::to_horizon(0.0, 1.0, 0.01);
  options.runs = 3;
  options.truth_guard = DivergenceGuard(2.0);
  options.reference = prior(model, 20);
  const MonteCarloResult result =
      run_monte_carlo(scheme, observation, Eigen::VectorXd::Zero(1), {kalman_bucy(model)}, options);
  REQUIRE(result.reference);
  CHECK(result.reference->stopped.count() == 3);
  CHECK(result.reference->stopped.earliest() == 0.0);
  CHECK(result.reference->horizon.runs == 0);
  CHECK(result.filters[0].reference->runs == 0);
  const std::string table = format_summary_table(result, {"x"});
  CHECK(table.find("Reference stopped (every particle diverged): 3 of 3 runs, first at t = 0") != std::string::npos);
  CHECK(table.find("nan") == std::string::npos);
  CHECK(format_stops_csv(result) ==
        "source,event,run,t\nreference,stopped,0,0\nreference,stopped,1,0\nreference,stopped,2,0\n");
}

TEST_CASE("particle reference: refused where it cannot run, and absent the outputs are as before",
          "[particles][runtime][unit]") {
  ScalarLinear model;
  EulerMaruyama scheme(scalar_linear_system(model));
  Observation observation = scalar_observation(model.r);
  const Eigen::VectorXd x0 = Eigen::VectorXd::Constant(1, 0.3);
  MonteCarloOptions options;
  options.grid = TimeGrid::to_horizon(0.0, 1.0, 0.01);
  options.runs = 3;
  const std::vector<FilterModel> filters{kalman_bucy(model)};
  const MonteCarloResult without = run_monte_carlo(scheme, observation, x0, filters, options);
  CHECK_FALSE(without.reference);
  CHECK_FALSE(without.filters[0].reference);
  CHECK(format_summary_table(without, {"x"}).find("particle reference") == std::string::npos);
  CHECK(format_results_csv(without, {"x"}).find("reference") == std::string::npos);
  CHECK(format_timing(without).find("particle reference") == std::string::npos);
  CHECK(format_stops_csv(without) == "source,event,run,t\n");

  auto refused = [&](const ParticleReferenceOptions& reference, const TruthScheme& truth,
                     const Observation& obs) {
    MonteCarloOptions bad = options;
    bad.reference = reference;
    CHECK_THROWS_AS(run_monte_carlo(truth, obs, x0, filters, bad), std::invalid_argument);
  };
  refused(prior(model, 0), scheme, observation);
  refused(prior(model, kMaxParticles + 1), scheme, observation);
  ParticleReferenceOptions negative = prior(model, 10);
  negative.P0(0, 0) = -1;
  refused(negative, scheme, observation);
  ParticleReferenceOptions wrong_size = prior(model, 10);
  wrong_size.m0 = Eigen::VectorXd::Zero(2);
  refused(wrong_size, scheme, observation);
  // No process noise: a deterministic truth (RK4 with q = 0).
  SdeSystem deterministic = scalar_linear_system(model);
  deterministic.q = 0;
  deterministic.diffusion = nullptr;
  RungeKutta4 ode(deterministic);
  CHECK_THROWS_WITH(ParticleReference(ode, observation, prior(model, 10), 1e8), Catch::Contains("no process noise"));
  // Delayed observations.
  Observation delayed = observation;
  delayed.set_delay(0.1);
  CHECK_THROWS_WITH(ParticleReference(scheme, delayed, prior(model, 10), 1e8), Catch::Contains("delayed"));
}

TEST_CASE("particle reference: every filter is paired against the closest, and the table says which is worse",
          "[particles][runtime][statistical]") {
  ScalarLinear model;
  EulerMaruyama scheme(scalar_linear_system(model));
  const Observation observation = scalar_observation(model.r);
  MonteCarloOptions options;
  options.grid = TimeGrid::to_horizon(0.0, 2.0, 0.01);
  options.runs = 30;
  options.seed = 48;
  options.record_points = 10;
  options.reference = prior(model, 400);
  options.initial_prior = InitialPrior{Eigen::VectorXd::Constant(1, model.m0), Eigen::MatrixXd::Constant(1, 1, model.P0)};
  // Kalman-Bucy's m with its gain multiplied: 3 is far off, 1.2 a little.
  auto off_gain = [&model](const std::string& name, double factor) {
    FilterModel filter = kalman_bucy(model);
    filter.name = name;
    filter.timing = std::make_unique<GridSteps>([model, factor](double* state, double, double dt, const double* dy) {
      const double m = state[0], P = state[1], K = factor * P / (model.r * model.r);
      state[0] = m - model.a * m * dt + K * (dy[0] - m * dt);
      state[1] = P + (-2 * model.a * P + model.s * model.s - P * P / (model.r * model.r)) * dt;
    });
    return filter;
  };
  const std::vector<FilterModel> filters{off_gain("far", 3.0), kalman_bucy(model), off_gain("near", 1.2)};
  const MonteCarloResult result = run_monte_carlo(scheme, observation, Eigen::VectorXd::Zero(1), filters, options);
  REQUIRE(result.reference);
  const ClosestToReference& c = result.reference->closest[0];
  CHECK(c.closest == 1);
  REQUIRE(c.others.size() == 2);
  CHECK(c.others[0].filter == 2);  // nearest first
  CHECK(c.others[1].filter == 0);
  CHECK(c.runner_up == std::optional<std::size_t>(2));
  CHECK(c.difference == c.others[0].difference);
  CHECK(c.others[1].runs == 30);
  CHECK(c.others[1].significant());
  CHECK(c.others[1].difference > c.others[0].difference);
  const std::string table = format_summary_table(result, {"x"});
  INFO(table);
  CHECK(table.find("\nPaired against the closest to the reference run by run") != std::string::npos);
  CHECK(std::regex_search(table, std::regex("\nfar +x +kalman-bucy +30 +\\+[0-9.e-]+ ± [0-9.e-]+ +yes\n")));
  CHECK(table.find("m_ref's own error") != std::string::npos);
}
