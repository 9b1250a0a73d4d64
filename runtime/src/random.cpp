#include "pfgen_runtime/random.hpp"

#include <stdexcept>

namespace pfgen_runtime {

Xoshiro256StarStar::Xoshiro256StarStar(std::uint64_t seed) {
  SplitMix64 seeder(seed);
  for (auto& word : s_) word = seeder.next();
  // Four consecutive SplitMix64 outputs are never all zero (its output function is a bijection of
  // distinct inputs), so the state is valid.
}

Xoshiro256StarStar::Xoshiro256StarStar(const State& state) : s_(state) {
  if (s_[0] == 0 && s_[1] == 0 && s_[2] == 0 && s_[3] == 0)
    throw std::invalid_argument("xoshiro256**: the all-zero state is not allowed");
}

std::uint64_t RandomStream::derive_key(std::uint64_t seed, std::uint64_t run, std::uint64_t substream) {
  // Each stage is a bijection of its second argument for a fixed first (an addition modulo 2^64
  // followed by the bijective mixer), so distinct runs, and distinct substreams of one run, get
  // distinct keys. The odd constants keep seed 0, run 0, substream 0 away from the zero word.
  const std::uint64_t seed_key = splitmix64_mix(seed + 0x9E3779B97F4A7C15ULL);
  const std::uint64_t run_key = splitmix64_mix(seed_key + run * 0xD1B54A32D192ED03ULL);
  return splitmix64_mix(run_key + (substream + 1) * 0xABC98388FB8FAC03ULL);
}

RandomStream::RandomStream(std::uint64_t seed, std::uint64_t run, std::uint64_t substream)
    : engine_(derive_key(seed, run, substream)) {}

void RandomStream::normals(double* out, std::size_t count) {
  std::size_t written = 0;
  if (count > 0 && has_spare_) {
    has_spare_ = false;
    out[written++] = spare_;
  }
  // The pairs normal() would accept, drawn in its order: a candidate is always stored, and kept
  // by advancing past it only when accepted, so that no branch depends on the random values.
  const std::size_t wanted = (count - written + 1) / 2;
  pairs_.resize(wanted + 1);  // + 1: the slot a rejected last candidate is written to
  std::size_t accepted = 0;
  while (accepted < wanted) {
    const double u = 2.0 * uniform() - 1.0;
    const double v = 2.0 * uniform() - 1.0;
    const double s = u * u + v * v;
    pairs_[accepted] = {u, v, s};
    accepted += (s < 1.0) & (s != 0.0);
  }
  for (std::size_t k = 0; k < wanted; ++k) {
    const Pair& pair = pairs_[k];
    const double factor = std::sqrt(-2.0 * std::log(pair.s) / pair.s);
    out[written++] = pair.u * factor;
    if (written < count) {
      out[written++] = pair.v * factor;
    } else {  // an odd count: the pair's second value is the next call's, as normal() keeps it
      spare_ = pair.v * factor;
      has_spare_ = true;
    }
  }
}

}  // namespace pfgen_runtime
