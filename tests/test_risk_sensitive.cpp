// The risk-sensitive kind (docs/theory.md §2.7) against what does not share its code:
// - the linear risk-sensitive (LEQG) filter of Speyer, Fan and Banavar written with GiNaC matrices,
//     dm = A m dt + P C^T V^-1 (dy - C m dt),  dP/dt = A P + P A^T + W - P (C^T V^-1 C - theta M) P,
//   theta = 2/eps, and Kalman-Bucy (pfgen's optimal filter there) as eps grows;
// - for nonlinear drifts, the closed form of the second-order expansion, by GiNaC differentiation:
//     dm = [f(m) - P grad(div f)(m)] dt + gain (dy - (A0 + A m) dt),
//     dP/dt = J P + P J^T + G - P (Hess(div f)(m) + A^T R^-1 A - (2/eps) M) P,  J = df/dx(m);
// - the construction's own consistency: its innovation term is -gain (A0 + A m).
#include <catch2/catch.hpp>

#include <algorithm>
#include <sstream>

#include "pfgen/derivation/filter_equations.hpp"
#include "pfgen/derivation/risk_sensitive.hpp"
#include "pfgen/model/model_builder.hpp"
#include "pfgen/model/model_filters.hpp"
#include "pfgen/model/yaml_model_loader.hpp"

#include "support/symbolic_mismatch.hpp"

using namespace pfgen;
using pfgen_test::mismatch;
using pfgen_test::text;
using GiNaC::ex;
using GiNaC::numeric;

namespace {

// The filter's variables as GiNaC symbols, and its equations as expressions in them.
struct Symbolic {
  std::vector<ex> variables;  // m1..mn, then the upper triangle of P
  GiNaC::matrix m, P;
  explicit Symbolic(const FilterVariables& vars) : variables(vars.symbols()), m(vars.n(), 1), P(vars.n(), vars.n()) {
    for (std::size_t i = 0; i < vars.n(); ++i) {
      m(i, 0) = variables[vars.m(i)];
      for (std::size_t j = 0; j < vars.n(); ++j) P(i, j) = variables[vars.P(i, j)];
    }
  }
  ex of(const Polynomial& p) const { return p.to_ex(variables); }
};

GiNaC::matrix to_matrix(const ExMatrix& m) {
  GiNaC::matrix out(static_cast<unsigned>(m.size()), static_cast<unsigned>(m.at(0).size()));
  for (unsigned i = 0; i < out.rows(); ++i)
    for (unsigned j = 0; j < out.cols(); ++j) out(i, j) = m[i][j];
  return out;
}

// Checks the derived filter against the closed form with f's derivatives taken by GiNaC.
void check_closed_form(const Model& model) {
  const FilterEquations eq = derive_filter(model, FilterKind::RiskSensitive);
  const Symbolic s(eq.variables);
  const std::size_t n = model.n();
  GiNaC::exmap at_m;
  for (std::size_t i = 0; i < n; ++i) at_m[model.states[i]] = s.m(i, 0);
  ex div_f = 0;
  for (std::size_t i = 0; i < n; ++i) div_f += model.drift[i].diff(model.states[i]);
  GiNaC::matrix J(n, n), grad_div(n, 1), hess_div(n, n);
  for (std::size_t i = 0; i < n; ++i) {
    grad_div(i, 0) = div_f.diff(model.states[i]).subs(at_m);
    for (std::size_t k = 0; k < n; ++k) {
      J(i, k) = model.drift[i].diff(model.states[k]).subs(at_m);
      hess_div(i, k) = div_f.diff(model.states[i]).diff(model.states[k]).subs(at_m);
    }
  }
  const AffineRate& obs = *model.observation.rate().affine();
  const GiNaC::matrix A = to_matrix(obs.A), R = to_matrix(multiply_by_transpose(obs.B));
  const GiNaC::matrix At_Rinv = A.transpose().mul(R.inverse());
  const GiNaC::matrix M = to_matrix(model.risk->weight);
  const GiNaC::matrix K = hess_div.add(At_Rinv.mul(A)).sub(M.mul_scalar(2 / model.risk->epsilon));
  const GiNaC::matrix P_drift =
      J.mul(s.P).add(s.P.mul(J.transpose())).add(to_matrix(model.diffusion.G)).sub(s.P.mul(K).mul(s.P));
  const GiNaC::matrix m_drift = s.P.mul(grad_div);
  const GiNaC::matrix gain = s.P.mul(At_Rinv);
  for (std::size_t i = 0; i < n; ++i) {
    INFO(model.name << ", m_drift[" << i + 1 << "]");
    CHECK(mismatch(model.drift[i].subs(at_m) - m_drift(i, 0), s.of(eq.m_drift[i])) == "");
    for (std::size_t r = 0; r < model.p(); ++r) CHECK(mismatch(gain(i, r), s.of(eq.gain[i][r])) == "");
    for (std::size_t j = i; j < n; ++j) {
      INFO("P_drift[" << i + 1 << "][" << j + 1 << "]");
      CHECK(mismatch(P_drift(i, j), s.of(eq.P_drift(i, j))) == "");
    }
  }
  // The innovation the construction gives is the one every filter uses: -gain (A0 + A m).
  const RiskSensitiveTerms terms = risk_sensitive_terms(model, eq.variables);
  for (std::size_t i = 0; i < n; ++i) {
    ex expected = 0;
    for (std::size_t r = 0; r < model.p(); ++r) expected -= s.of(eq.gain[i][r]) * s.of(eq.predicted_observation[r]);
    CHECK(mismatch(expected, s.of(terms.innovation_drift[i])) == "");
  }
  // Code generation computes the transport part from jacobian_term: it must be J(m).
  for (std::size_t i = 0; i < n; ++i)
    for (std::size_t k = 0; k < n; ++k) CHECK(mismatch(J(i, k), s.of(eq.jacobian_term[i][k])) == "");
}

}  // namespace

TEST_CASE("risk-sensitive kind of a linear model is the LEQG filter, and Kalman-Bucy as eps grows",
          "[risk][unit]") {
  ModelBuilder b("leqg_n2");
  auto x1 = b.state("x1"), x2 = b.state("x2");
  auto eps = b.parameter("eps", 3), k = b.parameter("k", numeric(1, 2)), s = b.parameter("s", numeric(2, 3));
  auto t = b.time();
  b.drift({x2 + sin(t), -k * x1 - x2 / 3});
  b.diffusion({{s, 0}, {numeric(1, 2), 1}});
  b.observation({0, sin(t)}, {{1, 0}, {1, 2}}, {{1, 0}, {numeric(1, 4), numeric(1, 2)}});
  b.risk_criterion(eps, {{2, numeric(1, 2)}, {numeric(1, 2), 1}});
  const Model model = b.build();

  const FilterEquations rs = derive_filter(model, FilterKind::RiskSensitive);
  CHECK(rs.exactness.exact);
  CHECK(rs.exactness.condition == "LEQG");
  const Symbolic sym(rs.variables);
  // Speyer-Fan-Banavar with theta = 2/eps and the weight M: written here with matrices.
  const GiNaC::matrix F{{0, 1}, {-k, numeric(-1, 3)}};
  const GiNaC::matrix C{{1, 0}, {1, 2}};
  const GiNaC::matrix Bv{{1, 0}, {numeric(1, 4), numeric(1, 2)}};
  const GiNaC::matrix g{{s, 0}, {numeric(1, 2), 1}};
  const GiNaC::matrix M{{2, numeric(1, 2)}, {numeric(1, 2), 1}};
  const GiNaC::matrix V = Bv.mul(Bv.transpose()), W = g.mul(g.transpose());
  const GiNaC::matrix Ct_Vinv = C.transpose().mul(V.inverse());
  const GiNaC::matrix P_leqg = F.mul(sym.P)
                                   .add(sym.P.mul(F.transpose()))
                                   .add(W)
                                   .sub(sym.P.mul(Ct_Vinv.mul(C).sub(M.mul_scalar(2 / ex(eps)))).mul(sym.P));
  const GiNaC::matrix m_leqg = F.mul(sym.m).add(GiNaC::matrix{{sin(t)}, {0}});
  const GiNaC::matrix gain_leqg = sym.P.mul(Ct_Vinv);

  const FilterEquations kb = derive_filter(model, FilterKind::Optimal);
  for (std::size_t i = 0; i < 2; ++i) {
    CHECK(mismatch(m_leqg(i, 0), sym.of(rs.m_drift[i])) == "");
    for (std::size_t r = 0; r < 2; ++r) CHECK(mismatch(gain_leqg(i, r), sym.of(rs.gain[i][r])) == "");
    for (std::size_t j = i; j < 2; ++j) {
      INFO("P_drift[" << i + 1 << "][" << j + 1 << "]");
      CHECK(mismatch(P_leqg(i, j), sym.of(rs.P_drift(i, j))) == "");
      // The risk term is all that separates it from Kalman-Bucy: (2/eps) (P M P)_ij, which
      // vanishes as eps grows.
      const ex risk = sym.P.mul(M).mul(sym.P)(i, j) * 2 / ex(eps);
      CHECK(mismatch(risk, sym.of(rs.P_drift(i, j)) - sym.of(kb.P_drift(i, j))) == "");
    }
    CHECK(mismatch(sym.of(kb.m_drift[i]), sym.of(rs.m_drift[i])) == "");
    for (std::size_t r = 0; r < 2; ++r) CHECK(mismatch(sym.of(kb.gain[i][r]), sym.of(rs.gain[i][r])) == "");
  }
}

TEST_CASE("risk-sensitive kind of quadratic and cubic drifts equals the closed-form expansion", "[risk][unit]") {
  {  // paper 002's stirred-tank reactor (u = 0), both states observed, eps and gamma parameters.
    ModelBuilder b("reactor");
    auto x1 = b.state("x1"), x2 = b.state("x2");
    auto eps = b.parameter("eps", 10), gamma = b.parameter("gamma", 1);
    const ex q = sqrt(eps / (2 * pow(gamma, 2)));
    b.drift({-2 * x1, x1 - x2 - pow(x2, 2)});
    b.diffusion({{q, 0}, {0, q}});
    b.observation({0, 0}, {{1, 0}, {0, 1}}, {{q, 0}, {0, q}});
    b.risk_criterion(eps);
    check_closed_form(b.build());
  }
  {  // paper 002's monoaxial satellite: cubic, x1 observed only.
    ModelBuilder b("satellite");
    auto x1 = b.state("x1"), x2 = b.state("x2");
    auto eps = b.parameter("eps", 10);
    b.drift({numeric(1, 2) * (1 + pow(x1, 2)) * x2, 0});
    b.diffusion({{1, 0}, {0, 1}});
    b.observation({0}, {{1, 0}}, {{1}});
    b.risk_criterion(eps, {{1, 0}, {0, 3}});
    check_closed_form(b.build());
  }
  {  // n = 3, dense cubic with time-varying and parameter coefficients, A0 != 0, correlated noise.
    ModelBuilder b("dense3");
    auto x = b.state("x"), y = b.state("y"), z = b.state("z");
    auto eps = b.parameter("eps", numeric(1, 2)), c = b.parameter("c", numeric(3, 2));
    auto t = b.time();
    b.drift({-x + c * x * y * z - pow(y, 3) + sin(t), x * x - y + numeric(1, 3) * z * z * x,
             -z + x * y - c * pow(z, 3) + t * y * y});
    b.diffusion_covariance({{1, numeric(1, 2), 0}, {numeric(1, 2), 2, 0}, {0, 0, cos(t) + 2}});
    b.observation({1, sin(t)}, {{1, 0, c}, {0, 1, 1}}, {{2, 0}, {1, 1}});
    b.risk_criterion(eps * c, {{1, 0, 0}, {0, 2, 1}, {0, 1, 2}});
    check_closed_form(b.build());
  }
}

TEST_CASE("risk-sensitive kind is refused, with the reason, where its construction does not apply",
          "[risk][unit]") {
  const std::string base = R"(name: refused
states: [x]
parameters: {eps: 2}
drift: ["DRIFT"]
diffusion: [["DIFFUSION"]]
observation: {A0: ["0"], A: [["1"]], B: [["1"]]}
initial: {x0: [1], m0: [0], P0: [[1]]}
RISK
)";
  auto model = [&](const std::string& drift, const std::string& diffusion, const std::string& risk) {
    std::string text = base;
    text.replace(text.find("DRIFT"), 5, drift);
    text.replace(text.find("DIFFUSION"), 9, diffusion);
    text.replace(text.find("RISK"), 4, risk);
    return load_model_text(text, "refused.yaml");
  };
  auto reason = [&](const Model& m) { return unsupported_reason(m, FilterKind::RiskSensitive).value_or(""); };
  CHECK(reason(model("-x + x^3", "1", "risk: {epsilon: eps}")) == "");
  CHECK(reason(model("-x + x^4", "1", "risk: {epsilon: eps}")) ==
        "is derived for drifts of degree <= 3 (drift[1] has degree 4)");
  CHECK(reason(model("-x", "x", "risk: {epsilon: eps}")) ==
        "needs a state-independent diffusion (additive noise, as its construction assumes)");
  CHECK(reason(model("-x", "1", "")) == "needs a risk: section (risk: {epsilon: ...})");
  // Not offered where refused, so the default filter lists of such models do not change.
  const std::vector<std::string> names = available_filter_names(model("-x", "1", ""));
  CHECK(std::find(names.begin(), names.end(), "risk-sensitive") == names.end());
  CHECK_THROWS_WITH(derive_named_filter(model("x^2*x^2", "1", "risk: {epsilon: eps}"), "risk-sensitive"),
                    Catch::Contains("drift[1] has degree 4"));
}
