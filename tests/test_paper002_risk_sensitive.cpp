// Paper 002's printed risk-sensitive filters, (21) for the reactor and (25) for the satellite,
// against pfgen's `risk-sensitive` kind for examples/paper002/. First the kind's equations for each
// model are checked against a hand derivation written here (docs/theory.md, the risk-sensitive
// filter): dC = [f(C) - P grad(div f)(C)] dt + P A^T R^-1 (dy - A C dt),
// dP/dt = F P + P F^T + W - P Hess(div f)(C) P - P (A^T R^-1 A - (2/eps) I) P, F = df/dx(C),
// W = R = s I, s = eps/(2 gamma^2). Then they are mapped to the paper's variable Q = -eps P^-1,
// dQ/dt = eps^-1 Q (dP/dt) Q, and the exact difference derived - printed of every Q equation is
// asserted, as is the printed gain against the derived one (docs/paper-discrepancies.md, "Paper 002").
#include <ginac/ginac.h>

#include <catch2/catch.hpp>
#include <string>
#include <vector>

#include "pfgen/derivation/filter_equations.hpp"
#include "pfgen/model/yaml_model_loader.hpp"
#include "support/test_paths.hpp"

namespace {

using GiNaC::ex;
using GiNaC::matrix;
using GiNaC::numeric;
using GiNaC::pow;
using GiNaC::symbol;

ex parameter(const pfgen::Model& model, const std::string& name) {
  for (const auto& p : model.parameters)
    if (p.name == name) return p.symbol;
  FAIL("no parameter " << name);
  return 0;
}

bool same(const ex& a, const ex& b) { return (a - b).normal().is_zero(); }

// The kind's equations for a two-state model, in its own symbols C1, C2 (= m1, m2), P11, P12, P22.
struct RiskSensitive {
  ex C1, C2, P11, P12, P22, eps, gamma;
  std::vector<ex> m_drift;         // 2
  matrix P_drift{2, 2};
  std::vector<std::vector<ex>> gain;  // 2 x p
  ex s() const { return eps / (2 * pow(gamma, 2)); }
};

RiskSensitive derive(const pfgen::Model& model) {
  const pfgen::FilterEquations eq = pfgen::derive_named_filter(model, "risk-sensitive");
  const auto& v = eq.variables.symbols();
  REQUIRE(v.size() == 5);
  RiskSensitive rs{v[0], v[1], v[2], v[3], v[4], parameter(model, "eps"), parameter(model, "gamma"), {}, matrix(2, 2), {}};
  for (std::size_t i = 0; i < 2; ++i) rs.m_drift.push_back(eq.m_drift.at(i).to_ex(v));
  for (unsigned i = 0; i < 2; ++i)
    for (unsigned j = 0; j < 2; ++j) rs.P_drift(i, j) = eq.P_drift(i, j).to_ex(v);
  for (const auto& row : eq.gain) {
    rs.gain.emplace_back();
    for (const auto& entry : row) rs.gain.back().push_back(entry.to_ex(v));
  }
  return rs;
}

// The paper's Q and the map P = -eps Q^-1.
struct QForm {
  symbol Q11{"Q11"}, Q12{"Q12"}, Q22{"Q22"};
  matrix Q() const { return matrix{{Q11, Q12}, {Q12, Q22}}; }
  ex det() const { return Q11 * Q22 - pow(Q12, 2); }
  matrix Q_inverse() const { return matrix{{Q22 / det(), -Q12 / det()}, {-Q12 / det(), Q11 / det()}}; }
  // P's entries as functions of Q.
  GiNaC::exmap P_of_Q(const RiskSensitive& rs) const {
    const matrix Qi = Q_inverse();
    return {{rs.P11, -rs.eps * Qi(0, 0)}, {rs.P12, -rs.eps * Qi(0, 1)}, {rs.P22, -rs.eps * Qi(1, 1)}};
  }
  // dQ/dt = eps^-1 Q (dP/dt) Q with P = -eps Q^-1.
  matrix Q_drift(const RiskSensitive& rs) const {
    const matrix dP = GiNaC::ex_to<matrix>(rs.P_drift.subs(P_of_Q(rs)));
    const matrix product = Q().mul(dP).mul(Q());
    matrix out(2, 2);
    for (unsigned i = 0; i < 2; ++i)
      for (unsigned j = 0; j < 2; ++j) out(i, j) = (product(i, j) / rs.eps).normal();
    return out;
  }
};

// (21)'s printed Q equations, its "Q11^2 Q12^2" read as Q11^2 + Q12^2 (the extraction lost a +).
std::vector<ex> reactor_printed_dQ(const QForm& q) {
  return {4 * q.Q11 + pow(q.Q11, 2) + pow(q.Q12, 2) - 1, 3 * q.Q12 + q.Q11 + q.Q11 * q.Q12 - q.Q12 * q.Q22,
          2 * q.Q22 - 2 * q.Q12 + pow(q.Q12, 2) + pow(q.Q22, 2) - 1};
}

// (25)'s printed Q equations.
std::vector<ex> satellite_printed_dQ(const QForm& q, const ex& C1, const ex& C2, const ex& eps) {
  return {q.Q12 - C1 * C2 * q.Q11 - pow(C2, 2) * q.Q12 + C2 * q.Q22 + q.Q11 + q.Q22 - eps * C1 * C2,
          numeric(1, 2) * q.Q22 + q.Q11 * q.Q12 + q.Q12 * q.Q22, pow(q.Q12, 2) + pow(q.Q22, 2) - eps * C1 * C2};
}

// A user filter of the example with its definitions substituted: m_drift, gain and P_drift in the
// kind's symbols (the same FilterVariables order), for comparison with a transcription here.
struct UserFilterExpressions {
  std::vector<ex> m_drift;
  std::vector<std::vector<ex>> gain;
  matrix P_drift{2, 2};
};

UserFilterExpressions user_filter(const pfgen::Model& model, const std::string& name, const RiskSensitive& rs) {
  const pfgen::FilterEquations eq = pfgen::derive_named_filter(model, name);
  const auto& v = eq.variables.symbols();
  // The filter's own symbols renamed to the kind's, then the definitions substituted, last first.
  GiNaC::exmap to_kind = {{v[0], rs.C1}, {v[1], rs.C2}, {v[2], rs.P11}, {v[3], rs.P12}, {v[4], rs.P22}};
  auto expression = [&](const pfgen::Polynomial& p) {
    ex e = p.to_ex(v);
    for (auto d = eq.definitions.rbegin(); d != eq.definitions.rend(); ++d) e = e.subs(d->name == d->value);
    return e.subs(to_kind);
  };
  UserFilterExpressions out;
  for (std::size_t i = 0; i < 2; ++i) out.m_drift.push_back(expression(eq.m_drift[i]));
  for (const auto& row : eq.gain) {
    out.gain.emplace_back();
    for (const auto& entry : row) out.gain.back().push_back(expression(entry));
  }
  for (unsigned i = 0; i < 2; ++i)
    for (unsigned j = 0; j < 2; ++j) out.P_drift(i, j) = expression(eq.P_drift(i, j));
  return out;
}

// Q = -eps P^-1 in the kind's P symbols.
GiNaC::exmap Q_of_P(const QForm& q, const RiskSensitive& rs) {
  const ex det = rs.P11 * rs.P22 - pow(rs.P12, 2);
  return {{q.Q11, -rs.eps * rs.P22 / det}, {q.Q12, rs.eps * rs.P12 / det}, {q.Q22, -rs.eps * rs.P11 / det}};
}

// dP/dt = eps^-1 P (dQ/dt) P, from P = -eps Q^-1: the printed Q equations carried over to P.
matrix P_drift_of_printed(const std::vector<ex>& dQ, const QForm& q, const RiskSensitive& rs) {
  const matrix P{{rs.P11, rs.P12}, {rs.P12, rs.P22}};
  const matrix dQm = GiNaC::ex_to<matrix>(matrix{{dQ[0], dQ[1]}, {dQ[1], dQ[2]}}.subs(Q_of_P(q, rs)));
  return GiNaC::ex_to<matrix>((P.mul(dQm).mul(P)).mul_scalar(1 / rs.eps));
}

void check_Q_difference(const matrix& derived, const ex printed[3], const ex difference[3]) {
  const char* names[] = {"dQ11", "dQ12", "dQ22"};
  const unsigned rows[] = {0, 0, 1}, columns[] = {0, 1, 1};
  for (int k = 0; k < 3; ++k) {
    INFO(names[k] << ": derived " << derived(rows[k], columns[k]) << ", printed " << printed[k]);
    CHECK(same(derived(rows[k], columns[k]) - printed[k], difference[k]));
  }
}

}  // namespace

TEST_CASE("paper 002: the reactor's risk-sensitive filter against the printed (21) in Q = -eps P^-1",
          "[paper002][risk-sensitive][unit]") {
  const pfgen::Model model = pfgen::load_model_file(pfgen_test::example("paper002/reactor.yaml"));
  const RiskSensitive rs = derive(model);
  const ex &C1 = rs.C1, &C2 = rs.C2, &P11 = rs.P11, &P12 = rs.P12, &P22 = rs.P22, &eps = rs.eps, &gamma = rs.gamma;
  // By hand: div f = -3 - 2 x2, so grad(div f) = (0, -2) and Hess(div f) = 0; F = [-2, 0; 1, -1 - 2 C2];
  // A = I, R = W = s I: the quadratic term is (1/s - 2/eps) P^2 = k P^2, zero at gamma = 1.
  const ex k = 2 * (pow(gamma, 2) - 1) / eps;
  CHECK(same(rs.m_drift[0], -2 * C1 + 2 * P12));
  CHECK(same(rs.m_drift[1], C1 - C2 - pow(C2, 2) + 2 * P22));
  CHECK(same(rs.P_drift(0, 0), -4 * P11 + rs.s() - k * (pow(P11, 2) + pow(P12, 2))));
  CHECK(same(rs.P_drift(0, 1), P11 - 3 * P12 - 2 * C2 * P12 - k * (P11 * P12 + P12 * P22)));
  CHECK(same(rs.P_drift(1, 1), 2 * P12 - 2 * P22 - 4 * C2 * P22 + rs.s() - k * (pow(P12, 2) + pow(P22, 2))));
  REQUIRE(rs.gain.size() == 2);
  CHECK(same(rs.gain[0][0], P11 / rs.s()));
  CHECK(same(rs.gain[0][1], P12 / rs.s()));
  CHECK(same(rs.gain[1][1], P22 / rs.s()));

  // Derived in Q: dQ/dt = -Q F - F^T Q + Q^2/(2 gamma^2) + (2 - 2 gamma^2) I. (21) as printed, its
  // "Q11^2 Q12^2" read as Q11^2 + Q12^2 (the extraction lost a +):
  const QForm q;
  const std::vector<ex> printed_dQ = reactor_printed_dQ(q);
  const ex* printed = printed_dQ.data();
  // derived - printed: (21) takes the constant A1 for F (no C2 terms), transposes it in dQ11 and
  // dQ22 (so -2 Q12 goes missing from dQ11 and +2 Q12 appears in dQ22) and twists dQ12's signs; its
  // Q^2 has coefficient 1 for 1/(2 gamma^2), and its constant -1 stands for 2 - 2 gamma^2 (the risk
  // term 2 I is absent: -1 is -E1^T E1 at gamma^2 = 1/2).
  const ex c = 1 / (2 * pow(gamma, 2)) - 1;
  const ex difference[3] = {-2 * q.Q12 + c * (pow(q.Q11, 2) + pow(q.Q12, 2)) + 3 - 2 * pow(gamma, 2),
                            2 * C2 * q.Q12 - q.Q22 - q.Q11 + c * q.Q11 * q.Q12 + (c + 2) * q.Q12 * q.Q22,
                            4 * C2 * q.Q22 + 2 * q.Q12 + c * (pow(q.Q12, 2) + pow(q.Q22, 2)) + 3 - 2 * pow(gamma, 2)};
  check_Q_difference(q.Q_drift(rs), printed, difference);

  // The gain in Q: derived K = P R^-1 = -2 gamma^2 Q^-1. (21) multiplies dY by
  // (-dQ11/det) [-dY1 Q22 + dY2 Q12] and (-dQ12/det) [-dY1 Q12 + dY2 Q11]: rows of Q^-1 scaled by
  // dQ11 and -dQ12 (the printed derivatives), where the derivation has -2 gamma^2 in both.
  const matrix Qi = q.Q_inverse();
  const GiNaC::exmap to_Q = q.P_of_Q(rs);
  for (unsigned i = 0; i < 2; ++i)
    for (unsigned j = 0; j < 2; ++j) CHECK(same(rs.gain[i][j].subs(to_Q), -2 * pow(gamma, 2) * Qi(i, j)));
  const ex det = q.det();
  CHECK(same(-printed[0] / det * -q.Q22, printed[0] * Qi(0, 0)));
  CHECK(same(-printed[1] / det * -q.Q12, -printed[1] * Qi(1, 0)));
}

TEST_CASE("paper 002: the satellite's risk-sensitive filter against the printed (25) in Q = -eps P^-1",
          "[paper002][risk-sensitive][unit]") {
  const pfgen::Model model = pfgen::load_model_file(pfgen_test::example("paper002/satellite.yaml"));
  const RiskSensitive rs = derive(model);
  const ex &C1 = rs.C1, &C2 = rs.C2, &P11 = rs.P11, &P12 = rs.P12, &P22 = rs.P22, &eps = rs.eps;
  const ex half = numeric(1, 2);
  // By hand: div f = x1 x2, grad(div f) = (x2, x1), Hess(div f) = [0, 1; 1, 0];
  // F = [C1 C2, (1 + C1^2)/2; 0, 0]; A = (1, 0), R = W = s.
  CHECK(same(rs.m_drift[0], half * C2 + half * pow(C1, 2) * C2 - P11 * C2 - P12 * C1));
  CHECK(same(rs.m_drift[1], -P12 * C2 - P22 * C1));
  CHECK(same(rs.P_drift(0, 0), 2 * C1 * C2 * P11 + (1 + pow(C1, 2)) * P12 + rs.s() - 2 * P11 * P12 -
                                   pow(P11, 2) / rs.s() + 2 / eps * (pow(P11, 2) + pow(P12, 2))));
  CHECK(same(rs.P_drift(0, 1), C1 * C2 * P12 + half * (1 + pow(C1, 2)) * P22 - P11 * P22 - pow(P12, 2) -
                                   P11 * P12 / rs.s() + 2 / eps * (P11 * P12 + P12 * P22)));
  CHECK(same(rs.P_drift(1, 1), rs.s() - 2 * P12 * P22 - pow(P12, 2) / rs.s() + 2 / eps * (pow(P12, 2) + pow(P22, 2))));
  REQUIRE(rs.gain.size() == 2);
  CHECK(same(rs.gain[0][0], P11 / rs.s()));
  CHECK(same(rs.gain[1][0], P12 / rs.s()));

  // Derived in Q: dQ/dt = -Q F - F^T Q + Q^2/(2 gamma^2) - eps (A^T R^-1 A - (2/eps) I + Hess div f).
  const QForm q;
  const ex &gamma = rs.gamma;
  const std::vector<ex> printed_dQ = satellite_printed_dQ(q, C1, C2, eps);
  const ex* printed = printed_dQ.data();
  const ex g = 1 / (2 * pow(gamma, 2));
  const ex derived[3] = {-2 * C1 * C2 * q.Q11 + g * (pow(q.Q11, 2) + pow(q.Q12, 2)) + 2 - 2 * pow(gamma, 2),
                         -half * (1 + pow(C1, 2)) * q.Q11 - C1 * C2 * q.Q12 + g * (q.Q11 * q.Q12 + q.Q12 * q.Q22) - eps,
                         -(1 + pow(C1, 2)) * q.Q12 + g * (pow(q.Q12, 2) + pow(q.Q22, 2)) + 2};
  // Nothing of (25)'s Q equations survives but the shape Q^2 (coefficient 1 for 1/(2 gamma^2)) and a
  // C1 C2 Q11 term (-1 for -2); the difference is listed whole.
  const ex difference[3] = {derived[0] - printed[0], derived[1] - printed[1], derived[2] - printed[2]};
  check_Q_difference(q.Q_drift(rs), printed, difference);
  // The printed terms the derivation does not have at all (in no reading of gamma):
  CHECK((difference[0].expand().coeff(C2, 2).coeff(q.Q12, 1) - 1).is_zero());  // -C2^2 Q12 printed
  CHECK((difference[1].expand().coeff(q.Q22, 1).subs(q.Q12 == 0) + half).is_zero());  // 0.5 Q22 printed
  CHECK((difference[2].expand().coeff(eps, 1).coeff(C1, 1).coeff(C2, 1) - 1).is_zero());  // -eps C1 C2 printed

  // The gain in Q: derived K = P A^T R^-1 = -2 gamma^2 (Q^-1)_{i1}.
  const matrix Qi = q.Q_inverse();
  const GiNaC::exmap to_Q = q.P_of_Q(rs);
  for (unsigned i = 0; i < 2; ++i) CHECK(same(rs.gain[i][0].subs(to_Q), -2 * pow(gamma, 2) * Qi(i, 0)));
}

// The printed filters run as printed through the examples' `filters:` (rs-printed, with Q, dQ and
// det Q under `define:`): with the definitions substituted, each equation is the transcription of
// (21) or (25) here, carried over to P = -eps Q^-1 (dP = eps^-1 P dQ P; dm = m_drift dt +
// gain (dy - A m dt), so the printed dC is m_drift - gain A m + gain dy/dt).
TEST_CASE("paper 002: the examples' rs-printed filters are (21) and (25) as printed",
          "[paper002][risk-sensitive][userfilter][unit]") {
  const QForm q;
  SECTION("reactor, (21)") {
    const pfgen::Model model = pfgen::load_model_file(pfgen_test::example("paper002/reactor.yaml"));
    const RiskSensitive rs = derive(model);
    const UserFilterExpressions user = user_filter(model, "rs-printed", rs);
    const std::vector<ex> dQ = reactor_printed_dQ(q);
    const matrix dP = P_drift_of_printed(dQ, q, rs);
    for (unsigned i = 0; i < 2; ++i)
      for (unsigned j = 0; j < 2; ++j) CHECK(same(user.P_drift(i, j), dP(i, j)));
    // dC1 = (-dQ11/det Q)[dQ11 (Q22 C1 - Q12 C2) + dQ12 (Q11 C2 - Q12 C1) - dY1 Q22 + dY2 Q12] - 2 C1 + Q11 C1 + Q12 C2
    // dC2 = (-dQ12/det Q)[dQ12 (Q22 C1 - Q12 C2) + dQ22 (Q11 C2 - Q12 C1) - dY1 Q12 + dY2 Q11 - 2 eps Q11]
    //       + C1 - C2 + Q12 C1 + Q22 C2
    const ex det = q.det();
    const ex K[2][2] = {{dQ[0] * q.Q22 / det, -dQ[0] * q.Q12 / det}, {dQ[1] * q.Q12 / det, -dQ[1] * q.Q11 / det}};
    const ex rest[2] = {-dQ[0] / det * (dQ[0] * (q.Q22 * rs.C1 - q.Q12 * rs.C2) + dQ[1] * (q.Q11 * rs.C2 - q.Q12 * rs.C1)) -
                            2 * rs.C1 + q.Q11 * rs.C1 + q.Q12 * rs.C2,
                        -dQ[1] / det *
                                (dQ[1] * (q.Q22 * rs.C1 - q.Q12 * rs.C2) + dQ[2] * (q.Q11 * rs.C2 - q.Q12 * rs.C1) -
                                 2 * rs.eps * q.Q11) +
                            rs.C1 - rs.C2 + q.Q12 * rs.C1 + q.Q22 * rs.C2};
    const GiNaC::exmap to_P = Q_of_P(q, rs);
    const ex C[2] = {rs.C1, rs.C2};
    for (unsigned i = 0; i < 2; ++i) {
      INFO("row " << i + 1);
      for (unsigned r = 0; r < 2; ++r) CHECK(same(user.gain[i][r], K[i][r].subs(to_P)));
      CHECK(same(user.m_drift[i] - user.gain[i][0] * C[0] - user.gain[i][1] * C[1], rest[i].subs(to_P)));
    }
  }
  SECTION("satellite, (25)") {
    const pfgen::Model model = pfgen::load_model_file(pfgen_test::example("paper002/satellite.yaml"));
    const RiskSensitive rs = derive(model);
    const UserFilterExpressions user = user_filter(model, "rs-printed", rs);
    const std::vector<ex> dQ = satellite_printed_dQ(q, rs.C1, rs.C2, rs.eps);
    const matrix dP = P_drift_of_printed(dQ, q, rs);
    for (unsigned i = 0; i < 2; ++i)
      for (unsigned j = 0; j < 2; ++j) CHECK(same(user.P_drift(i, j), dP(i, j)));
    // dC1 = (-dQ22/det Q)(C1 dQ11 + C2 dQ12 + dY) + (-dQ12/det Q)(C1 dQ12 + C2 dQ22) - C2/2 + C1 Q11 + C2 Q12
    // dC2 = (-dQ12/det Q)(C1 dQ11 + C2 dQ12 + dY) + (-dQ11/det Q)(C1 dQ12 + C2 dQ22) + C1 Q12 + C2 Q22
    const ex det = q.det();
    const ex &C1 = rs.C1, &C2 = rs.C2;
    const ex K[2] = {-dQ[2] / det, -dQ[1] / det};
    const ex rest[2] = {-dQ[2] / det * (C1 * dQ[0] + C2 * dQ[1]) - dQ[1] / det * (C1 * dQ[1] + C2 * dQ[2]) -
                            numeric(1, 2) * C2 + C1 * q.Q11 + C2 * q.Q12,
                        -dQ[1] / det * (C1 * dQ[0] + C2 * dQ[1]) - dQ[0] / det * (C1 * dQ[1] + C2 * dQ[2]) + C1 * q.Q12 +
                            C2 * q.Q22};
    const GiNaC::exmap to_P = Q_of_P(q, rs);
    for (unsigned i = 0; i < 2; ++i) {
      INFO("row " << i + 1);
      REQUIRE(user.gain[i].size() == 1);
      CHECK(same(user.gain[i][0], K[i].subs(to_P)));
      CHECK(same(user.m_drift[i] - user.gain[i][0] * C1, rest[i].subs(to_P)));
    }
  }
}
