// The derived Gaussian expectations against plain sampling: draw x ~ N(m, P)
// at a fixed random (m, P) and compare the sample means of f, of the
// symmetrised cross moment (x-m) f^T + f (x-m)^T and of g g^T with the
// derived m_drift, P_moment and P_diffusion evaluated at (m, P). This checks
// the closure's meaning, not just its algebra: a reference with the same
// algebraic slip as the production code would not pass it.
#include <catch2/catch.hpp>

#include <Eigen/Dense>
#include <cmath>
#include <random>
#include <sstream>

#include "pfgen/derivation/filter_equations.hpp"
#include "pfgen/evaluation/point_evaluator.hpp"
#include "support/random_polynomial_system.hpp"

using namespace pfgen;

namespace {

// f and g in double precision, with the parameter and time already applied:
// evaluating through GiNaC 10^6 times would take minutes (docs/theory.md §9.2).
struct FastPolynomial {
  struct Term {
    double coefficient;
    std::vector<unsigned> exponents;
  };
  std::vector<Term> terms;

  FastPolynomial(const pfgen_test::RandomPolynomial& p, double a, double t) {
    for (const auto& term : p.terms) {
      double c = term.coefficient.to_double();
      if (term.times_parameter) c *= a;
      if (term.times_sin_t) c *= std::sin(t);
      terms.push_back(Term{c, term.exponents});
    }
  }
  double operator()(const double* x) const {
    double sum = 0;
    for (const auto& term : terms) {
      double value = term.coefficient;
      for (std::size_t i = 0; i < term.exponents.size(); ++i)
        for (unsigned k = 0; k < term.exponents[i]; ++k) value *= x[i];
      sum += value;
    }
    return sum;
  }
};

// Running mean and variance (Welford), so that a large mean does not swamp
// the variance estimate.
struct Accumulator {
  std::size_t count = 0;
  double mean = 0, m2 = 0;
  void add(double value) {
    ++count;
    const double delta = value - mean;
    mean += delta / static_cast<double>(count);
    m2 += delta * (value - mean);
  }
  double standard_error() const {
    return std::sqrt(m2 / static_cast<double>(count - 1) / static_cast<double>(count));
  }
};

// |estimate - derived| within 5 standard errors; the tiny absolute slack only
// matters for quantities with zero variance (a constant g entry).
bool within_five_se(const Accumulator& mc, double derived) {
  return std::abs(mc.mean - derived) <= 5 * mc.standard_error() + 1e-9 * (1 + std::abs(derived));
}

std::string describe(const std::string& what, const Accumulator& mc, double derived) {
  std::ostringstream out;
  out << what << ": Monte Carlo " << mc.mean << " +- " << mc.standard_error() << " (1 SE), derived " << derived
      << ", off by " << (mc.mean - derived) / mc.standard_error() << " SE";
  return out.str();
}

struct McCase {
  unsigned seed;
  std::size_t n, q;
};

}  // namespace

TEST_CASE("derived expectations agree with Monte Carlo sampling of N(m, P)", "[montecarlo][derivation][statistical]") {
  const McCase cases[] = {{101, 2, 2}, {202, 2, 1}, {303, 3, 2}, {404, 3, 3}};
  constexpr std::size_t kSamples = 1000000;

  for (const McCase& c : cases) {
    std::mt19937 rng(c.seed);
    pfgen_test::RandomSystemOptions options;
    options.n = c.n;
    options.q = c.q;
    options.drift_degree = 3;      // cubic drift
    options.diffusion_degree = 2;  // quadratic multiplicative diffusion
    options.max_terms = 5;
    options.identity_observation = false;
    const pfgen_test::RandomSystem s = pfgen_test::make_random_system(rng, options, "mc" + std::to_string(c.seed));
    const std::size_t n = s.n;
    INFO("case seed " << c.seed << ", n = " << n << ", q = " << c.q << ", p = " << s.p);
    REQUIRE(s.f[0].degree() == 3);
    REQUIRE(s.g[0][0].degree() == 2);

    // A random point: m in [-1, 1], P = L L^T + I/10 with L lower triangular,
    // so P is positive definite. Exact rationals, for evaluate_at.
    std::uniform_int_distribution<int> small(-8, 8), diag(2, 6), off(-4, 4);
    std::vector<GiNaC::numeric> m(n);
    for (auto& mi : m) mi = GiNaC::numeric(small(rng), 8);
    std::vector<std::vector<GiNaC::numeric>> L(n, std::vector<GiNaC::numeric>(n, 0));
    for (std::size_t i = 0; i < n; ++i)
      for (std::size_t j = 0; j <= i; ++j) L[i][j] = GiNaC::numeric(i == j ? diag(rng) : off(rng), 8);
    std::vector<std::vector<GiNaC::numeric>> P(n, std::vector<GiNaC::numeric>(n, 0));
    for (std::size_t i = 0; i < n; ++i)
      for (std::size_t j = 0; j < n; ++j) {
        for (std::size_t k = 0; k < n; ++k) P[i][j] += L[i][k] * L[j][k];
        if (i == j) P[i][j] += GiNaC::numeric(1, 10);
      }
    const GiNaC::numeric t0(7, 10);

    Eigen::VectorXd md(n);
    Eigen::MatrixXd Pd(n, n);
    for (std::size_t i = 0; i < n; ++i) {
      md(i) = m[i].to_double();
      for (std::size_t j = 0; j < n; ++j) Pd(i, j) = P[i][j].to_double();
    }
    Eigen::LLT<Eigen::MatrixXd> cholesky(Pd);
    REQUIRE(cholesky.info() == Eigen::Success);
    const Eigen::MatrixXd chol = cholesky.matrixL();

    // ---- sampling ----
    const double a = s.a_default.to_double(), t = t0.to_double();
    std::vector<FastPolynomial> f;
    for (const auto& fi : s.f) f.emplace_back(fi, a, t);
    std::vector<std::vector<FastPolynomial>> g(n);
    for (std::size_t i = 0; i < n; ++i)
      for (std::size_t k = 0; k < c.q; ++k) g[i].emplace_back(s.g[i][k], a, t);

    const std::size_t upper = n * (n + 1) / 2;
    std::vector<Accumulator> mc_f(n), mc_moment(upper), mc_diffusion(upper), mc_sum(upper);
    std::mt19937_64 sampler(c.seed * 7919ull + 1);
    std::normal_distribution<double> normal(0.0, 1.0);
    Eigen::VectorXd z(n), x(n), e(n), fx(n);
    Eigen::MatrixXd gx(n, c.q);
    for (std::size_t sample = 0; sample < kSamples; ++sample) {
      for (std::size_t i = 0; i < n; ++i) z(i) = normal(sampler);
      e = chol * z;
      x = md + e;
      for (std::size_t i = 0; i < n; ++i) {
        fx(i) = f[i](x.data());
        for (std::size_t k = 0; k < c.q; ++k) gx(i, k) = g[i][k](x.data());
      }
      for (std::size_t i = 0; i < n; ++i) mc_f[i].add(fx(i));
      std::size_t u = 0;
      for (std::size_t i = 0; i < n; ++i)
        for (std::size_t j = i; j < n; ++j, ++u) {
          const double moment = e(i) * fx(j) + fx(i) * e(j);
          const double diffusion = gx.row(i).dot(gx.row(j));
          mc_moment[u].add(moment);
          mc_diffusion[u].add(diffusion);
          mc_sum[u].add(moment + diffusion);
        }
    }

    // ---- derived, evaluated at (m, P, a default, t0) ----
    const FilterEquations eq = derive_filter(s.model, FilterKind::Optimal);
    GiNaC::exmap point;
    const auto& sym = eq.variables.symbols();
    for (std::size_t i = 0; i < n; ++i) {
      point[sym[i]] = m[i];
      for (std::size_t j = i; j < n; ++j) point[sym[eq.variables.P(i, j)]] = P[i][j];
    }
    point[s.a] = s.a_default;
    point[s.t] = t0;
    auto value = [&](const Polynomial& poly) {
      const GiNaC::ex v = poly.to_ex(sym).subs(point).evalf();
      REQUIRE(GiNaC::is_a<GiNaC::numeric>(v));
      return GiNaC::ex_to<GiNaC::numeric>(v).to_double();
    };

    for (std::size_t i = 0; i < n; ++i) {
      const double derived = value(eq.m_drift[i]);
      INFO(describe("E[f_" + std::to_string(i + 1) + "]", mc_f[i], derived));
      CHECK(within_five_se(mc_f[i], derived));
    }
    for (std::size_t i = 0, u = 0; i < n; ++i)
      for (std::size_t j = i; j < n; ++j, ++u) {
        REQUIRE(eq.variables.upper_index(i, j) == u);
        const std::string entry = "(" + std::to_string(i + 1) + "," + std::to_string(j + 1) + ")";
        const double moment = value(eq.P_moment[u]);
        const double diffusion = value(eq.P_diffusion[u]);
        {
          INFO(describe("P_moment" + entry, mc_moment[u], moment));
          CHECK(within_five_se(mc_moment[u], moment));
        }
        {
          INFO(describe("P_diffusion" + entry, mc_diffusion[u], diffusion));
          CHECK(within_five_se(mc_diffusion[u], diffusion));
        }
      }

    // The same through pfgen::evaluate_at (the `pfgen eval` path): m_drift
    // against E[f], P_drift against the sampled moment + diffusion minus the
    // correction P A^T R^-1 A P computed here in double precision (B = I).
    EvaluationPoint at;
    at.t = t0;
    at.m = m;
    at.P = P;
    const EvaluatedFilter evaluated = evaluate_at(s.model, eq, at);
    Eigen::MatrixXd A(s.p, n);
    for (std::size_t r = 0; r < s.p; ++r)
      for (std::size_t i = 0; i < n; ++i) A(r, i) = GiNaC::ex_to<GiNaC::numeric>(s.A[r][i]).to_double();
    const Eigen::MatrixXd gain = Pd * A.transpose();
    const Eigen::MatrixXd correction = gain * A * Pd;
    for (std::size_t i = 0; i < n; ++i) {
      INFO(describe("evaluate_at m_drift[" + std::to_string(i + 1) + "]", mc_f[i], evaluated.m_drift[i]));
      CHECK(within_five_se(mc_f[i], evaluated.m_drift[i]));
      for (std::size_t r = 0; r < s.p; ++r) CHECK(evaluated.gain[i][r] == Approx(gain(i, r)).margin(1e-12));
    }
    for (std::size_t i = 0, u = 0; i < n; ++i)
      for (std::size_t j = i; j < n; ++j, ++u) {
        const double drift_plus_correction = evaluated.P_drift[i][j] + correction(i, j);
        INFO(describe("evaluate_at P_drift(" + std::to_string(i + 1) + "," + std::to_string(j + 1) + ") + correction",
                      mc_sum[u], drift_plus_correction));
        CHECK(within_five_se(mc_sum[u], drift_plus_correction));
        CHECK(evaluated.P_drift[j][i] == evaluated.P_drift[i][j]);
      }

    // The comparison must have the power to reject a wrong closure: the
    // extended Kalman filter's f(m), J(m) and g(m) g(m)^T are not the
    // expectations for cubic f and quadratic g, and must be caught.
    const FilterEquations ekf = derive_filter(s.model, FilterKind::Ekf);
    int rejected = 0;
    for (std::size_t i = 0; i < n; ++i) rejected += !within_five_se(mc_f[i], value(ekf.m_drift[i]));
    for (std::size_t u = 0; u < upper; ++u) {
      rejected += !within_five_se(mc_moment[u], value(ekf.P_moment[u]));
      rejected += !within_five_se(mc_diffusion[u], value(ekf.P_diffusion[u]));
    }
    CHECK(rejected > 0);
  }
}
