// How good is Φ*? pfgen's generated delay-optimal (paper 004's Φ* gain) and delay-uncorrected
// filters against the exact optimal filter of the time-discretised problem, the Kalman filter on
// the state augmented with its delayed copies (tests/support/delayed_linear_reference.hpp), all
// fed the same dy of the same truths: dx = a x dt + sigma dW1 sampled exactly on the grid,
// dy_k = (x(t_k - h) + x(t_{k+1} - h)) dt/2 + dW2 (the runtime's trapezoid), x(s) = x(0) for
// s < 0, x(0) ~ N(m0 = 1, P0 = 1). docs/reproductions/basin-rodriguez-gonzalez-martinez-zuniga-2004.md shows the output and the command.
//
//   delay_reference [RUNS [T [SEED]]]     (defaults 2000 runs, T = 10, seed 1)
//
// For each a (stable -1, unstable 0.5) and h it prints, over the grid times of (T/2, T] and all
// runs: the RMS error of the reference and sqrt of its mean P (they must agree: the reference is
// exact), the continuous-time steady value of that P, the RMS gap |m - m_ref| of each filter and
// each filter's own RMS error; each RMS with its standard error over runs. A run whose filter
// leaves the finite numbers is counted apart and kept out of that filter's figures.
#include <algorithm>
#include <cmath>
#include <cstdint>
#include <cstdio>
#include <cstdlib>
#include <string>
#include <vector>

#include "delay_cases.hpp"
#include "support/delayed_linear_reference.hpp"

namespace {

// Mean and standard error over runs of one per-run mean square, reported as an RMS.
struct RmsAccumulator {
  double sum = 0, sum_squares = 0;
  std::size_t runs = 0;
  void add(double mean_square) {
    sum += mean_square;
    sum_squares += mean_square * mean_square;
    ++runs;
  }
  double rms() const { return runs ? std::sqrt(sum / static_cast<double>(runs)) : NAN; }
  // Delta method: se(sqrt(ms)) = se(ms) / (2 sqrt(ms)).
  double se() const {
    if (runs < 2) return NAN;
    const double n = static_cast<double>(runs), mean = sum / n;
    const double variance = (sum_squares - n * mean * mean) / (n - 1);
    return std::sqrt(std::max(variance, 0.0) / n) / (2 * std::sqrt(mean));
  }
  std::string text() const {
    char buffer[64];
    std::snprintf(buffer, sizeof buffer, "%.4g ± %.2g", rms(), se());
    return buffer;
  }
};

// The steady conditional variance of x(t) given y up to t for the continuous problem: the
// Kalman-Bucy P of x(t - h), carried over h by the prior, e^{2ah} P_KB + σ² (e^{2ah} - 1)/(2a);
// for a > 0 it is still finite (observability), P_KB = a + sqrt(a² + σ²) with B = 1.
double continuous_steady_variance(double a, double sigma, double h) {
  const double P_kb = a + std::sqrt(a * a + sigma * sigma);
  const double growth = std::exp(2 * a * h);
  return growth * P_kb + sigma * sigma * (growth - 1) / (2 * a);
}

bool all_finite(const std::vector<double>& v) {
  for (double x : v)
    if (!std::isfinite(x)) return false;
  return true;
}

}  // namespace

int main(int argc, char** argv) {
  const std::size_t runs = argc > 1 ? std::strtoul(argv[1], nullptr, 10) : 2000;
  const double T = argc > 2 ? std::strtod(argv[2], nullptr) : 10.0;
  const std::uint64_t seed = argc > 3 ? std::strtoull(argv[3], nullptr, 10) : 1;
  if (runs < 2 || !(T > 0)) {
    std::fprintf(stderr, "usage: delay_reference [RUNS >= 2 [T > 0 [SEED]]]\n");
    return 2;
  }
  const double sigma = 1.0;
  std::printf("delay_reference: %zu runs, T = %g, seed %llu; dx = a x dt + dW1, dy = x(t - h) dt + dW2, m0 = P0 = 1\n",
              runs, T, static_cast<unsigned long long>(seed));
  std::printf("RMS over the grid times of (T/2, T] and the runs, ± standard error over runs\n\n");
  std::printf("%-5s %-4s %-6s %-5s %-18s %-9s %-9s %-18s %-18s %-18s %-18s %s\n", "a", "h", "dt", "D", "ref RMS error",
              "ref sqrtP", "sqrtP(ct)", "gap phi*", "gap uncorrected", "phi* RMS error", "uncorr. RMS error", "diverged (phi*/unc.)");
  for (const double a : {-1.0, 0.5}) {
    for (const pfgen_bench::DelayCase& c : pfgen_bench::delay_cases()) {
      pfgen_test::DelayedLinearModel model;
      model.a = a;
      model.sigma = sigma;
      model.dt = c.dt;
      model.D = static_cast<std::size_t>(std::llround(c.h / c.dt));
      model.m0 = 1.0;
      model.P0 = 1.0;
      model.rule = pfgen_test::DelayedObservationRule::trapezoid;
      const std::size_t steps = static_cast<std::size_t>(std::llround(T / c.dt));
      const std::size_t first = steps / 2 + 1;  // grid indices of (T/2, T]
      // The reference's gains and variances do not depend on the data: once for all runs.
      pfgen_test::AugmentedKalmanGain recursion(model);
      std::vector<std::vector<double>> gains(steps);
      double mean_P = 0;
      for (std::size_t k = 0; k < steps; ++k) {
        recursion.advance();
        gains[k] = recursion.gain();
        if (k + 1 >= first) mean_P += recursion.variance();
      }
      mean_P /= static_cast<double>(steps + 1 - first);

      RmsAccumulator reference_error, gap_optimal, gap_uncorrected, error_optimal, error_uncorrected;
      std::size_t diverged_optimal = 0, diverged_uncorrected = 0;
      std::vector<double> m_reference(steps + 1), m_optimal, m_uncorrected;
      for (std::size_t r = 0; r < runs; ++r) {
        const pfgen_test::DelayedLinearPath path = pfgen_test::simulate_delayed_linear(model, steps, seed, r);
        pfgen_test::AugmentedMean mean(model);
        m_reference[0] = mean.mean();
        for (std::size_t k = 0; k < steps; ++k) {
          mean.advance(gains[k], path.dy[k]);
          m_reference[k + 1] = mean.mean();
        }
        c.optimal(path.dy, a, sigma, c.dt, m_optimal);
        c.uncorrected(path.dy, a, sigma, c.dt, m_uncorrected);
        const bool optimal_ok = all_finite(m_optimal), uncorrected_ok = all_finite(m_uncorrected);
        diverged_optimal += !optimal_ok;
        diverged_uncorrected += !uncorrected_ok;
        double e_ref = 0, g_opt = 0, g_unc = 0, e_opt = 0, e_unc = 0;
        for (std::size_t k = first; k <= steps; ++k) {
          const double x = path.x[k], ref = m_reference[k];
          e_ref += (x - ref) * (x - ref);
          g_opt += (m_optimal[k] - ref) * (m_optimal[k] - ref);
          g_unc += (m_uncorrected[k] - ref) * (m_uncorrected[k] - ref);
          e_opt += (x - m_optimal[k]) * (x - m_optimal[k]);
          e_unc += (x - m_uncorrected[k]) * (x - m_uncorrected[k]);
        }
        const double count = static_cast<double>(steps + 1 - first);
        reference_error.add(e_ref / count);
        if (optimal_ok) {
          gap_optimal.add(g_opt / count);
          error_optimal.add(e_opt / count);
        }
        if (uncorrected_ok) {
          gap_uncorrected.add(g_unc / count);
          error_uncorrected.add(e_unc / count);
        }
      }
      std::printf("%-5g %-4g %-6g %-5zu %-18s %-9.4g %-9.4g %-18s %-18s %-18s %-18s %zu/%zu\n", a, c.h, c.dt, model.D,
                  reference_error.text().c_str(), std::sqrt(mean_P), std::sqrt(continuous_steady_variance(a, sigma, c.h)),
                  gap_optimal.text().c_str(), gap_uncorrected.text().c_str(), error_optimal.text().c_str(),
                  error_uncorrected.text().c_str(), diverged_optimal, diverged_uncorrected);
      std::fflush(stdout);
    }
  }
  return 0;
}
