// The delay kinds' equations checked against code they do not share (docs/theory.md §2.6):
// - the gain and correction against the matrix products written out with GiNaC matrices:
//   delay-optimal's K = P Phi A^T R^-1 and P Phi A^T R^-1 A Phi P with Phi = diag(phi), the others'
//   P A^T R^-1 and P A^T R^-1 A P. A scalar model cannot tell (P Phi)_jl = P_jl phi_l from
//   P_lj phi_j: this one has three states, two observations and a non-diagonal R;
// - paper 004's example (dx = x^2 dt, y = x(t - 0.8) + noise), its eqs 17-20 written out by hand.
#include <catch2/catch.hpp>

#include <functional>

#include "pfgen/derivation/filter_equations.hpp"
#include "pfgen/evaluation/point_evaluator.hpp"
#include "pfgen/model/model_builder.hpp"

using namespace pfgen;

namespace {

Model three_state_delayed_model() {
  ModelBuilder b("delayed_three");
  const GiNaC::symbol x = b.state("x"), y = b.state("y"), z = b.state("z");
  b.drift({-x + x * y, -y, -z + GiNaC::pow(x, 2)});
  b.diffusion({{GiNaC::numeric(1, 10)}, {GiNaC::numeric(1, 5)}, {GiNaC::numeric(3, 10)}});
  b.delayed_observation(GiNaC::numeric(1, 2), {0, GiNaC::numeric(1, 4)}, {{1, 2, 0}, {0, -1, 3}},
                        {{1, GiNaC::numeric(1, 2)}, {0, 2}});
  return b.build();
}

// Paper 004's example: no state noise, A = B = 1, h = 0.8.
Model paper004_printed_model() {
  ModelBuilder b("paper004_printed");
  const GiNaC::symbol x = b.state("x");
  b.drift({GiNaC::pow(x, 2)});
  b.diffusion({{0}});
  b.delayed_observation(GiNaC::numeric(4, 5), {0}, {{1}}, {{1}});
  return b.build();
}

GiNaC::matrix to_matrix(const ExMatrix& m) {
  GiNaC::matrix out(static_cast<unsigned>(m.size()), static_cast<unsigned>(m[0].size()));
  for (unsigned i = 0; i < m.size(); ++i)
    for (unsigned j = 0; j < m[0].size(); ++j) out(i, j) = m[i][j];
  return out;
}

void check_equal(const Polynomial& derived, const GiNaC::ex& expected, const std::vector<GiNaC::ex>& symbols,
                 const std::string& what) {
  const GiNaC::ex difference = GiNaC::expand(derived.to_ex(symbols) - expected);
  INFO(what << ": derived minus expected = " << difference);
  CHECK(difference.is_zero());
}

}  // namespace

TEST_CASE("delay kinds: gain and correction are the matrix products with Phi* on both sides", "[unit][delay]") {
  const Model model = three_state_delayed_model();
  const AffineRate& obs = *model.observation.rate().affine();
  const GiNaC::matrix A = to_matrix(obs.A);
  const GiNaC::matrix R = to_matrix(obs.B).mul(to_matrix(obs.B).transpose());
  const GiNaC::matrix At_Rinv = A.transpose().mul(R.inverse());
  for (const FilterKind kind : {FilterKind::DelayOptimal, FilterKind::DelayUncorrected, FilterKind::DelayEkf}) {
    const FilterEquations eq = derive_filter(model, kind);
    INFO("kind " << eq.name);
    const FilterVariables& vars = eq.variables;
    const std::vector<GiNaC::ex>& s = vars.symbols();
    const unsigned n = static_cast<unsigned>(eq.n());
    GiNaC::matrix P(n, n), Phi(n, n);
    for (unsigned i = 0; i < n; ++i) {
      for (unsigned j = 0; j < n; ++j) P(i, j) = s[vars.P(i, j)];
      Phi(i, i) = kind == FilterKind::DelayOptimal ? s[vars.phi(i)] : GiNaC::ex(1);
    }
    const GiNaC::matrix K = P.mul(Phi).mul(At_Rinv);
    const GiNaC::matrix correction = K.mul(A).mul(Phi).mul(P);
    for (unsigned i = 0; i < n; ++i)
      for (unsigned r = 0; r < eq.p; ++r)
        check_equal(eq.gain[i][r], K(i, r), s, "gain[" + std::to_string(i + 1) + "][" + std::to_string(r + 1) + "]");
    for (unsigned i = 0; i < n; ++i)
      for (unsigned j = i; j < n; ++j)
        check_equal(eq.P_correction[vars.upper_index(i, j)], correction(i, j), s,
                    "P_correction[" + std::to_string(i + 1) + "][" + std::to_string(j + 1) + "]");
    // The innovation compares dy with A0 + A m(t - h).
    for (unsigned r = 0; r < eq.p; ++r) {
      GiNaC::ex expected = obs.A0[r];
      for (unsigned k = 0; k < n; ++k) expected += obs.A[r][k] * s[vars.m_delayed(k)];
      check_equal(eq.predicted_observation[r], expected, s, "predicted_observation[" + std::to_string(r + 1) + "]");
    }
  }
}

TEST_CASE("delay kinds: paper 004's eqs 17-20 for dx = x^2 dt, and the textbook EKF", "[unit][delay]") {
  const Model model = paper004_printed_model();
  struct Expected {
    FilterKind kind;
    std::function<GiNaC::ex(GiNaC::ex, GiNaC::ex, GiNaC::ex)> m_drift, gain, P_drift;  // of (m, P, phi)
  };
  // eqs 17-18: m^2 + P, P Phi*, 4 P m - P^2 Phi*^2; eqs 19-20: the same without Phi*; the textbook
  // EKF: f(m) = m^2, J = 2m, so 4 m P - P^2 (the paper's eq 22 prints 2P: docs/theory.md §8).
  const std::vector<Expected> cases = {
      {FilterKind::DelayOptimal, [](GiNaC::ex m, GiNaC::ex P, GiNaC::ex) { return m * m + P; },
       [](GiNaC::ex, GiNaC::ex P, GiNaC::ex phi) { return P * phi; },
       [](GiNaC::ex m, GiNaC::ex P, GiNaC::ex phi) { return 4 * P * m - P * P * phi * phi; }},
      {FilterKind::DelayUncorrected, [](GiNaC::ex m, GiNaC::ex P, GiNaC::ex) { return m * m + P; },
       [](GiNaC::ex, GiNaC::ex P, GiNaC::ex) { return P; },
       [](GiNaC::ex m, GiNaC::ex P, GiNaC::ex) { return 4 * P * m - P * P; }},
      {FilterKind::DelayEkf, [](GiNaC::ex m, GiNaC::ex, GiNaC::ex) { return m * m; },
       [](GiNaC::ex, GiNaC::ex P, GiNaC::ex) { return P; },
       [](GiNaC::ex m, GiNaC::ex P, GiNaC::ex) { return 4 * m * P - P * P; }},
  };
  for (const auto& c : cases) {
    const FilterEquations eq = derive_filter(model, c.kind);
    INFO("kind " << eq.name);
    const FilterVariables& vars = eq.variables;
    const std::vector<GiNaC::ex>& s = vars.symbols();
    const GiNaC::ex m = s[vars.m(0)], P = s[vars.P(0, 0)], phi = s[vars.phi(0)];
    CHECK(eq.delay == GiNaC::numeric(4, 5));
    check_equal(eq.m_drift[0], c.m_drift(m, P, phi), s, "m drift");
    check_equal(eq.gain[0][0], c.gain(m, P, phi), s, "gain");
    check_equal(eq.P_drift(0, 0), c.P_drift(m, P, phi), s, "P drift");
    check_equal(eq.predicted_observation[0], s[vars.m_delayed(0)], s, "innovation: dy - m(t - 0.8) dt");
    // The auxiliary x*: dx*/dt = x*^2 from m0 (only the Phi* kind has it).
    REQUIRE(eq.x_star_drift.size() == (c.kind == FilterKind::DelayOptimal ? 1u : 0u));
    if (!eq.x_star_drift.empty()) check_equal(eq.x_star_drift[0], GiNaC::pow(s[vars.x_star(0)], 2), s, "x* drift");
  }
}

TEST_CASE("evaluate_at of delay-optimal reads phi by the generated step's rule, 1 when h = 0", "[unit][delay]") {
  // dx = x^2 dt, dy = x(t - h) dt + dW2 at m = 0.5, P = 2 with x* = 0 (where the ratio would be 0/0).
  auto gain_at = [](const GiNaC::numeric& h, const GiNaC::numeric& t, const GiNaC::numeric& x_star) {
    ModelBuilder b("phi_rule");
    const GiNaC::symbol x = b.state("x");
    b.drift({GiNaC::pow(x, 2)});
    b.diffusion({{0}});
    b.delayed_observation(h, {0}, {{1}}, {{1}});
    const Model model = b.build();
    EvaluationPoint point;
    point.t = t;
    point.m = {GiNaC::numeric(1, 2)};
    point.P = {{2}};
    point.x_star = {x_star};
    point.x_star_delayed = {GiNaC::numeric(1, 4)};
    const EvaluatedFilter value = evaluate_at(model, derive_filter(model, FilterKind::DelayOptimal), point);
    REQUIRE(value.phi.size() == 1);
    CHECK(value.gain[0][0] == 2 * value.phi[0]);  // K = P phi
    return value.phi[0];
  };
  CHECK(gain_at(0, 0, 0) == 1);                          // h = 0: Phi* = I, even where x* = 0
  CHECK(gain_at(0, 3, GiNaC::numeric(1, 2)) == 1);
  CHECK(gain_at(GiNaC::numeric(4, 5), 3, 0) == 0);       // x*(t) = 0
  CHECK(gain_at(GiNaC::numeric(4, 5), GiNaC::numeric(1, 2), 1) == 0);  // t < h
  CHECK(gain_at(GiNaC::numeric(4, 5), GiNaC::numeric(4, 5), 1) == 0.25);  // t = h: x*(0) / x*(h)
}
