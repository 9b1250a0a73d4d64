// Stepping many states at once (TruthScheme::step_batch, RandomStream::normals, the particle
// reference's blocks) is a speed-up only: every lane must get the bits it gets stepped alone, the
// schemes' own draws must come in lane order, and the particle reference must not depend on
// whether its scheme has batched functions. Each batched path is compared here with the
// one-state path it replaces.
#include <catch2/catch.hpp>

#include <cmath>
#include <cstring>
#include <limits>
#include <random>
#include <vector>

#include <Eigen/Core>

#include "pfgen_runtime/particle_reference.hpp"
#include "pfgen_runtime/random.hpp"
#include "pfgen_runtime/schemes.hpp"
#include "pfgen_runtime/simulation.hpp"

using namespace pfgen_runtime;

namespace {

bool same_bits(double a, double b) { return std::memcmp(&a, &b, sizeof a) == 0; }

// A one-state function as a batched one, state by state, as a plugin's batch::lanes does.
SdeSystem::Batch lanes(std::function<void(double, const double*, double*)> one, std::size_t in, std::size_t out) {
  return [one, in, out](double t, std::size_t count, const double* x, double* values) {
    std::vector<double> state(in), value(out);
    for (std::size_t k = 0; k < count; ++k) {
      for (std::size_t i = 0; i < in; ++i) state[i] = x[i * count + k];
      one(t, state.data(), value.data());
      for (std::size_t e = 0; e < out; ++e) values[e * count + k] = value[e];
    }
  };
}

// Two states, two noises, superlinear and state-multiplicative, so that AdaptiveEuler bisects the
// grid steps of states far out and takes the others whole.
SdeSystem coupled(bool batched) {
  SdeSystem system;
  system.n = 2;
  system.q = 2;
  system.drift = [](double t, const double* x, double* f) {
    f[0] = 0.1 * x[0] * x[0] - x[1] + 0.5 * t;
    f[1] = -0.3 * x[0] * x[1];
  };
  system.diffusion = [](double, const double* x, double* g) {
    g[0] = 0.1 * x[0] * x[0];
    g[1] = 0.2;
    g[2] = 0.05 * x[1];
    g[3] = 0.1 * x[0] * x[1];
  };
  system.diffusion_jacobian = [](double, const double* x, double* dg) {  // [(i q + j) n + l]
    const double values[8] = {0.2 * x[0], 0, 0, 0, 0, 0.05, 0.1 * x[1], 0.1 * x[0]};
    for (int k = 0; k < 8; ++k) dg[k] = values[k];
  };
  if (batched) {
    system.drift_batch = lanes(system.drift, 2, 2);
    system.diffusion_batch = lanes(system.diffusion, 2, 4);
  }
  return system;
}

// Lanes with states near 0 (whole steps), far out (bisected), dead (NaN, never touched) and
// beyond any bound (1e200: a step overflows).
struct Lanes {
  std::size_t count;
  std::vector<double> x;   // entry-major
  std::vector<LaneFlag> live;
};

Lanes some_lanes(std::size_t count, std::mt19937& rng) {
  std::uniform_real_distribution<double> near(-1.5, 1.5), far(20.0, 60.0);
  Lanes lanes{count, std::vector<double>(2 * count), std::vector<LaneFlag>(count, 1)};
  for (std::size_t k = 0; k < count; ++k) {
    const bool out = k % 5 == 2;
    lanes.x[k] = out ? far(rng) : near(rng);
    lanes.x[count + k] = near(rng);
    if (k % 7 == 3) {
      lanes.live[k] = 0;
      lanes.x[k] = std::numeric_limits<double>::quiet_NaN();
    }
  }
  return lanes;
}

std::vector<double> increments(std::size_t count, std::size_t q, double dt, RandomStream& stream) {
  std::vector<double> dW(q * count);
  for (std::size_t k = 0; k < count; ++k)
    for (std::size_t j = 0; j < q; ++j) dW[j * count + k] = std::sqrt(dt) * stream.normal();
  return dW;
}

// Steps `lanes` 30 times by step_batch on one clone and lane by lane by step() on another, both
// keyed for the same run; every lane's bits and liveness must agree after every step.
void check_against_step(const TruthScheme& prototype, std::size_t count) {
  std::mt19937 rng(static_cast<unsigned>(count));
  Lanes batch = some_lanes(count, rng), single = batch;
  auto many = prototype.clone(), one = prototype.clone();
  many->start_run(5, 9);
  one->start_run(5, 9);
  RandomStream noise(5, 9, substream::truth_noise);
  const std::size_t n = prototype.system().n, q = prototype.system().q;
  const double dt = 0.01;
  Eigen::VectorXd x(static_cast<Eigen::Index>(n)), dW(static_cast<Eigen::Index>(q));
  for (int step = 0; step < 30; ++step) {
    const double t = 0.01 * step;
    const std::vector<double> increment = increments(count, q, dt, noise);
    many->step_batch(t, count, batch.x.data(), dt, increment.data(), batch.live.data());
    for (std::size_t k = 0; k < count; ++k) {
      if (!single.live[k]) continue;
      for (std::size_t i = 0; i < n; ++i) x[static_cast<Eigen::Index>(i)] = single.x[i * count + k];
      for (std::size_t j = 0; j < q; ++j) dW[static_cast<Eigen::Index>(j)] = increment[j * count + k];
      one->step(t, x, dt, dW);
      if (one->last_step_incomplete()) single.live[k] = 0;
      for (std::size_t i = 0; i < n; ++i) single.x[i * count + k] = x[static_cast<Eigen::Index>(i)];
    }
    for (std::size_t k = 0; k < count; ++k) {
      INFO(prototype.name() << ": step " << step << ", lane " << k << " of " << count);
      REQUIRE(batch.live[k] == single.live[k]);
      if (!single.live[k]) continue;
      for (std::size_t i = 0; i < n; ++i) REQUIRE(same_bits(batch.x[i * count + k], single.x[i * count + k]));
    }
  }
}

}  // namespace

TEST_CASE("batch stepping: every truth scheme's step_batch gives each lane the bits of step(), draws in lane order",
          "[runtime][batch][unit]") {
  for (const bool batched : {true, false}) {  // the schemes' own batched paths, and the default loop over step()
    for (const SchemeKind kind : {SchemeKind::euler_maruyama, SchemeKind::milstein, SchemeKind::derivative_free_milstein,
                                  SchemeKind::tamed_euler, SchemeKind::adaptive_euler}) {
      const auto scheme = make_scheme(kind, coupled(batched));
      for (const std::size_t count : {1, 7, 32, 33}) check_against_step(*scheme, count);
    }
  }
  // A deterministic truth: RK4 through the default loop.
  SdeSystem ode = coupled(true);
  ode.q = 0;
  ode.diffusion = nullptr;
  ode.diffusion_batch = nullptr;
  check_against_step(RungeKutta4(ode), 9);
}

TEST_CASE("batch stepping: adaptive Euler's batched step bisects the lanes far out and stops a lane out of budget",
          "[runtime][batch][unit]") {
  std::mt19937 rng(4);
  Lanes lanes = some_lanes(32, rng);
  std::size_t live = 0;
  for (LaneFlag alive : lanes.live) live += alive ? 1 : 0;
  AdaptiveEuler roomy(coupled(true));
  roomy.start_run(1, 2);
  RandomStream noise(1, 2, substream::truth_noise);
  const std::vector<double> dW = increments(32, 2, 0.01, noise);
  Lanes copy = lanes;
  roomy.step_batch(0.0, 32, copy.x.data(), 0.01, dW.data(), copy.live.data());
  CHECK(roomy.substeps() > live);  // some lanes bisected
  CHECK(copy.live == lanes.live);

  AdaptiveEuler::Options tight;
  tight.max_substeps = 2;
  AdaptiveEuler strict(coupled(true), tight);
  strict.start_run(1, 2);
  strict.step_batch(0.0, 32, lanes.x.data(), 0.01, dW.data(), lanes.live.data());
  for (std::size_t k = 0; k < 32; ++k) {
    INFO("lane " << k << " at x = " << copy.x[k]);
    if (k % 7 == 3) CHECK(lanes.live[k] == 0);  // dead before
    else if (k % 5 == 2) CHECK(lanes.live[k] == 0);  // far out: more than 2 substeps
    else CHECK(lanes.live[k] == 1);
  }
}

TEST_CASE("batch stepping: normals() gives the values, and leaves the stream, of as many normal() calls",
          "[runtime][batch][random][unit]") {
  RandomStream one(3, 4, 5), many(3, 4, 5);
  std::vector<double> out;
  for (const std::size_t count : {0, 1, 2, 3, 0, 31, 32, 1, 33, 1000, 5}) {
    out.assign(count + 1, 0.0);
    many.normals(out.data(), count);
    for (std::size_t k = 0; k < count; ++k) {
      INFO("count " << count << ", value " << k);
      REQUIRE(same_bits(out[k], one.normal()));
    }
    CHECK(out[count] == 0.0);  // nothing written beyond
    REQUIRE(same_bits(many.normal(), one.normal()));  // the spare and the engine where normal() left them
    REQUIRE(many.next_u64() == one.next_u64());
  }
}

TEST_CASE("batch stepping: the particle reference is the same whether its scheme steps particles in blocks or alone",
          "[runtime][batch][particles][unit]") {
  // dy = (x1 + 0.5 x2^2 ... ) through a linear observation of both states (p = 2: the general
  // weight path) and of the first only (p = 1: the fast path); adaptive Euler, some particles far
  // out; N around the block width.
  const TimeGrid grid = TimeGrid::to_horizon(0.0, 0.5, 0.01);
  for (const int p : {1, 2}) {
    Eigen::VectorXd A0 = Eigen::VectorXd::Zero(p);
    Eigen::MatrixXd A = Eigen::MatrixXd::Identity(p, 2), B = 0.5 * Eigen::MatrixXd::Identity(p, p);
    Observation observation(A0, A, B);
    AdaptiveEuler truth_scheme(coupled(true));
    const TruthRun truth = simulate_truth(truth_scheme, observation, Eigen::Vector2d(0.5, -0.2), grid, 8, 1);
    REQUIRE(truth.completed_steps == grid.steps);
    ParticleReferenceOptions options;
    options.m0 = Eigen::Vector2d(0.0, 0.0);
    options.P0 = Eigen::Matrix2d::Identity() * 4.0;
    for (const std::size_t N : {1, 31, 32, 33, 100}) {
      options.particles = N;
      Eigen::MatrixXd blocked(2, grid.steps + 1), alone(2, grid.steps + 1);
      ParticleReference in_blocks(AdaptiveEuler(coupled(true)), observation, options, 1e6);
      ParticleReference one_by_one(AdaptiveEuler(coupled(false)), observation, options, 1e6);
      const auto a = in_blocks.run(grid, truth.dy, static_cast<std::ptrdiff_t>(grid.steps), 8, 1, blocked);
      const auto b = one_by_one.run(grid, truth.dy, static_cast<std::ptrdiff_t>(grid.steps), 8, 1, alone);
      INFO("p = " << p << ", N = " << N);
      CHECK(a.last == b.last);
      CHECK(a.resamplings == b.resamplings);
      CHECK(a.particle_steps == b.particle_steps);
      CHECK(std::memcmp(blocked.data(), alone.data(), sizeof(double) * static_cast<std::size_t>(blocked.size())) == 0);
    }
  }
}

TEST_CASE("batch stepping: WienerIncrements gives, step by step, the increments wiener_increment draws",
          "[runtime][batch][random][unit]") {
  for (const std::size_t size : {0, 1, 2, 3}) {
    RandomStream ahead_stream(6, 7, substream::truth_noise), step_stream(6, 7, substream::truth_noise);
    WienerIncrements ahead(ahead_stream, size, 0.003);
    Eigen::VectorXd dW(static_cast<Eigen::Index>(size));
    for (int step = 0; step < 700; ++step) {  // across chunk boundaries (256 steps a chunk)
      const double* drawn = ahead.next();
      step_stream.wiener_increment(0.003, dW);
      for (std::size_t j = 0; j < size; ++j) {
        INFO("size " << size << ", step " << step << ", entry " << j);
        REQUIRE(same_bits(drawn[j], dW[static_cast<Eigen::Index>(j)]));
      }
    }
    CHECK(ahead.size() == size);
  }
}

TEST_CASE("batch stepping: WienerIncrements::next_chunk gives a chunk of steps, next()'s values in its order",
          "[runtime][batch][random][unit]") {
  constexpr std::size_t chunk = WienerIncrements::kChunkSteps;
  for (const std::size_t size : {0, 1, 3}) {
    RandomStream chunk_stream(8, 9, substream::observation_noise), step_stream(8, 9, substream::observation_noise);
    WienerIncrements chunks(chunk_stream, size, 0.02), steps(step_stream, size, 0.02);
    for (int c = 0; c < 3; ++c) {  // a whole chunk, then next() and next_chunk() alternating
      const bool by_chunk = c != 1;
      const double* drawn = by_chunk ? chunks.next_chunk() : nullptr;
      for (std::size_t s = 0; s < chunk; ++s) {
        const double* one = by_chunk ? drawn + s * size : chunks.next();
        const double* expected = steps.next();
        for (std::size_t j = 0; j < size; ++j) {
          INFO("size " << size << ", chunk " << c << ", step " << s << ", entry " << j);
          REQUIRE(same_bits(one[j], expected[j]));
        }
      }
    }
  }
}

TEST_CASE("batch stepping: a linear observation's increment over lanes is increment()'s, lane by lane",
          "[runtime][batch][observation][unit]") {
  const std::size_t p = 2, n = 3, r = 2;
  std::mt19937_64 random(5);
  std::normal_distribution<double> normal;
  // Time-varying coefficients (with a -0.0 in A0), and constant ones.
  const Observation varying(p, n, r, [](double t, Eigen::VectorXd& A0, Eigen::MatrixXd& A, Eigen::MatrixXd& B) {
    A0 << -0.0, std::sin(t);
    A << 1.0, -2.0 * t, 0.5, 0.0, 3.0, -1.0 + t;
    B << 1.0, 0.25 * t, 0.0, 2.0;
  });
  Eigen::MatrixXd A(p, n), B(p, r);
  A << 0.3, -1.0, 2.0, 0.0, 1.5, -0.7;
  B << 0.9, 0.0, 0.1, 1.1;
  const Observation constant(Eigen::Vector2d(0.2, -0.4), A, B);
  for (const Observation* model : {&varying, &constant}) {
    Observation lanes_model = *model, one_model = *model;
    for (const std::size_t count : {1, 2, 5, 8}) {
      std::vector<double> x_start(n * count), x_end(n * count), dW2(r * count), dy(p * count);
      for (double& v : x_start) v = normal(random);
      for (double& v : x_end) v = normal(random);
      for (double& v : dW2) v = 0.01 * normal(random);
      x_start[0] = 0.0;  // a lane whose rate may be a signed zero
      x_end[0] = 0.0;
      lanes_model.increment_lanes(0.3, 0.01, count, x_start.data(), x_end.data(), dW2.data(), dy.data());
      for (std::size_t k = 0; k < count; ++k) {
        Eigen::VectorXd start(n), end(n), noise(r), one(p);
        for (std::size_t i = 0; i < n; ++i) {
          start[static_cast<Eigen::Index>(i)] = x_start[i * count + k];
          end[static_cast<Eigen::Index>(i)] = x_end[i * count + k];
        }
        for (std::size_t j = 0; j < r; ++j) noise[static_cast<Eigen::Index>(j)] = dW2[j * count + k];
        one_model.increment(0.3, 0.01, start, end, noise, one);
        for (std::size_t a = 0; a < p; ++a) {
          INFO("count " << count << ", lane " << k << ", entry " << a);
          CHECK(same_bits(dy[a * count + k], one[static_cast<Eigen::Index>(a)]));
        }
      }
    }
  }
}
