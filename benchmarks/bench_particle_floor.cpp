// What a particle step of the particle reference cannot go below on this machine, keeping its
// random streams and results: each particle step draws q normals from its run's one stream (the
// polar method: 1.27 uniform pairs, a logarithm, a division and a square root per pair, in
// sequence, since xoshiro's state is a chain) and takes one std::exp for its weight. Those are
// timed here in isolation, beside the machine's scalar and packed arithmetic peak, so that
// bench_particles.sh's figures can be read against them (docs/benchmarks.md).
//
//   bench_particle_floor [--count N]
#include <chrono>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <string>
#include <vector>

#include "pfgen_runtime/random.hpp"

namespace {

using Clock = std::chrono::steady_clock;

double ns_per(Clock::time_point start, std::size_t count) {
  return std::chrono::duration<double, std::nano>(Clock::now() - start).count() / static_cast<double>(count);
}

// Keeps a value alive without letting the compiler see through it.
volatile double sink;
void keep(double value) { sink = value; }

}  // namespace

int main(int argc, char** argv) {
  std::size_t count = 20000000;
  for (int a = 1; a < argc; ++a) {
    if (std::strcmp(argv[a], "--count") == 0 && a + 1 < argc) {
      count = std::strtoull(argv[++a], nullptr, 10);
    } else {
      std::fprintf(stderr, "usage: bench_particle_floor [--count N]\n");
      return 2;
    }
  }
  using pfgen_runtime::RandomStream;
  std::vector<double> out(count);

  Clock::time_point start = Clock::now();
  RandomStream uniforms(1, 2, 3);
  double sum = 0;
  for (std::size_t k = 0; k < count; ++k) sum += uniforms.uniform();
  keep(sum);
  const double uniform_ns = ns_per(start, count);

  start = Clock::now();
  RandomStream one(1, 2, 3);
  for (std::size_t k = 0; k < count; ++k) out[k] = one.normal();
  const double normal_ns = ns_per(start, count);

  start = Clock::now();
  RandomStream many(1, 2, 3);
  for (std::size_t k = 0; k + 32 <= count; k += 32) many.normals(out.data() + k, 32);
  const double normals_ns = ns_per(start, count);

  // exp and log of independent arguments (throughput, as in the weight loop).
  for (std::size_t k = 0; k < count; ++k) out[k] = -std::abs(out[k]);
  start = Clock::now();
  sum = 0;
  for (std::size_t k = 0; k < count; ++k) sum += std::exp(out[k]);
  keep(sum);
  const double exp_ns = ns_per(start, count);
  start = Clock::now();
  sum = 0;
  for (std::size_t k = 0; k < count; ++k) sum += std::log(1.0 - out[k]);
  keep(sum);
  const double log_ns = ns_per(start, count);

  // Arithmetic peak: 8 independent multiply-add chains, scalar and as the compiler packs them.
  const std::size_t rounds = count / 8;
  double acc[8] = {1, 2, 3, 4, 5, 6, 7, 8};
  const double factor = 0.999999, offset = 1e-9;
  start = Clock::now();
  for (std::size_t k = 0; k < rounds; ++k)
    for (double& a : acc) a = a * factor + offset;
  const double flop_ns = ns_per(start, rounds * 16);
  for (double a : acc) keep(a);

  std::printf("per call on this machine (%zu calls each):\n", count);
  std::printf("  uniform()                %6.2f ns\n", uniform_ns);
  std::printf("  normal()                 %6.2f ns   (polar method, one at a time)\n", normal_ns);
  std::printf("  normals(), blocks of 32  %6.2f ns   (the same values)\n", normals_ns);
  std::printf("  std::exp                 %6.2f ns\n", exp_ns);
  std::printf("  std::log                 %6.2f ns\n", log_ns);
  std::printf("  arithmetic               %6.3f ns per flop (%.2f Gflop/s, 8 chains of multiply-add)\n", flop_ns,
              1.0 / flop_ns);
  std::printf("floor of a particle step with q = 1 (one normal, one exp): %.1f ns\n", normals_ns + exp_ns);
  return 0;
}
