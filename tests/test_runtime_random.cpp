// The runtime's random numbers: reference values of SplitMix64 and xoshiro256** (checked against
// an independent implementation of the published algorithms), the polar normal generator's
// law, and per-run streams that do not depend on the order or thread in which runs are made.
#include <catch2/catch.hpp>

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <thread>
#include <vector>

#include "pfgen_runtime/random.hpp"
#include "pfgen_runtime/simulation.hpp"

using namespace pfgen_runtime;

TEST_CASE("runtime: SplitMix64 and xoshiro256 star-star give the published sequences", "[runtime][random][unit]") {
  SplitMix64 splitmix(0);
  CHECK(splitmix.next() == 0xE220A8397B1DCDAFULL);
  CHECK(splitmix.next() == 0x6E789E6AA1B965F4ULL);
  CHECK(splitmix.next() == 0x06C45D188009454FULL);

  // xoshiro256** from the state {1, 2, 3, 4}.
  Xoshiro256StarStar engine(Xoshiro256StarStar::State{1, 2, 3, 4});
  const std::uint64_t expected[] = {0x2D00ULL, 0x0ULL, 0x5A007080ULL, 0x10E0000000009D80ULL, 0x10E0B61CE1009D80ULL,
                                    0x0870021CE143AD00ULL};
  for (std::uint64_t value : expected) CHECK(engine.next() == value);

  CHECK_THROWS_AS(Xoshiro256StarStar(Xoshiro256StarStar::State{0, 0, 0, 0}), std::invalid_argument);
}

TEST_CASE("runtime: a run's stream is fixed by its seed and run and substream", "[runtime][random][unit]") {
  // Values from an independent Python implementation of the derivation documented in random.cpp.
  CHECK(RandomStream::derive_key(42, 7, 1) == 0xA011CA63C3D7166FULL);
  RandomStream raw(42, 7, 1);
  CHECK(raw.next_u64() == 0x8EB24A6214E1F19AULL);
  CHECK(raw.next_u64() == 0x93C42925E1F7F773ULL);

  // Polar normals of the same stream. Only sqrt and log enter, so any libm within an ulp or two
  // reproduces them to ~1e-15; std::normal_distribution would not.
  RandomStream stream(42, 7, 1);
  const double normals[] = {1.5319345235339583, 2.0604030448243265, 2.8818846316360287,
                            -1.6993446664829455, -1.8684952944957423, -0.8387885380547186};
  for (double expected : normals) CHECK(stream.normal() == Approx(expected).epsilon(1e-14));

  // Distinct runs and substreams get distinct keys and distinct numbers.
  std::vector<std::uint64_t> keys;
  for (std::uint64_t run = 0; run < 1000; ++run)
    for (std::uint64_t sub = 0; sub < 4; ++sub) keys.push_back(RandomStream::derive_key(1, run, sub));
  std::sort(keys.begin(), keys.end());
  CHECK(std::adjacent_find(keys.begin(), keys.end()) == keys.end());
  RandomStream a(1, 0, substream::truth_noise), b(1, 1, substream::truth_noise), c(1, 0, substream::observation_noise),
      d(2, 0, substream::truth_noise);
  const std::uint64_t first = a.next_u64();
  CHECK(first != b.next_u64());
  CHECK(first != c.next_u64());
  CHECK(first != d.next_u64());
}

TEST_CASE("runtime: polar normals have the standard normal law", "[runtime][random][statistical]") {
  RandomStream stream(2024, 0);
  const int N = 1000000;
  double sum = 0, sum2 = 0, sum3 = 0, sum4 = 0;
  int beyond = 0;  // |z| > 1.959964: probability 0.05
  std::vector<int> bins(10, 0);  // deciles of the normal law
  const double deciles[] = {-1.2815515655446004, -0.8416212335729143, -0.5244005127080407, -0.2533471031357997, 0.0,
                            0.2533471031357997,  0.5244005127080407,  0.8416212335729143,  1.2815515655446004};
  for (int i = 0; i < N; ++i) {
    const double z = stream.normal();
    sum += z;
    sum2 += z * z;
    sum3 += z * z * z;
    sum4 += z * z * z * z;
    if (std::abs(z) > 1.959964) ++beyond;
    bins[std::upper_bound(std::begin(deciles), std::end(deciles), z) - std::begin(deciles)]++;
  }
  const double mean = sum / N, variance = sum2 / N - mean * mean;
  INFO("mean " << mean << " variance " << variance << " skew " << sum3 / N << " kurtosis " << sum4 / N);
  // Bands of 5 standard errors.
  CHECK(std::abs(mean) < 5 / std::sqrt(N));
  CHECK(std::abs(variance - 1) < 5 * std::sqrt(2.0 / N));
  CHECK(std::abs(sum3 / N) < 5 * std::sqrt(15.0 / N));
  CHECK(std::abs(sum4 / N - 3) < 5 * std::sqrt(96.0 / N));
  CHECK(std::abs(beyond / double(N) - 0.05) < 5 * std::sqrt(0.05 * 0.95 / N));
  // Chi-square over the ten equiprobable bins (9 degrees of freedom; 27.88 is the 0.001 point).
  double chi2 = 0;
  for (int count : bins) chi2 += (count - N / 10.0) * (count - N / 10.0) / (N / 10.0);
  INFO("chi-square " << chi2);
  CHECK(chi2 < 27.88);

  // Wiener increments are scaled by sqrt(dt).
  Eigen::VectorXd dW(3);
  RandomStream s1(5, 3), s2(5, 3);
  s1.wiener_increment(0.25, dW);
  for (int i = 0; i < 3; ++i) CHECK(dW[i] == 0.5 * s2.normal());
}

namespace {

// A small SDE with multiplicative noise and a time-varying observation, used to check that whole
// truth runs do not depend on the order in which they are simulated.
SdeSystem test_system() {
  SdeSystem system;
  system.n = 2;
  system.q = 2;
  system.drift = [](double t, const double* x, double* f) {
    f[0] = -x[0] + 0.1 * x[1] * x[1];
    f[1] = std::sin(t) - 0.5 * x[1];
  };
  system.diffusion = [](double, const double* x, double* g) {
    g[0] = 0.2 * x[0];
    g[1] = 0.1;
    g[2] = 0.0;
    g[3] = 0.3 + 0.1 * x[0] * x[0];
  };
  return system;
}

Observation test_observation() {
  return Observation(1, 2, 1, [](double t, Eigen::VectorXd& A0, Eigen::MatrixXd& A, Eigen::MatrixXd& B) {
    A0 << 0.1 * t;
    A << 1.0, 0.5;
    B << 1.0;
  });
}

bool identical(const TruthRun& a, const TruthRun& b) {
  return a.completed_steps == b.completed_steps && a.x.cols() == b.x.cols() && a.x == b.x && a.dy == b.dy;
}

}  // namespace

TEST_CASE("runtime: runs are identical whatever order or thread generates them", "[runtime][random][unit]") {
  const TimeGrid grid = TimeGrid::to_horizon(0.0, 2.0, 0.01);
  const int runs = 24;
  Eigen::VectorXd x0(2);
  x0 << 1.0, -0.5;

  for (SchemeKind kind : {SchemeKind::euler_maruyama, SchemeKind::adaptive_euler}) {
    INFO("scheme " << to_string(kind));
    auto simulate = [&](TruthScheme& scheme, Observation& observation, int run) {
      return simulate_truth(scheme, observation, x0, grid, 99, static_cast<std::uint64_t>(run));
    };
    std::vector<TruthRun> forward(runs), backward(runs), threaded(runs);
    {
      auto scheme = make_scheme(kind, test_system());
      Observation observation = test_observation();
      for (int r = 0; r < runs; ++r) forward[r] = simulate(*scheme, observation, r);
      for (int r = runs - 1; r >= 0; --r) backward[r] = simulate(*scheme, observation, r);
    }
    {
      // Two threads, each with its own scheme and observation, taking runs alternately.
      auto worker = [&](int first) {
        auto scheme = make_scheme(kind, test_system());
        Observation observation = test_observation();
        for (int r = first; r < runs; r += 2) threaded[r] = simulate(*scheme, observation, r);
      };
      std::thread one(worker, 1), two(worker, 0);
      one.join();
      two.join();
    }
    for (int r = 0; r < runs; ++r) {
      REQUIRE(forward[r].completed_steps == grid.steps);
      CHECK(identical(forward[r], backward[r]));
      CHECK(identical(forward[r], threaded[r]));
    }
    // And the runs differ from one another.
    CHECK(forward[0].x(0, 100) != forward[1].x(0, 100));
    CHECK(forward[0].dy(0, 10) != forward[1].dy(0, 10));
  }
}
