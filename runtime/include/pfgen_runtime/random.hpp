#pragma once
// Deterministic, portable random numbers for Monte Carlo runs.
//
// - SplitMix64 (Steele, Lea, Flood 2014) seeds and mixes.
// - xoshiro256** (Blackman, Vigna 2018) is the engine: 256 bits of state, period 2^256 - 1.
// - Normals come from Marsaglia's polar method written here, never from
//   std::normal_distribution, whose output differs between standard libraries. The polar method
//   needs only uniform doubles, sqrt (exact in IEEE arithmetic) and log.
// - Every (seed, run, substream) triple names its own stream, derived by hashing, so a run's
//   numbers do not depend on which thread generates it or in what order runs are generated.
#include <array>
#include <cmath>
#include <cstddef>
#include <cstdint>
#include <vector>

#include <Eigen/Core>

namespace pfgen_runtime {

// SplitMix64's output function: a bijection on 64-bit words with good avalanche.
inline std::uint64_t splitmix64_mix(std::uint64_t z) {
  z = (z ^ (z >> 30)) * 0xBF58476D1CE4E5B9ULL;
  z = (z ^ (z >> 27)) * 0x94D049BB133111EBULL;
  return z ^ (z >> 31);
}

class SplitMix64 {
 public:
  explicit SplitMix64(std::uint64_t seed) : state_(seed) {}
  std::uint64_t next() {
    state_ += 0x9E3779B97F4A7C15ULL;
    return splitmix64_mix(state_);
  }

 private:
  std::uint64_t state_;
};

class Xoshiro256StarStar {
 public:
  using State = std::array<std::uint64_t, 4>;
  // State from four SplitMix64 outputs of `seed`, as the xoshiro authors recommend.
  explicit Xoshiro256StarStar(std::uint64_t seed);
  // An explicit state; it must not be all zero (std::invalid_argument).
  explicit Xoshiro256StarStar(const State& state);

  std::uint64_t next() {
    const std::uint64_t result = rotl(s_[1] * 5, 7) * 9;
    const std::uint64_t t = s_[1] << 17;
    s_[2] ^= s_[0];
    s_[3] ^= s_[1];
    s_[1] ^= s_[2];
    s_[0] ^= s_[3];
    s_[2] ^= t;
    s_[3] = rotl(s_[3], 45);
    return result;
  }
  const State& state() const { return s_; }

 private:
  static std::uint64_t rotl(std::uint64_t x, int k) { return (x << k) | (x >> (64 - k)); }
  State s_;
};

// Substreams of one run: the truth's Wiener increments and the observation noise are drawn from
// different streams, so changing the truth scheme or the number of noise dimensions of one does
// not change the other's numbers.
namespace substream {
inline constexpr std::uint64_t truth_noise = 0;
inline constexpr std::uint64_t observation_noise = 1;
inline constexpr std::uint64_t initial_state = 2;
inline constexpr std::uint64_t truth_refinement = 3;  // Brownian-bridge draws of adaptive schemes
// The particle reference (particle_reference.hpp): its prior draws, the particles' Wiener
// increments and the resampling uniforms, and its scheme's own bridge draws.
inline constexpr std::uint64_t particle_reference = 4;
inline constexpr std::uint64_t particle_refinement = 5;
// The particle reference's second, independent set of particles (ParticleReference::run's `set`
// 1), which only estimates the first one's Monte Carlo error.
inline constexpr std::uint64_t second_particle_reference = 6;
inline constexpr std::uint64_t second_particle_refinement = 7;
}  // namespace substream

class RandomStream {
 public:
  // The stream of run `run` (0, 1, 2, ...) of a Monte Carlo job seeded with `seed`.
  RandomStream(std::uint64_t seed, std::uint64_t run, std::uint64_t substream = 0);
  // The 64-bit key the stream's engine is seeded from; injective in `run` for fixed seed and
  // substream, and in `substream` for fixed seed and run.
  static std::uint64_t derive_key(std::uint64_t seed, std::uint64_t run, std::uint64_t substream);

  std::uint64_t next_u64() { return engine_.next(); }
  // Uniform on [0, 1) with 53 random bits.
  double uniform() { return static_cast<double>(engine_.next() >> 11) * 0x1.0p-53; }
  // Standard normal, Marsaglia's polar method (the second value of each pair is kept for the next
  // call).
  double normal() {
    if (has_spare_) {
      has_spare_ = false;
      return spare_;
    }
    double u, v, s;
    do {
      u = 2.0 * uniform() - 1.0;
      v = 2.0 * uniform() - 1.0;
      s = u * u + v * v;
    } while (s >= 1.0 || s == 0.0);
    const double factor = std::sqrt(-2.0 * std::log(s) / s);
    spare_ = v * factor;
    has_spare_ = true;
    return u * factor;
  }
  // `count` standard normals into `out`: exactly the values of `count` calls of normal(), leaving
  // the stream as they would, but several times faster for long runs. The polar method's
  // rejection loop only picks the accepted pairs (branch-free), and their logarithms, divisions
  // and square roots, independent of one another, then overlap in the pipeline.
  void normals(double* out, std::size_t count);
  // dW ~ N(0, dt I): the Wiener increments of one step, entry by entry.
  void wiener_increment(double dt, Eigen::Ref<Eigen::VectorXd> dW) {
    const double scale = std::sqrt(dt);
    for (Eigen::Index i = 0; i < dW.size(); ++i) dW[i] = scale * normal();
  }

 private:
  Xoshiro256StarStar engine_;
  double spare_ = 0.0;
  bool has_spare_ = false;
  struct Pair {
    double u, v, s;
  };
  std::vector<Pair> pairs_;  // normals()' accepted pairs
};

// The Wiener increments of consecutive steps, dW ~ N(0, dt I) with `size` entries each, drawn
// ahead from one stream in chunks by normals(): the values wiener_increment would give step by
// step, at a fraction of the cost. The stream runs ahead of the steps taken.
class WienerIncrements {
 public:
  WienerIncrements(RandomStream& stream, std::size_t size, double dt)
      : stream_(stream), size_(size), scale_(std::sqrt(dt)), values_(kChunkSteps * size) {}
  // The next step's increment (size() entries), valid until the next call.
  const double* next() {
    if (used_ == kChunkSteps) used_ = 0;
    if (used_ == 0 && size_ > 0) {
      stream_.normals(values_.data(), values_.size());
      for (double& value : values_) value *= scale_;
    }
    return values_.data() + size_ * used_++;
  }
  // The increments of the next kChunkSteps steps at once (kChunkSteps * size() entries, step by
  // step), the values next() would give one call after another. Only at a chunk's start: before
  // the first next(), or after a multiple of kChunkSteps steps.
  const double* next_chunk() {
    const double* chunk = next();
    used_ = kChunkSteps;
    return chunk;
  }
  std::size_t size() const { return size_; }
  static constexpr std::size_t kChunkSteps = 256;

 private:
  RandomStream& stream_;
  std::size_t size_;
  double scale_;
  std::vector<double> values_;
  std::size_t used_ = 0;
};

}  // namespace pfgen_runtime
