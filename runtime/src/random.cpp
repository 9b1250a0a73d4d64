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

}  // namespace pfgen_runtime
