#pragma once
// The element-wise loops of the continuous filter's Heun step, as statements for every language
// (the templates' {{increment_loops}}, {{predicted_loop}} and {{average_loop}}): the innovation
// dy - h dt, the increment rates dt + K (dy - h dt), the predicted state and the average of the two
// increments.
//
// From kStepWrittenOutBelow states on they are loops over the named sizes. Below it each loop is
// written out, one statement per entry with its index as a number, in the loop's order (so the
// arithmetic, and the result, is the loop's). g++ -O2 (GCC 12) neither unrolls loops this short
// whose unrolling grows the code nor vectorises them wider than the vector its trip count is a
// multiple of: a state of 14 entries went two floats at a time from rates()' scalar stores. Dense
// linear n = 4, float, -O2: these loops took 482 of the step's 1 396 instructions (callgrind); the
// step went from 1.40x to 1.19x hand-written Eigen with these loops alone written out, -O3 and
// -O3 -march=native unchanged (docs/benchmarks.md, "Generated code against hand-written code").
#include <cstddef>
#include "pfgen/codegen/ir/statements.hpp"

namespace pfgen::codegen {

// The same threshold as the P drift's full block (kFullCombineBelow): below 8 states the filter
// state has at most 35 entries.
inline constexpr std::size_t kStepWrittenOutBelow = 8;

struct HeunStepLoops {
  ir::Block increment, predicted, average;
};

// The loops for a filter of n states, p observations and a state of state_size entries (m, then
// P's upper triangle). The loops run to the file's sizes n, p and state_size (ir::dimension).
HeunStepLoops heun_step_loops(std::size_t n, std::size_t p, std::size_t state_size);

}  // namespace pfgen::codegen
