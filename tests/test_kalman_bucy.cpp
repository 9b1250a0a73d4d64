// docs/theory.md §4: for affine f = a0 + a1 x and state-independent diffusion
// the optimal filter is exactly the Kalman-Bucy filter,
//   dm/dt (drift part) = a0 + a1 m,
//   dP/dt = a1 P + P a1^T + G - P A^T R^-1 A P,   gain = P A^T R^-1,
// for any observation matrix A (square or not), and the extended filter
// coincides with it. The coefficients here are symbolic (model parameters,
// sin(t), a time-dependent A), so the check is on exact expressions, not numbers.
#include <catch2/catch.hpp>

#include <functional>
#include <sstream>

#include "pfgen/derivation/filter_equations.hpp"
#include "pfgen/model/model_builder.hpp"

#include "support/symbolic_mismatch.hpp"

using namespace pfgen;
using pfgen_test::mismatch;
using pfgen_test::text;
using GiNaC::ex;
using GiNaC::numeric;

namespace {

GiNaC::matrix to_matrix(const ExMatrix& m) {
  GiNaC::matrix out(static_cast<unsigned>(m.size()), static_cast<unsigned>(m.at(0).size()));
  for (unsigned i = 0; i < out.rows(); ++i)
    for (unsigned j = 0; j < out.cols(); ++j) out(i, j) = m[i][j];
  return out;
}

// One linear-Gaussian model, with the pieces the expected filter is built from.
struct LinearCase {
  std::string name;
  ExVector a0;   // n
  ExMatrix a1;   // n x n
  ExMatrix G;    // n x n, state-free (g g^T when g is given)
  ExMatrix A;    // p x n
  ExMatrix B;    // p x r
  Model model;
};

// Builds the model from a0, a1 and either g (G = g g^T) or G itself.
LinearCase make_case(const std::string& name, ModelBuilder& b, const std::vector<GiNaC::symbol>& x, ExVector a0,
                     ExMatrix a1, const ExMatrix* g, const ExMatrix* G, ExVector A0, ExMatrix A, ExMatrix B) {
  LinearCase c;
  c.name = name;
  const std::size_t n = x.size();
  ExVector f(n);
  for (std::size_t i = 0; i < n; ++i) {
    f[i] = a0[i];
    for (std::size_t j = 0; j < n; ++j) f[i] += a1[i][j] * x[j];
  }
  b.drift(f);
  if (g) {
    b.diffusion(*g);
    // G = g g^T, formed here rather than read back from the model.
    c.G.assign(n, ExVector(n, 0));
    for (std::size_t i = 0; i < n; ++i)
      for (std::size_t j = 0; j < n; ++j)
        for (std::size_t k = 0; k < (*g)[i].size(); ++k) c.G[i][j] += (*g)[i][k] * (*g)[j][k];
  } else {
    b.diffusion_covariance(*G);
    c.G = *G;
  }
  b.observation(A0, A, B);
  c.a0 = std::move(a0);
  c.a1 = std::move(a1);
  c.A = std::move(A);
  c.B = std::move(B);
  c.model = b.build();
  return c;
}

std::vector<LinearCase> linear_cases() {
  std::vector<LinearCase> cases;
  {  // n = 1, two sensors of one state (p = 2 > n), noise of the first scaled by r.
    ModelBuilder b("kb_n1_p2");
    auto x = b.state("x");
    auto k = b.parameter("k", numeric(1, 2)), c = b.parameter("c", 2), s = b.parameter("s", numeric(1, 3)),
         r = b.parameter("r", numeric(3, 2));
    auto t = b.time();
    ExMatrix g{{s, sin(t) / 2}};
    cases.push_back(make_case("n=1, p=2", b, {x}, {c * sin(t)}, {{-k}}, &g, nullptr, {0, sin(t)}, {{1}, {2}},
                              {{r, 0}, {0, 1}}));
  }
  {  // n = 1, square observation, G given directly.
    ModelBuilder b("kb_n1_p1");
    auto x = b.state("x");
    auto k = b.parameter("k", numeric(1, 2)), s = b.parameter("s", numeric(1, 3)), r = b.parameter("r", 2);
    auto t = b.time();
    ExMatrix G{{s * s + pow(cos(t), 2)}};
    cases.push_back(make_case("n=1, p=1", b, {x}, {1}, {{-k * sin(t)}}, nullptr, &G, {0}, {{r}}, {{r}}));
  }
  {  // n = 2, one observation of the first state only (p = 1 < n), noise in the second state only.
    ModelBuilder b("kb_n2_p1");
    auto x1 = b.state("x1"), x2 = b.state("x2");
    auto k = b.parameter("k", numeric(1, 2)), c = b.parameter("c", numeric(1, 5)), s = b.parameter("s", 1),
         r = b.parameter("r", numeric(1, 10));
    auto t = b.time();
    ExMatrix g{{0}, {s}};
    cases.push_back(make_case("n=2, p=1", b, {x1, x2}, {c * sin(t), 0}, {{0, 1}, {-k, -c}}, &g, nullptr, {0},
                              {{1, 0}}, {{r}}));
  }
  {  // n = 2, square but mixed observation, correlated observation noise, full G.
    ModelBuilder b("kb_n2_p2");
    auto x1 = b.state("x1"), x2 = b.state("x2");
    auto k = b.parameter("k", numeric(1, 2)), s = b.parameter("s", 1), r = b.parameter("r", numeric(1, 2));
    auto t = b.time();
    ExMatrix G{{s * s, s * sin(t)}, {s * sin(t), 1 + pow(sin(t), 2)}};
    cases.push_back(make_case("n=2, p=2", b, {x1, x2}, {0, numeric(3, 2)}, {{k, sin(t)}, {-1, 0}}, nullptr, &G,
                              {sin(t), 1}, {{1, 1}, {0, 2}}, {{1, numeric(1, 2)}, {0, r}}));
  }
  {  // n = 3, two observations (p = 2 < n), one row of A depends on time.
    ModelBuilder b("kb_n3_p2");
    auto x1 = b.state("x1"), x2 = b.state("x2"), x3 = b.state("x3");
    auto k = b.parameter("k", numeric(1, 2)), c = b.parameter("c", 3), s = b.parameter("s", numeric(1, 4)),
         r = b.parameter("r", 1);
    auto t = b.time();
    ExMatrix g{{s, 0}, {sin(t), 1}, {0, c * s}};
    cases.push_back(make_case("n=3, p=2", b, {x1, x2, x3}, {0, c * sin(t), -1},
                              {{-k, 1, 0}, {0, -1, sin(t)}, {numeric(1, 2), 0, -c}}, &g, nullptr, {0, 0},
                              {{1, 0, 0}, {0, cos(t), 1}}, {{r, 0}, {numeric(1, 2), 1}}));
  }
  {  // n = 3, four observations (p = 4 > n), B not square (p x 5).
    ModelBuilder b("kb_n3_p4");
    auto x1 = b.state("x1"), x2 = b.state("x2"), x3 = b.state("x3");
    auto k = b.parameter("k", numeric(1, 2)), s = b.parameter("s", numeric(1, 2)), r = b.parameter("r", 2);
    auto t = b.time();
    ExMatrix G{{s, 0, 0}, {0, s * sin(t) * sin(t) + 1, numeric(1, 3)}, {0, numeric(1, 3), 2}};
    cases.push_back(make_case("n=3, p=4", b, {x1, x2, x3}, {k, 0, sin(t)},
                              {{-1, k, 0}, {0, -k * sin(t), 1}, {1, 1, -2}}, nullptr, &G, {0, 0, 0, 0},
                              {{1, 0, 0}, {0, 1, 0}, {0, 0, 1}, {1, 1, 1}},
                              {{1, 0, 0, 0, 0}, {0, 1, 0, 0, 0}, {0, 0, r, 0, 0}, {0, 0, 0, 2, 1}}));
  }
  return cases;
}

// Checks every equation of `eq` against the Kalman-Bucy filter of `c`.
void check_kalman_bucy(const LinearCase& c, const FilterEquations& eq) {
  const std::size_t n = c.model.n(), p = c.model.p();
  REQUIRE(eq.n() == n);
  REQUIRE(eq.p == p);
  const auto& sym = eq.variables.symbols();
  GiNaC::matrix m(n, 1), P(n, n);
  for (std::size_t i = 0; i < n; ++i) {
    m(i, 0) = sym[eq.variables.m(i)];
    for (std::size_t j = 0; j < n; ++j) P(i, j) = sym[eq.variables.P(i, j)];
  }
  const GiNaC::matrix a0 = to_matrix({c.a0}).transpose(), a1 = to_matrix(c.a1), G = to_matrix(c.G);
  const GiNaC::matrix A = to_matrix(c.A), B = to_matrix(c.B);
  const GiNaC::matrix Rinv = B.mul(B.transpose()).inverse();
  const GiNaC::matrix gain = P.mul(A.transpose()).mul(Rinv);
  const GiNaC::matrix m_drift = a0.add(a1.mul(m));
  const GiNaC::matrix moment = a1.mul(P).add(P.mul(a1.transpose()));
  const GiNaC::matrix correction = gain.mul(A).mul(P);

  for (std::size_t i = 0; i < n; ++i) {
    INFO("m_drift[" << i + 1 << "]");
    CHECK(mismatch(m_drift(i, 0), eq.m_drift[i].to_ex(sym)) == "");
  }
  for (std::size_t i = 0; i < n; ++i)
    for (std::size_t j = i; j < n; ++j) {
      INFO("P entry (" << i + 1 << "," << j + 1 << ")");
      const std::size_t u = eq.variables.upper_index(i, j);
      CHECK(mismatch(moment(i, j), eq.P_moment[u].to_ex(sym)) == "");
      CHECK(mismatch(G(i, j), eq.P_diffusion[u].to_ex(sym)) == "");
      CHECK(mismatch(correction(i, j), eq.P_correction[u].to_ex(sym)) == "");
      CHECK(mismatch(moment(i, j) + G(i, j) - correction(i, j), eq.P_drift(i, j).to_ex(sym)) == "");
    }
  for (std::size_t i = 0; i < n; ++i)
    for (std::size_t r = 0; r < p; ++r) {
      INFO("gain[" << i + 1 << "][" << r + 1 << "]");
      CHECK(mismatch(gain(i, r), eq.gain[i][r].to_ex(sym)) == "");
    }
}

}  // namespace

TEST_CASE("optimal filter of a linear model is exactly the Kalman-Bucy filter", "[kalman][derivation][unit]") {
  for (const LinearCase& c : linear_cases()) {
    INFO("case " << c.name);
    const FilterEquations eq = derive_filter(c.model, FilterKind::Optimal);
    check_kalman_bucy(c, eq);
    CHECK(eq.exactness.exact);
    CHECK(eq.exactness.condition == "Kalman-Bucy");
    CHECK(eq.exactness.failed.empty());
  }
}

TEST_CASE("extended Kalman-Bucy filter of a linear model equals the Kalman-Bucy filter", "[kalman][derivation][unit]") {
  for (const LinearCase& c : linear_cases()) {
    INFO("case " << c.name);
    const FilterEquations ekf = derive_filter(c.model, FilterKind::Ekf);
    check_kalman_bucy(c, ekf);
    // Same polynomials term by term as the optimal filter, not only equal after simplification.
    const FilterEquations optimal = derive_filter(c.model, FilterKind::Optimal);
    CHECK(ekf.m_drift == optimal.m_drift);
    CHECK(ekf.P_moment == optimal.P_moment);
    CHECK(ekf.P_diffusion == optimal.P_diffusion);
    CHECK(ekf.P_correction == optimal.P_correction);
    CHECK(ekf.gain == optimal.gain);
    CHECK(ekf.exactness.exact);
    CHECK(ekf.exactness.condition == "Kalman-Bucy");
  }
}
