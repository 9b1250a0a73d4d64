// Paper 004's example with the drift its printed truth follows (examples/paper004/quadratic_009.yaml:
// dx = 0.09 x^2 dt from 1.1, dy = x(t - 0.8) dt + dW2, m0 = 0.1, P0 = 1), its filters generated
// with `pfgen codegen --dt 0.001`, run on two readings of what y is before t = h, which the paper
// does not say:
//   x(0)  x(s) = x(0) for s < 0, the pre-history `pfgen simulate` uses (docs/theory.md §2.6): for
//         t < h every dy carries x(0) = 1.1, which the comparators use and the Phi* filter, whose
//         gain is 0 before h, does not;
//   none  x(s) = 0 for s < 0: no signal before t = h.
// The truth is the closed form x(t) = 1.1 / (1 - 0.099 t); dy_k = (x_{k-D} + x_{k+1-D}) dt/2 + dW2
// as the runtime forms it, dW2 from pfgen_runtime::RandomStream(seed, run, observation noise), so the
// x(0) reading is the same data as `pfgen simulate` draws. Prints the mean estimate at t = 1..4 of
// each filter over the runs, ± standard error, beside the paper's printed values, and the mean |x - m|
// (docs/reproductions/basin-rodriguez-gonzalez-martinez-zuniga-2004.md).
//
//   paper004_prehistory [RUNS [SEED]]     (defaults 2000 runs, seed 4)
#include <cmath>
#include <cstdint>
#include <cstdio>
#include <cstdlib>
#include <string>
#include <vector>

#include "paper004_quadratic_009/delay_ekf.hpp"
#include "paper004_quadratic_009/delay_optimal.hpp"
#include "paper004_quadratic_009/delay_uncorrected.hpp"
#include "paper004_quadratic_009/ekf_printed.hpp"
#include "pfgen_runtime/random.hpp"

namespace {

namespace optimal = bench_p4::paper004_quadratic_009::delay_optimal;
constexpr double step_size = optimal::dt();
constexpr std::size_t D = optimal::delay_steps;
constexpr std::size_t steps = 4000;  // T = 4
constexpr double report_times[] = {1, 2, 3, 4};

double truth(double t) { return 1.1 / (1.0 - 0.099 * t); }

// m at t = 1..4 of one filter over one run's dy.
template <class Filter>
std::vector<double> estimates(const std::vector<double>& dy) {
  Filter filter;
  std::vector<double> m;
  for (std::size_t k = 0; k < steps; ++k) {
    filter.step(&dy[k]);
    for (double t : report_times)
      if (k + 1 == static_cast<std::size_t>(std::llround(t / step_size))) m.push_back(filter.state[0]);
  }
  return m;
}

// Mean and standard error over runs of four values (one per report time).
struct Mean {
  std::vector<double> sum = std::vector<double>(4, 0.0), squares = std::vector<double>(4, 0.0);
  std::size_t runs = 0;
  void add(const std::vector<double>& v) {
    for (std::size_t i = 0; i < 4; ++i) {
      sum[i] += v[i];
      squares[i] += v[i] * v[i];
    }
    ++runs;
  }
  std::string cell(std::size_t i) const {
    const double n = static_cast<double>(runs), mean = sum[i] / n;
    const double se = std::sqrt(std::max(squares[i] - n * mean * mean, 0.0) / (n - 1) / n);
    char text[64];
    std::snprintf(text, sizeof text, "%.3f ± %.3f", mean, se);
    return text;
  }
};

// A filter's mean m and mean |x - m| at the report times.
struct Figures {
  Mean m, abs_error;
  void add(const std::vector<double>& m_at) {
    m.add(m_at);
    std::vector<double> e(4);
    for (std::size_t i = 0; i < 4; ++i) e[i] = std::abs(truth(report_times[i]) - m_at[i]);
    abs_error.add(e);
  }
};

void print_row(const char* label, const std::string& a, const std::string& b, const std::string& c,
               const std::string& d) {
  std::printf("%-34s %-16s %-16s %-16s %s\n", label, a.c_str(), b.c_str(), c.c_str(), d.c_str());
}

}  // namespace

int main(int argc, char** argv) {
  const std::size_t runs = argc > 1 ? std::strtoul(argv[1], nullptr, 10) : 2000;
  const std::uint64_t seed = argc > 2 ? std::strtoull(argv[2], nullptr, 10) : 4;
  if (runs < 2 || std::abs(static_cast<double>(steps) * step_size - 4.0) > 1e-9) {
    std::fprintf(stderr, "usage: paper004_prehistory [RUNS >= 2 [SEED]] (filters generated for dt = 0.001)\n");
    return 2;
  }
  std::vector<double> x(steps + 1);
  for (std::size_t k = 0; k <= steps; ++k) x[k] = truth(static_cast<double>(k) * step_size);
  std::printf("paper004_prehistory: %zu runs, seed %llu, dt = %g (D = %zu); mean m at t = 1, 2, 3, 4 ± standard error\n",
              runs, static_cast<unsigned long long>(seed), step_size, D);
  for (const bool signal_before_h : {true, false}) {
    Figures mean_optimal, mean_uncorrected, mean_ekf, mean_printed;
    std::vector<double> dy(steps);
    for (std::size_t r = 0; r < runs; ++r) {
      pfgen_runtime::RandomStream noise(seed, r, pfgen_runtime::substream::observation_noise);
      const double before = signal_before_h ? x[0] : 0.0;
      for (std::size_t k = 0; k < steps; ++k) {
        const double start = k >= D ? x[k - D] : before, end = k + 1 >= D ? x[k + 1 - D] : before;
        dy[k] = 0.5 * (start + end) * step_size + std::sqrt(step_size) * noise.normal();
      }
      mean_optimal.add(estimates<optimal::Filter>(dy));
      mean_uncorrected.add(estimates<bench_p4::paper004_quadratic_009::delay_uncorrected::Filter>(dy));
      mean_ekf.add(estimates<bench_p4::paper004_quadratic_009::delay_ekf::Filter>(dy));
      mean_printed.add(estimates<bench_p4::paper004_quadratic_009::ekf_printed::Filter>(dy));
    }
    std::printf("\nbefore t = h: %s\n", signal_before_h ? "x(s) = x(0) = 1.1 (pfgen simulate's pre-history)"
                                                        : "x(s) = 0, no signal");
    print_row("t", "1", "2", "3", "4");
    const auto row = [](const char* label, const Mean& m) { print_row(label, m.cell(0), m.cell(1), m.cell(2), m.cell(3)); };
    row("m  delay-optimal", mean_optimal.m);
    print_row("m  paper", "0.377", "1.1", "1.533", "1.820");
    row("m1 delay-uncorrected", mean_uncorrected.m);
    print_row("m1 paper", "0.272", "0.744", "1.136", "1.466");
    row("m2 delay-ekf", mean_ekf.m);
    row("m2 ekf-printed (0.18 P)", mean_printed.m);
    print_row("m2 paper", "0.205", "0.611", "0.901", "1.119");
    row("|x - m|  delay-optimal", mean_optimal.abs_error);
    row("|x - m|  delay-uncorrected", mean_uncorrected.abs_error);
    row("|x - m|  delay-ekf", mean_ekf.abs_error);
    row("|x - m|  ekf-printed (0.18 P)", mean_printed.abs_error);
  }
  return 0;
}
