// bench_ins16: the 16-state strapdown INS of examples/ins16.yaml (docs/benchmarks.md, "A 16-state INS").
//
// 1. Operation counts of `derivatives()` for its `ekf` and `optimal` filters, with CSE and without
//    (the counts `pfgen codegen --stats` reports: every output as its own expression tree, or
//    after common-subexpression elimination), whole and in parts, to compare with PX4's
//    symbolically generated 24-state EKF covariance prediction (2882 operations for the 300
//    entries of its 24 x 24 symmetric P). derivatives() computes m's drift and P's drift
//    F P + P F^T + G - P A^T R^-1 A P (ekf; the optimal filter's moment terms in place of F P);
//    the parts are counted by generating the same filter with some of its equations zeroed:
//      P drift, no correction   m_drift = 0 and P_correction = 0: F P + P F^T + G alone,
//                               the continuous-time counterpart of PX4's prediction
//      P drift                  m_drift = 0: with the measurement term P A^T R^-1 A P
//      whole                    what derivatives() computes
//    Per entry: divided by the 136 entries of P's upper triangle (PX4: 2882 / 300).
// 2. ns per call of the generated derivatives() (double and float, each filter compiled in its own
//    translation unit at build time and called through a pointer), cycling over 64 random states
//    (a random unit quaternion, velocity, position and small biases; P = M M^T / n + 1e-4 I), with
//    the model's default parameters. Repetitions of the four are interleaved; the table gives
//    medians. Before timing, float and double must agree (1e-3 relative in the max norm).
//
// Usage: bench_ins16 [--repeats 11] [--min-time-ms 100]
#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <functional>
#include <random>
#include <string>
#include <vector>

#include "pfgen/codegen/filter_codegen.hpp"
#include "pfgen/derivation/filter_equations.hpp"
#include "pfgen/model/yaml_model_loader.hpp"

// The generated derivatives(), one translation unit each (benchmarks/CMakeLists.txt).
void ins16_double_ekf(const double* state, double* out);
void ins16_double_optimal(const double* state, double* out);
void ins16_float_ekf(const float* state, float* out);
void ins16_float_optimal(const float* state, float* out);

namespace {

using Clock = std::chrono::steady_clock;
constexpr std::size_t kN = 16;
constexpr std::size_t kStateSize = kN + kN * (kN + 1) / 2;
constexpr double kPx4Ops = 2882, kPx4Entries = 300;

inline void clobber_memory() { asm volatile("" : : : "memory"); }

double median(std::vector<double> v) {
  std::sort(v.begin(), v.end());
  const std::size_t k = v.size() / 2;
  return v.size() % 2 ? v[k] : 0.5 * (v[k - 1] + v[k]);
}

// derivatives()'s counts (naive, CSE) for the filter as given.
std::pair<std::size_t, std::size_t> derivative_ops(const pfgen::Model& model, const pfgen::FilterEquations& eq) {
  pfgen::codegen::CodegenOptions options;
  options.scalar = pfgen::codegen::ScalarMode::Double;
  const pfgen::codegen::GeneratedFilter code = pfgen::codegen::generate_filter_code(model, eq, options);
  for (const auto& f : code.functions)
    if (f.function == "derivatives") return {f.naive.total(), f.cse.total()};
  std::fprintf(stderr, "bench_ins16: no derivatives() counted\n");
  std::exit(1);
}

void print_ops(const pfgen::Model& model, pfgen::FilterKind kind, const char* name) {
  const pfgen::FilterEquations whole = pfgen::derive_filter(model, kind);
  pfgen::FilterEquations with_correction = whole;
  for (auto& m : with_correction.m_drift) m = pfgen::Polynomial();
  pfgen::FilterEquations prediction = with_correction;
  for (auto& c : prediction.P_correction) c = pfgen::Polynomial();
  const double entries = static_cast<double>(kN * (kN + 1) / 2);
  struct Part {
    const char* label;
    const pfgen::FilterEquations* eq;
  };
  for (const Part& part : {Part{"P drift, no correction", &prediction}, Part{"P drift", &with_correction},
                           Part{"whole derivatives()", &whole}}) {
    const auto [naive, cse] = derivative_ops(model, *part.eq);
    std::printf("%-8s %-24s %10zu %9zu %12.1f %10.1f %9.2fx\n", name, part.label, naive, cse,
                static_cast<double>(naive) / entries, static_cast<double>(cse) / entries,
                (static_cast<double>(cse) / entries) / (kPx4Ops / kPx4Entries));
  }
}

// Random valid filter states: m = (unit quaternion, v, p, biases), P = M M^T / n + 1e-4 I.
std::vector<std::vector<double>> random_states(std::size_t count) {
  std::mt19937_64 rng(16);
  std::normal_distribution<double> normal(0.0, 1.0);
  std::vector<std::vector<double>> states;
  for (std::size_t s = 0; s < count; ++s) {
    std::vector<double> state(kStateSize, 0.0);
    double norm = 0.0;
    for (std::size_t i = 0; i < 4; ++i) norm += (state[i] = normal(rng)) * state[i];
    for (std::size_t i = 0; i < 4; ++i) state[i] /= std::sqrt(norm);
    for (std::size_t i = 4; i < 7; ++i) state[i] = 10.0 * normal(rng);
    for (std::size_t i = 7; i < 10; ++i) state[i] = 50.0 * normal(rng);
    for (std::size_t i = 10; i < 16; ++i) state[i] = 0.01 * normal(rng);
    std::vector<double> M(kN * kN);
    for (double& x : M) x = 0.1 * normal(rng);
    std::size_t k = kN;
    for (std::size_t i = 0; i < kN; ++i)
      for (std::size_t j = i; j < kN; ++j) {
        double sum = i == j ? 1e-4 : 0.0;
        for (std::size_t l = 0; l < kN; ++l) sum += M[i * kN + l] * M[j * kN + l] / static_cast<double>(kN);
        state[k++] = sum;
      }
    states.push_back(state);
  }
  return states;
}

template <class Scalar>
std::function<double(std::size_t)> timing_loop(void (*f)(const Scalar*, Scalar*),
                                               const std::vector<std::vector<double>>& states) {
  std::vector<std::vector<Scalar>> typed;
  for (const auto& s : states) typed.emplace_back(s.begin(), s.end());
  return [f, typed](std::size_t rounds) {
    std::vector<Scalar> out(kStateSize);
    const auto start = Clock::now();
    for (std::size_t r = 0; r < rounds; ++r)
      for (const auto& s : typed) {
        f(s.data(), out.data());
        clobber_memory();
      }
    return std::chrono::duration<double>(Clock::now() - start).count();
  };
}

std::size_t calibrate(const std::function<double(std::size_t)>& loop, double min_seconds) {
  std::size_t rounds = 1;
  while (loop(rounds) < min_seconds) rounds *= 2;
  return rounds;
}

template <class A, class B>
double max_relative_difference(void (*a)(const A*, A*), void (*b)(const B*, B*), const std::vector<double>& state) {
  std::vector<A> sa(state.begin(), state.end()), oa(kStateSize);
  std::vector<B> sb(state.begin(), state.end()), ob(kStateSize);
  a(sa.data(), oa.data());
  b(sb.data(), ob.data());
  double scale = 0.0, difference = 0.0;
  for (std::size_t i = 0; i < kStateSize; ++i) {
    if (!std::isfinite(static_cast<double>(oa[i])) || !std::isfinite(static_cast<double>(ob[i]))) return INFINITY;
    scale = std::max(scale, std::fabs(static_cast<double>(oa[i])));
    difference = std::max(difference, std::fabs(static_cast<double>(oa[i]) - static_cast<double>(ob[i])));
  }
  return difference / scale;
}

}  // namespace

int main(int argc, char** argv) {
  int repeats = 11;
  double min_seconds = 0.1;
  for (int k = 1; k + 1 < argc; k += 2) {
    if (!std::strcmp(argv[k], "--repeats")) repeats = std::max(1, std::atoi(argv[k + 1]));
    else if (!std::strcmp(argv[k], "--min-time-ms")) min_seconds = std::max(1.0, std::atof(argv[k + 1])) / 1000.0;
    else {
      std::fprintf(stderr, "usage: bench_ins16 [--repeats 11] [--min-time-ms 100]\n");
      return 2;
    }
  }
  const pfgen::Model model = pfgen::load_model_file(PFGEN_INS16_MODEL);
  std::printf("derivatives() operations (ops_* / 136 entries of P's upper triangle; PX4's 24-state EKF\n"
              "covariance prediction: %.0f ops / %.0f entries = %.2f per entry)\n",
              kPx4Ops, kPx4Entries, kPx4Ops / kPx4Entries);
  std::printf("%-8s %-24s %10s %9s %12s %10s %10s\n", "filter", "counted", "ops_naive", "ops_cse", "naive/entry",
              "cse/entry", "cse/PX4");
  print_ops(model, pfgen::FilterKind::Ekf, "ekf");
  print_ops(model, pfgen::FilterKind::Optimal, "optimal");

  const auto states = random_states(64);
  for (const auto& s : states) {
    const double ekf = max_relative_difference(&ins16_double_ekf, &ins16_float_ekf, s);
    const double optimal = max_relative_difference(&ins16_double_optimal, &ins16_float_optimal, s);
    if (!(ekf <= 1e-3) || !(optimal <= 1e-3)) {
      std::fprintf(stderr, "bench_ins16: float and double derivatives() disagree (%.3g, %.3g)\n", ekf, optimal);
      return 1;
    }
  }
  struct Timed {
    const char* filter;
    const char* scalar;
    std::function<double(std::size_t)> loop;
  };
  std::vector<Timed> timed{{"ekf", "double", timing_loop(&ins16_double_ekf, states)},
                           {"ekf", "float", timing_loop(&ins16_float_ekf, states)},
                           {"optimal", "double", timing_loop(&ins16_double_optimal, states)},
                           {"optimal", "float", timing_loop(&ins16_float_optimal, states)}};
  std::vector<std::size_t> rounds;
  for (const auto& t : timed) rounds.push_back(calibrate(t.loop, min_seconds));
  std::vector<std::vector<double>> ns(timed.size());
  for (int r = 0; r < repeats; ++r)
    for (std::size_t k = 0; k < timed.size(); ++k)
      ns[k].push_back(timed[k].loop(rounds[k]) * 1e9 / static_cast<double>(rounds[k] * states.size()));
  std::printf("\nns per derivatives() call (median of %d repetitions of >= %.0f ms, 64 states)\n", repeats,
              min_seconds * 1000);
  std::printf("%-8s %-7s %10s %10s %10s\n", "filter", "scalar", "ns_median", "ns_min", "ns_max");
  for (std::size_t k = 0; k < timed.size(); ++k)
    std::printf("%-8s %-7s %10.0f %10.0f %10.0f\n", timed[k].filter, timed[k].scalar, median(ns[k]),
                *std::min_element(ns[k].begin(), ns[k].end()), *std::max_element(ns[k].begin(), ns[k].end()));
  return 0;
}
