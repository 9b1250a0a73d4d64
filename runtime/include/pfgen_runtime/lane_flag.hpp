#pragma once

namespace pfgen_runtime {

// A lane's flag in batched stepping (live, or taking a step): 1.0 or 0.0, a double like the values
// it selects between, so that the loops over lanes vectorise: a char flag beside doubles keeps
// them scalar, and SSE2 cannot compare 64-bit integers.
using LaneFlag = double;

}  // namespace pfgen_runtime
