#pragma once
// One generated filter of bench_handwritten as the benchmark sees it: plain function pointers into
// its own translation unit (benchmarks/CMakeLists.txt writes one per size and scalar).
#include <cstddef>

namespace pfgen_bench {

template <class Scalar>
struct GeneratedFilter {
  // `steps` generated step() calls over dy (p entries per step), in place on state.
  void (*run)(Scalar* state, const Scalar* dy, std::size_t steps, Scalar dt);
  void (*initial_state)(Scalar* state);
  std::size_t n, p, state_size;
};

struct Options {
  int repeats = 11;
  double min_time_ms = 100;
  bool with_float = true;
  int only_n = 0;  // --n: time this size alone (0: every size)
};

}  // namespace pfgen_bench
