// The production derivation (Stein-lemma recursion in GaussianExpectation,
// Jacobian form of E[(x-m) f^T]) against an independent brute-force reference:
// expansion around m and Isserlis/Wick pairing (support/isserlis_reference).
// Agreement must be exact: the symbolic difference expands to zero.
#include <catch2/catch.hpp>

#include <random>
#include <sstream>

#include "pfgen/derivation/filter_equations.hpp"
#include "support/isserlis_reference.hpp"
#include "support/random_polynomial_system.hpp"

using namespace pfgen;
using pfgen_test::IsserlisReference;

namespace {

std::string text(const GiNaC::ex& e) {
  std::ostringstream out;
  out << e;
  return out.str();
}

// Empty when `expected` and `derived` are the same polynomial; otherwise a
// description that Catch prints with the failed REQUIRE.
std::string mismatch(const GiNaC::ex& expected, const GiNaC::ex& derived) {
  const GiNaC::ex diff = (expected - derived).expand();
  if (diff.is_zero()) return {};
  return "expected " + text(expected) + "\nderived  " + text(derived) + "\ndifference " + text(diff);
}

}  // namespace

// The reference must itself be right before it can judge anything: check it
// on moments known in closed form.
TEST_CASE("Isserlis reference reproduces known Gaussian moments", "[isserlis][derivation][unit]") {
  SECTION("scalar moments of x ~ N(m, P)") {
    FilterVariables vars(1);
    GiNaC::symbol x("x");
    IsserlisReference ref({x}, vars);
    const GiNaC::ex m = vars.symbols()[0], P = vars.symbols()[1];
    CHECK(mismatch(m, ref.expectation(x)) == "");
    CHECK(mismatch(m * m + P, ref.expectation(x * x)) == "");
    CHECK(mismatch(pow(m, 3) + 3 * m * P, ref.expectation(pow(x, 3))) == "");
    CHECK(mismatch(pow(m, 4) + 6 * m * m * P + 3 * P * P, ref.expectation(pow(x, 4))) == "");
    CHECK(mismatch(pow(m, 5) + 10 * pow(m, 3) * P + 15 * m * P * P, ref.expectation(pow(x, 5))) == "");
    CHECK(mismatch(15 * pow(P, 3), ref.central_moment({6})) == "");
    CHECK(ref.central_moment({5}).is_zero());
    // E[(x - m) x^2] = 2 m P (Stein: P E[2x]).
    CHECK(mismatch(2 * m * P, ref.expectation((x - m) * x * x)) == "");
  }
  SECTION("paper 000 eq 22 from the reference alone") {
    // f = g = x^2/10: dP/dt = 2 E[(x-m) f] + E[g^2] - P^2 (A = B = 1).
    FilterVariables vars(1);
    GiNaC::symbol x("x");
    IsserlisReference ref({x}, vars);
    const GiNaC::ex m = vars.symbols()[0], P = vars.symbols()[1];
    const GiNaC::ex f = GiNaC::numeric(1, 10) * x * x;
    const GiNaC::ex dP = 2 * ref.expectation((x - m) * f) + ref.expectation(f * f) - P * P;
    const GiNaC::ex eq22 = GiNaC::numeric(4, 10) * P * m + GiNaC::numeric(3, 100) * P * P +
                           GiNaC::numeric(6, 100) * P * m * m + GiNaC::numeric(1, 100) * pow(m, 4) - P * P;
    CHECK(mismatch(eq22, dP) == "");
  }
  SECTION("mixed moments in several variables") {
    FilterVariables vars(4);
    std::vector<GiNaC::symbol> x{GiNaC::symbol("x1"), GiNaC::symbol("x2"), GiNaC::symbol("x3"), GiNaC::symbol("x4")};
    IsserlisReference ref(x, vars);
    auto m = [&](std::size_t i) { return ref.m(i); };
    auto P = [&](std::size_t i, std::size_t j) { return ref.P(i, j); };
    CHECK(mismatch(P(0, 1) * P(2, 3) + P(0, 2) * P(1, 3) + P(0, 3) * P(1, 2), ref.central_moment({1, 1, 1, 1})) == "");
    CHECK(ref.central_moment({1, 1, 1, 0}).is_zero());
    CHECK(mismatch(m(0) * m(1) + P(0, 1), ref.expectation(x[0] * x[1])) == "");
    const GiNaC::ex x1sq_x2sq = m(0) * m(0) * m(1) * m(1) + m(0) * m(0) * P(1, 1) + m(1) * m(1) * P(0, 0) +
                                4 * m(0) * m(1) * P(0, 1) + P(0, 0) * P(1, 1) + 2 * P(0, 1) * P(0, 1);
    CHECK(mismatch(x1sq_x2sq, ref.expectation(x[0] * x[0] * x[1] * x[1])) == "");
    // E[e1^2 e2 e3] = P11 P23 + 2 P12 P13.
    CHECK(mismatch(P(0, 0) * P(1, 2) + 2 * P(0, 1) * P(0, 2), ref.central_moment({2, 1, 1, 0})) == "");
    // Coefficients that are not numbers pass through untouched.
    GiNaC::symbol a("a"), t("t");
    CHECK(mismatch(a * sin(t) * (m(2) * m(3) + P(2, 3)), ref.expectation(a * sin(t) * x[2] * x[3])) == "");
  }
}

// Every equation of the optimal filter of `s` against the reference: m_drift,
// P_moment, P_diffusion, P_correction, the combined P_drift and the gain.
// Returns the number of entries checked.
static int check_against_reference(const pfgen_test::RandomSystem& s, const std::string& label) {
  const std::size_t n = s.n;
  const pfgen::ExVector f = s.f_ex();
  const pfgen::ExMatrix g = s.g_ex();
  std::string f_text;
  for (const auto& fi : f) f_text += (f_text.empty() ? "" : ", ") + text(fi);
  INFO(label << ": n = " << n << ", p = " << s.p << ", q = " << s.q << ", f = (" << f_text << ")");

  const FilterEquations eq = derive_filter(s.model, FilterKind::Optimal);
  REQUIRE(eq.n() == n);
  REQUIRE(eq.p == s.p);
  const std::vector<GiNaC::ex>& sym = eq.variables.symbols();
  IsserlisReference ref(s.x, eq.variables);

  // Symbolic P and the observation terms, from the system's A and B directly.
  GiNaC::matrix P(n, n), A(s.p, n), B(s.p, s.p);
  for (std::size_t i = 0; i < n; ++i)
    for (std::size_t j = 0; j < n; ++j) P(i, j) = ref.P(i, j);
  for (std::size_t r = 0; r < s.p; ++r) {
    for (std::size_t i = 0; i < n; ++i) A(r, i) = s.A[r][i];
    for (std::size_t c = 0; c < s.p; ++c) B(r, c) = s.B[r][c];
  }
  const GiNaC::matrix Rinv = B.mul(B.transpose()).inverse();
  const GiNaC::matrix gain = P.mul(A.transpose()).mul(Rinv);
  const GiNaC::matrix correction = gain.mul(A).mul(P);

  int checked = 0;
  for (std::size_t i = 0; i < n; ++i) {
    INFO("m_drift[" << i + 1 << "]");
    REQUIRE(mismatch(ref.expectation(f[i]), eq.m_drift[i].to_ex(sym)) == "");
    ++checked;
  }
  // E[(x_i - m_i) f_j] straight from the pairing expansion (no Stein's lemma).
  std::vector<std::vector<GiNaC::ex>> cross(n, std::vector<GiNaC::ex>(n));
  for (std::size_t i = 0; i < n; ++i)
    for (std::size_t j = 0; j < n; ++j) cross[i][j] = ref.expectation((s.x[i] - ref.m(i)) * f[j]);
  for (std::size_t i = 0; i < n; ++i)
    for (std::size_t j = i; j < n; ++j) {
      INFO("P entry (" << i + 1 << "," << j + 1 << ")");
      GiNaC::ex ggT = 0;
      for (std::size_t c = 0; c < s.q; ++c) ggT += g[i][c] * g[j][c];
      const GiNaC::ex moment = cross[i][j] + cross[j][i];
      const GiNaC::ex diffusion = ref.expectation(ggT);
      const std::size_t u = eq.variables.upper_index(i, j);
      REQUIRE(mismatch(moment, eq.P_moment[u].to_ex(sym)) == "");
      REQUIRE(mismatch(diffusion, eq.P_diffusion[u].to_ex(sym)) == "");
      REQUIRE(mismatch(correction(i, j), eq.P_correction[u].to_ex(sym)) == "");
      const GiNaC::ex expected = moment + diffusion - correction(i, j);
      REQUIRE(mismatch(expected, eq.P_drift(i, j).to_ex(sym)) == "");
      REQUIRE(mismatch(expected, eq.P_drift(j, i).to_ex(sym)) == "");
      ++checked;
    }
  for (std::size_t i = 0; i < n; ++i)
    for (std::size_t r = 0; r < s.p; ++r) {
      INFO("gain[" << i + 1 << "][" << r + 1 << "]");
      REQUIRE(mismatch(gain(i, r), eq.gain[i][r].to_ex(sym)) == "");
      ++checked;
    }
  return checked;
}

// 128 sparse random systems: n = 1..4, drift degree 1..4 (every pair of n and
// degree occurs 8 times), multiplicative g of degree 0..2 with q = 1..3
// columns, A identity or random integer rows (p = 1..n+1), B = I, some
// coefficients scaled by the parameter a or by sin(t). Fixed seeds: the test
// is deterministic.
TEST_CASE("optimal filter agrees exactly with the Isserlis reference on random systems", "[isserlis][derivation][unit]") {
  constexpr int kSystems = 128;
  int checked = 0;
  for (int k = 0; k < kSystems; ++k) {
    std::mt19937 rng(20240601u + static_cast<unsigned>(k));
    pfgen_test::RandomSystemOptions options;
    options.n = 1 + static_cast<std::size_t>(k % 4);
    options.drift_degree = 1 + static_cast<unsigned>((k / 4) % 4);
    options.diffusion_degree = static_cast<unsigned>(k % 3);
    options.q = 1 + static_cast<std::size_t>((k / 3) % 3);
    options.max_terms = 6;
    options.identity_observation = (k / 2) % 2 == 0;
    const auto s = pfgen_test::make_random_system(rng, options, "random" + std::to_string(k));
    REQUIRE(s.f[0].degree() == options.drift_degree);
    checked += check_against_reference(s, "system " + std::to_string(k) + ", drift degree " +
                                              std::to_string(options.drift_degree));
  }
  CHECK(checked > 0);
}

// Dense systems: every monomial of degree <= 4 in each drift entry (70 terms
// for n = 4) and of degree <= 2 in each entry of g, so every moment pattern up
// to degree 5 (E[(x-m) f]) and 4 (E[g g^T]) is exercised.
TEST_CASE("optimal filter agrees exactly with the Isserlis reference on dense quartic systems", "[isserlis][derivation][unit]") {
  for (std::size_t n = 1; n <= 4; ++n) {
    std::mt19937 rng(777u + static_cast<unsigned>(n));
    pfgen_test::RandomSystemOptions options;
    options.n = n;
    options.q = 2;
    options.drift_degree = 4;
    options.diffusion_degree = 2;
    options.dense = true;
    options.identity_observation = n % 2 == 0;
    const auto s = pfgen_test::make_random_system(rng, options, "dense" + std::to_string(n));
    REQUIRE(s.f[n - 1].terms.size() >= 5);
    CHECK(check_against_reference(s, "dense n = " + std::to_string(n)) > 0);
  }
}
