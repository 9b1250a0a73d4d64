#pragma once
// The check that makes benchmarks/bench_handwritten's baseline worth timing, shared with
// tests/test_handwritten_agreement.cpp: pfgen's generated `optimal` filter and the hand-written
// Kalman-Bucy filter (handwritten_kalman_bucy.hpp) start from the same state and, stepped over the
// same increments dy, end in the same state.
#include <algorithm>
#include <cmath>
#include <cstddef>
#include <vector>

#include "support/handwritten_kalman_bucy.hpp"

namespace pfgen_test {

// The hand-written (m, P) in the generated layout: m, then P's upper triangle row by row.
template <class Scalar, int N, int Q>
std::vector<Scalar> flat_state(const typename HandwrittenKalmanBucy<Scalar, N, Q>::Vec& m,
                               const typename HandwrittenKalmanBucy<Scalar, N, Q>::Mat& P) {
  std::vector<Scalar> state(m.data(), m.data() + N);
  for (int i = 0; i < N; ++i)
    for (int j = i; j < N; ++j) state.push_back(P(i, j));
  return state;
}

// max_k |a_k - b_k| / max_k |b_k|: one scale for the whole state, so that an entry near zero is
// not held to a relative bound it cannot meet.
template <class Scalar>
double relative_difference(const std::vector<Scalar>& a, const std::vector<Scalar>& b) {
  double scale = 0, difference = 0;
  for (std::size_t k = 0; k < b.size(); ++k) {
    scale = std::max(scale, std::abs(double(b[k])));
    difference = std::max(difference, std::abs(double(a[k]) - double(b[k])));
  }
  return difference / std::max(scale, 1e-300);
}

struct Agreement {
  double initial = 0;  // relative difference of the initial states
  double final = 0;    // relative difference after every step
  double moved = 0;    // how far the hand-written state moved from its start, relative: a check
                       // of two states that never left m0 and P0 would prove nothing
};

// Both filters from their initial states over dy (Q entries per step, steps = dy.size() / Q);
// `initial_state(Scalar*)` and `step(Scalar* state, const Scalar* dy)` are the generated filter's.
template <class Scalar, int N, int Q, class InitialState, class Step>
Agreement handwritten_agreement(const HandwrittenKalmanBucy<Scalar, N, Q>& hand, InitialState initial_state, Step step,
                                const std::vector<Scalar>& dy, Scalar dt) {
  std::vector<Scalar> generated(N + N * (N + 1) / 2);
  initial_state(generated.data());
  typename HandwrittenKalmanBucy<Scalar, N, Q>::Vec m = hand.m0();
  typename HandwrittenKalmanBucy<Scalar, N, Q>::Mat P = hand.P0();
  Agreement result;
  const std::vector<Scalar> start = flat_state<Scalar, N, Q>(m, P);
  result.initial = relative_difference(generated, start);
  for (std::size_t k = 0; k + Q <= dy.size(); k += Q) {
    step(generated.data(), dy.data() + k);
    hand.step(m, P, dy.data() + k, dt);
  }
  const std::vector<Scalar> end = flat_state<Scalar, N, Q>(m, P);
  result.final = relative_difference(generated, end);
  result.moved = relative_difference(start, end);
  return result;
}

}  // namespace pfgen_test
