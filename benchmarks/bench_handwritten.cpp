// ns per step of pfgen's generated optimal filter against a hand-written fixed-size Eigen
// implementation of the same Heun step, for the dense linear models of
// tests/support/dense_linear_system.hpp (n = 4, 8, 16, dense stable A, dense constant G, p = 3;
// float for n = 4 and 8, see benchmarks/CMakeLists.txt), where the optimal filter is the Kalman-Bucy filter (docs/benchmarks.md, "Generated code against hand-written
// code").
//
// Before timing, every case runs both filters from their initial states over the same 1000
// increments dy (an Euler-Maruyama path of the model, dt = 1e-3) and aborts unless their states
// agree to 1e-12 relative in double (1e-4 in float) at the start and at the end: a baseline that
// computes something else proves nothing.
//
// Timing: one sample is the whole 1000-step sequence run again and again from the initial state
// for at least --min-time-ms; the generated code is called through a pointer into its own
// translation unit, where step() is inlined into the loop; the hand-written step is inlined into
// its loop here. The two alternate within each repetition (which goes first alternates too); the
// table gives medians over repetitions of ns per step and of the per-repetition ratio.
//
// Op counts per step: the generated one from `pfgen codegen --stats` (rates(), the one function
// step() calls per increment, CSE count) plus step()'s own loops; the hand-written one by formula from
// the matrix products it writes (handwritten_ops below), since Eigen computes every entry of them.
//
// Usage: bench_handwritten [--repeats 11] [--min-time-ms 100] [--no-float] [--n N]
// (--n: the one size N alone, to repeat a cell)
#include <algorithm>
#include <chrono>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <string>
#include <vector>

#include "handwritten_cases.hpp"
#include "support/dense_linear_system.hpp"
#include "support/handwritten_agreement.hpp"

namespace pfgen_bench {
namespace {

using Clock = std::chrono::steady_clock;
constexpr std::size_t kSteps = 1000;
constexpr double kDt = 1e-3;
constexpr unsigned kSeed = 7;
constexpr int kObservations = 3;  // dense_linear_system's p

// Keeps the compiler from dropping work whose result is only in memory behind p.
inline void escape(const void* p) { asm volatile("" : : "g"(p) : "memory"); }

double median(std::vector<double> v) {
  std::sort(v.begin(), v.end());
  const std::size_t h = v.size() / 2;
  return v.size() % 2 ? v[h] : (v[h - 1] + v[h]) / 2;
}

// Operations (+ - * /) of one hand-written Heun step as written in handwritten_kalman_bucy.hpp,
// each dense product r x k times k x c counted as r c (2k - 1).
double handwritten_ops(double n, double p) {
  const double increment = n * p * (2 * n - 1)       // P C^T
                           + n * p * (2 * p - 1)     // K = (P C^T) R^-1
                           + n * n * (2 * n - 1)     // A P
                           + n * n * (2 * p - 1)     // K (P C^T)^T
                           + 4 * n * n               // A P + (A P)^T + W - ..., times dt
                           + n * (2 * n - 1) + n     // A m dt
                           + p * (2 * n - 1) + 2 * p  // dy - C m dt
                           + n * (2 * p - 1) + n;    // K (...) and the sum
  return 2 * increment + (n + n * n) + 3 * (n + n * n);  // predicted state, then the average
}

// Operations of one generated Heun step: rates()'s CSE count per increment plus
// detail::increment's loops (rates dt: state_size; the innovation dy - h dt: 2 p; K times it: 2 n p),
// and step()'s predicted state (state_size) and average (3 state_size).
double generated_ops(double function_ops, double n, double p, double state_size) {
  return 2 * (function_ops + state_size + 2 * p + 2 * n * p) + 4 * state_size;
}

// ns per step of run_once (kSteps steps), run for at least min_time_ms.
template <class F>
double ns_per_step(F&& run_once, double min_time_ms) {
  std::size_t calls = 0;
  const Clock::time_point start = Clock::now();
  double elapsed_ms = 0;
  do {
    run_once();
    ++calls;
    elapsed_ms = std::chrono::duration<double, std::milli>(Clock::now() - start).count();
  } while (elapsed_ms < min_time_ms);
  return elapsed_ms * 1e6 / (double(calls) * kSteps);
}

template <class Scalar, int N>
void measure(const Options& options, const GeneratedFilter<Scalar>& generated, double function_ops,
             const char* scalar, double tolerance) {
  using Hand = pfgen_test::HandwrittenKalmanBucy<Scalar, N, kObservations>;
  const pfgen_test::DenseLinearSystem system = pfgen_test::dense_linear_system(N);
  if (generated.n != std::size_t(N) || generated.p != system.p || system.p != std::size_t(kObservations)) {
    std::fprintf(stderr, "bench_handwritten: n = %d: the generated filter's sizes do not match the system\n", N);
    std::exit(1);
  }
  const Hand hand(system);
  const std::vector<double> dy_double = pfgen_test::dense_linear_increments(system, kSteps, kDt, kSeed);
  const std::vector<Scalar> dy(dy_double.begin(), dy_double.end());
  const Scalar dt = Scalar(kDt);

  // One step per call through the same run() that is timed (t = 0 each time: the model is
  // time-invariant, so t is unused).
  const pfgen_test::Agreement agreement = pfgen_test::handwritten_agreement(
      hand, generated.initial_state, [&](Scalar* state, const Scalar* y) { generated.run(state, y, 1, dt); }, dy, dt);
  if (!(agreement.initial <= tolerance && agreement.final <= tolerance)) {
    std::fprintf(stderr,
                 "bench_handwritten: n = %d %s: generated and hand-written filters disagree (relative %.3g at the "
                 "start, %.3g after %zu steps; bound %.3g): not timing a baseline that computes something else\n",
                 N, scalar, agreement.initial, agreement.final, kSteps, tolerance);
    std::exit(1);
  }

  std::vector<Scalar> start(generated.state_size), state(generated.state_size);
  generated.initial_state(start.data());
  auto run_generated = [&] {
    state = start;
    generated.run(state.data(), dy.data(), kSteps, dt);
    escape(state.data());
  };
  typename Hand::Vec m;
  typename Hand::Mat P;
  auto run_hand = [&] {
    m = hand.m0();
    P = hand.P0();
    for (std::size_t k = 0; k < kSteps; ++k) hand.step(m, P, dy.data() + k * kObservations, dt);
    escape(m.data());
    escape(P.data());
  };
  std::vector<double> gen_ns, hand_ns, ratios;
  for (int r = 0; r < options.repeats; ++r) {
    double g = 0, h = 0;
    if (r % 2 == 0) {
      g = ns_per_step(run_generated, options.min_time_ms);
      h = ns_per_step(run_hand, options.min_time_ms);
    } else {
      h = ns_per_step(run_hand, options.min_time_ms);
      g = ns_per_step(run_generated, options.min_time_ms);
    }
    gen_ns.push_back(g);
    hand_ns.push_back(h);
    ratios.push_back(g / h);
  }
  const double ops_gen = generated_ops(function_ops, N, kObservations, double(generated.state_size));
  const double ops_hand = handwritten_ops(N, kObservations);
  std::printf("%4d %-6s %10.1f %10.1f %8.2fx %10.0f %10.0f %8.2fx %10.1e\n", N, scalar, median(gen_ns), median(hand_ns),
              median(ratios), ops_gen, ops_hand, ops_gen / ops_hand, agreement.final);
  std::fflush(stdout);
}

}  // namespace

template <int N>
void run_case(const Options& options, const GeneratedFilter<double>& d, const GeneratedFilter<float>* f, double ops) {
  if (options.only_n != 0 && options.only_n != N) return;
  measure<double, N>(options, d, ops, "double", 1e-12);
  if (options.with_float && f) measure<float, N>(options, *f, ops, "float", 1e-4);
}

}  // namespace pfgen_bench

int main(int argc, char** argv) {
  pfgen_bench::Options options;
  for (int k = 1; k < argc; ++k) {
    const std::string arg = argv[k];
    if (arg == "--repeats" && k + 1 < argc) {
      options.repeats = std::atoi(argv[++k]);
    } else if (arg == "--min-time-ms" && k + 1 < argc) {
      options.min_time_ms = std::atof(argv[++k]);
    } else if (arg == "--n" && k + 1 < argc) {
      options.only_n = std::atoi(argv[++k]);
    } else if (arg == "--no-float") {
      options.with_float = false;
    } else {
      std::fprintf(stderr, "usage: bench_handwritten [--repeats 11] [--min-time-ms 100] [--no-float] [--n N]\n");
      return 2;
    }
  }
  if (options.repeats < 1 || options.min_time_ms <= 0) {
    std::fprintf(stderr, "bench_handwritten: --repeats must be >= 1 and --min-time-ms > 0\n");
    return 2;
  }
  std::printf("%4s %-6s %10s %10s %9s %10s %10s %9s %10s\n", "n", "scalar", "gen_ns", "hand_ns", "gen/hand", "gen_ops",
              "hand_ops", "ops_ratio", "agree_rel");
  pfgen_bench::run_cases(options);
  return 0;
}
