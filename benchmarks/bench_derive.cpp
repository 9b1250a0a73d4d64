// Derivation time of the optimal filter for a dense random cubic drift (every
// monomial up to degree 3 in every component) with linear multiplicative
// diffusion g = diag(c_i0 + sum_k c_ik x_k), over one observation per state
// (tests/support/dense_cubic_system.hpp: the models of benchmarks/models/).
//
// Baseline measured in the same run: the heat-operator formula
//   E[p] = sum_k (1/k!) (1/2 sum_ij P_ij d_i d_j)^k p  evaluated at m,
// written directly with GiNaC's diff/expand, for E[f] alone at small n. The
// ratio shows what the memoised Stein recursion on pfgen's own polynomials buys.
//
// Usage: bench_derive [--sizes 2,4,6,8,10,15,20] [--repeats 3] [--baseline-max-n 6]
#include <algorithm>
#include <chrono>
#include <cstdio>
#include <cstring>
#include <sstream>
#include <string>
#include <vector>

#include "pfgen/derivation/filter_equations.hpp"
#include "pfgen/derivation/gaussian_expectation.hpp"
#include "pfgen/model/model.hpp"
#include "support/dense_cubic_model.hpp"  // tests/support, shared with the tests

namespace {

using Clock = std::chrono::steady_clock;

// The baseline: heat-operator series with GiNaC differentiation, E[f] only.
double baseline_expected_drift_seconds(const pfgen::Model& model) {
  const std::size_t n = model.n();
  std::vector<GiNaC::symbol> P;
  for (std::size_t i = 0; i < n * n; ++i) P.push_back(GiNaC::symbol("P" + std::to_string(i)));
  auto start = Clock::now();
  for (const auto& fi : model.drift) {
    GiNaC::ex term = fi, sum = fi;
    for (int k = 1; k <= 2; ++k) {
      GiNaC::ex next = 0;
      for (std::size_t i = 0; i < n; ++i)
        for (std::size_t j = 0; j < n; ++j)
          next += GiNaC::numeric(1, 2) * P[std::min(i, j) * n + std::max(i, j)] *
                  term.diff(model.states[i]).diff(model.states[j]);
      term = (next / k).expand();
      sum += term;
    }
    volatile bool keep = sum.expand().is_zero();
    (void)keep;
  }
  return std::chrono::duration<double>(Clock::now() - start).count();
}

std::vector<std::size_t> parse_sizes(const char* text) {
  std::vector<std::size_t> sizes;
  std::stringstream in(text);
  std::string part;
  while (std::getline(in, part, ',')) sizes.push_back(std::stoul(part));
  return sizes;
}

}  // namespace

int main(int argc, char** argv) {
  std::vector<std::size_t> sizes{2, 4, 6, 8, 10, 15, 20};
  int repeats = 3;
  std::size_t baseline_max_n = 6;
  for (int k = 1; k + 1 < argc; k += 2) {
    if (!std::strcmp(argv[k], "--sizes")) sizes = parse_sizes(argv[k + 1]);
    else if (!std::strcmp(argv[k], "--repeats")) repeats = std::max(1, std::atoi(argv[k + 1]));
    else if (!std::strcmp(argv[k], "--baseline-max-n")) baseline_max_n = std::stoul(argv[k + 1]);
  }
  std::printf("%4s %10s %12s %14s %16s %14s %10s\n", "n", "drift_terms", "P_terms", "derive_s(med)",
              "E[f]_pfgen_s", "E[f]_heat_s", "ratio");
  for (std::size_t n : sizes) {
    pfgen::Model model = pfgen_test::dense_cubic_model(n);
    std::vector<double> times;
    std::size_t P_terms = 0, drift_terms = 0;
    for (int r = 0; r < repeats; ++r) {
      auto start = Clock::now();
      pfgen::FilterEquations eq = pfgen::derive_filter(model, pfgen::FilterKind::Optimal);
      times.push_back(std::chrono::duration<double>(Clock::now() - start).count());
      P_terms = 0;
      drift_terms = 0;
      for (const auto& p : eq.m_drift) drift_terms += p.terms().size();
      for (std::size_t u = 0; u < eq.P_moment.size(); ++u)
        P_terms += eq.P_moment[u].terms().size() + eq.P_diffusion[u].terms().size() + eq.P_correction[u].terms().size();
    }
    std::sort(times.begin(), times.end());
    double median = times[times.size() / 2];
    if (n <= baseline_max_n) {
      // E[f] alone through pfgen's expectation, against the heat-operator baseline.
      auto start = Clock::now();
      pfgen::FilterVariables vars(n);
      pfgen::GaussianExpectation E(vars);
      for (const auto& fi : model.drift) (void)E.of(pfgen::Polynomial::from_ex(fi, model.states));
      double ours = std::chrono::duration<double>(Clock::now() - start).count();
      double heat = baseline_expected_drift_seconds(model);
      std::printf("%4zu %10zu %12zu %14.4f %16.5f %14.5f %9.1fx\n", n, drift_terms, P_terms, median, ours, heat,
                  heat / ours);
    } else {
      std::printf("%4zu %10zu %12zu %14.4f %16s %14s %10s\n", n, drift_terms, P_terms, median, "-", "-", "-");
    }
    std::fflush(stdout);
  }
  return 0;
}
