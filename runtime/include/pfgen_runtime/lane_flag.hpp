#pragma once

#include <cstddef>
#include <cstdint>

namespace pfgen_runtime {

// A lane's flag in batched stepping (live, or taking a step): 1.0 or 0.0, a double like the values
// it selects between, so that the loops over lanes vectorise: a char flag beside doubles keeps
// them scalar, and SSE2 cannot compare 64-bit integers.
using LaneFlag = double;

// The lanes whose flag is set among `count`: the flags' sum, in four running sums, exact in any
// order (whole numbers far below 2^53), which the compiler packs; one running sum, or a count of
// flags != 0, is a chain of dependent operations, one lane after another.
inline std::uint64_t lanes_set(const LaneFlag* flags, std::size_t count) {
  double sums[4] = {0.0, 0.0, 0.0, 0.0};
  std::size_t k = 0;
  for (; k + 4 <= count; k += 4)
    for (std::size_t j = 0; j < 4; ++j) sums[j] += flags[k + j];
  for (; k < count; ++k) sums[0] += flags[k];
  return static_cast<std::uint64_t>((sums[0] + sums[1]) + (sums[2] + sums[3]));
}

}  // namespace pfgen_runtime
