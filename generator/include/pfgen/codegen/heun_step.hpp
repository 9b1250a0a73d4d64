#pragma once
// The element-wise loops of a filter's Heun step, as statements for every language: the parts of
// an increment (the innovation dy - h dt, the rates times dt, a gain times the innovation), step()'s
// predictor and corrector around an increment, and the average of the two increments. Each
// observation module composes its increment from these parts (its rates and innovation differ),
// after its own statements that give their inputs (local arrays and the calls that fill them), and
// the templates place the blocks ({{increment_body}}, or the continuous file's parts ending with
// {{increment_loops}}; {{step_increments}}, {{average_loop}}), holding no statement of their own; the
// names they use (delta, dy, state, t, dt, params, first, predicted, second) are the templates' frame's.
//
// The loops run to the file's sizes n, p and state_size (ir::dimension). Written out, each loop is
// one statement per entry with its index as a number, in the loop's order (so the arithmetic, and
// the result, is the loop's). The continuous filter writes them out below kStepWrittenOutBelow
// states: g++ -O2 (GCC 12) neither unrolls loops this short whose unrolling grows the code nor
// vectorises them wider than the vector its trip count is a multiple of: a state of 14 entries went
// two floats at a time from rates()' scalar stores. Dense linear n = 4, float, -O2: these loops took
// 482 of the step's 1 396 instructions (callgrind); the step went from 1.40x to 1.19x hand-written
// Eigen with these loops alone written out, -O3 and -O3 -march=native unchanged (docs/benchmarks.md,
// "Generated code against hand-written code"). The polynomial and delayed filters, whose steps were
// not measured so, keep their loops.
#include <cstddef>
#include <functional>
#include <string>

#include "pfgen/codegen/ir/statements.hpp"

namespace pfgen::codegen {

// The same threshold as the P drift's full block (kFullCombineBelow): below 8 states the filter
// state has at most 35 entries.
inline constexpr std::size_t kStepWrittenOutBelow = 8;

// The loops of the step of a filter of n states, p observations and a state of state_size entries
// (m, then P's upper triangle, then what else the filter carries).
class HeunStepLoops {
 public:
  // An entry of an array, given its index (a loop's name or a written-out number).
  using Entry = std::function<ir::Expr(const ir::Expr& index)>;

  HeunStepLoops(std::size_t n, std::size_t p, std::size_t state_size, bool written_out);

  // innovation[r] = dy[r] - observation[r] dt for each r < p.
  void innovation(ir::Block& block, const std::string& observation, const ir::Expr& dt) const;
  // delta[i] = rate(i) dt for each i < state_size.
  void scaled_rates(ir::Block& block, const Entry& rate, const ir::Expr& dt) const;
  // delta[i] += gain[i p + r] innovation(r) for each i < n and r < p: m's correction by K.
  void state_gain(ir::Block& block, const std::string& gain, const Entry& innovation) const;
  // delta[n + u] += gain[u p + r] innovation(r) for each u < state_size - n and r < p: P's by L.
  void covariance_gain(ir::Block& block, const std::string& gain, const Entry& innovation) const;
  // predicted[i] = state[i] + first[i] for each i < state_size: the predictor's end state.
  ir::Block predicted() const;
  // state[i] += (first[i] + second[i]) / 2 for each i < state_size: the trapezoid of the two increments.
  ir::Block average() const;

  // The statements of one increment: of the state `state` at the step's start (`end` false) or at
  // its end, into the array `delta` (the calls of the file's functions that give it).
  using Increment = std::function<ir::Block(bool end, const ir::Expr& state, const ir::Expr& delta)>;
  // step()'s predictor and corrector: the local arrays first, predicted and second (state_size
  // entries; `written_first`: declared as arrays written before they are read, ir::LocalArrays),
  // increment(start, state, first), predicted(), increment(end, predicted, second).
  ir::Block predictor_corrector(const Increment& increment, bool written_first = false) const;

 private:
  // for index < count: body(index), or written out body(0), body(1), ...
  void each(ir::Block& block, const std::string& index, const ir::Expr& count_size, std::size_t count,
            const std::function<ir::Statement(const ir::Expr&)>& body) const;
  // delta[offset + row] += gain[row p + r] innovation(r) for row < rows (`rows_size` in the file) and r < p.
  void gain_times_innovation(ir::Block& block, const std::string& index, std::size_t first_row, std::size_t rows,
                             const ir::Expr& rows_size, const std::string& gain, const Entry& innovation) const;

  std::size_t n_, p_, state_size_;
  bool written_out_;
};

}  // namespace pfgen::codegen
