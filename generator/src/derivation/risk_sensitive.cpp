#include "pfgen/derivation/risk_sensitive.hpp"

#include <map>

#include "pfgen/derivation/affine_rate_terms.hpp"

namespace pfgen {
namespace {

// Beyond the filter's own variables the construction uses u_1..u_n (x = m + P u) and, for the
// observation increment, ydot_1..ydot_p: numbered after FilterVariables::count(), never leaving
// this file.
class Construction {
 public:
  Construction(const Model& model, const FilterVariables& vars)
      : n_(model.n()), p_(model.p()), u0_(static_cast<std::uint32_t>(vars.count())) {
    // x_i = m_i + sum_k P_ik u_k; state x_i and mean m_i share index i (FilterVariables).
    for (std::size_t i = 0; i < n_; ++i) {
      Polynomial xi = Polynomial::variable(vars.m(i));
      for (std::size_t k = 0; k < n_; ++k)
        xi.add_term(Monomial::variable(vars.P(i, k)) * Monomial::variable(u(k)), 1);
      x_.push_back(std::move(xi));
    }
  }

  std::uint32_t u(std::size_t k) const { return u0_ + static_cast<std::uint32_t>(k); }
  std::uint32_t ydot(std::size_t r) const { return u0_ + static_cast<std::uint32_t>(n_ + r); }
  const Polynomial& x(std::size_t i) const { return x_[i]; }
  // (P u)_i, the part of x_i - m_i.
  Polynomial Pu(std::size_t i) const { return x_[i] - Polynomial::variable(static_cast<std::uint32_t>(i)); }

  // A polynomial in the states at x = m + P u, keeping powers of u up to 2 (the ansatz's order).
  Polynomial at_x(const Polynomial& in_states) const {
    Polynomial out;
    for (const auto& [monomial, coefficient] : in_states.terms()) {
      Polynomial term = Polynomial::constant(coefficient);
      for (const auto& [index, exponent] : monomial.factors())
        for (std::uint32_t e = 0; e < exponent; ++e) term = truncated(term * x_[index]);
      out += term;
    }
    return out;
  }

  Polynomial truncated(const Polynomial& p) const {
    Polynomial out;
    for (const auto& [monomial, coefficient] : p.terms())
      if (construction_degree(monomial) <= 2) out.add_term(monomial, coefficient);
    return out;
  }

  // The coefficient of the monomial `key` in the construction's variables (u, ydot): the
  // polynomial in m and P that multiplies exactly that power.
  Polynomial coefficient(const Polynomial& p, const Monomial& key) const {
    Polynomial out;
    for (const auto& [monomial, coefficient] : p.terms()) {
      Monomial own, rest;
      for (const auto& [index, exponent] : monomial.factors())
        (index >= u0_ ? own : rest) = (index >= u0_ ? own : rest) * Monomial::variable(index, exponent);
      if (own == key) out.add_term(rest, coefficient);
    }
    return out;
  }
  // dm_k is the coefficient of u_k; dP_ij that of u_i u_j (i < j) and twice that of u_i^2,
  // because the left-hand side is 1/2 u^T dP u + u^T dm (+ terms free of u).
  Polynomial linear(const Polynomial& p, std::size_t k) const { return coefficient(p, Monomial::variable(u(k))); }
  Polynomial quadratic(const Polynomial& p, std::size_t i, std::size_t j) const {
    if (i != j) return coefficient(p, Monomial::variable(u(i)) * Monomial::variable(u(j)));
    return coefficient(p, Monomial::variable(u(i), 2)).scaled(2);
  }

 private:
  std::uint32_t construction_degree(const Monomial& monomial) const {
    std::uint32_t degree = 0;
    for (const auto& [index, exponent] : monomial.factors())
      if (index >= u0_ && index < u0_ + n_) degree += exponent;
    return degree;
  }

  std::size_t n_, p_;
  std::uint32_t u0_;
  std::vector<Polynomial> x_;
};

}  // namespace

RiskSensitiveTerms risk_sensitive_terms(const Model& model, const FilterVariables& vars) {
  const std::size_t n = model.n(), p = model.p();
  const RiskCriterion& risk = *model.risk;
  const ContinuousObservation& observation = model.observation.rate();
  const ObservationTerms obs = observation_terms(observation);
  const Construction c(model, vars);
  auto u = [&](std::size_t k) { return Polynomial::variable(c.u(k)); };

  // The right-hand side of d(log sigma)/dt at x = m + P u, term by term (docs/theory.md §2.7):
  Polynomial transport, compression, diffusion, risk_term, observation_term, increment;
  for (std::size_t i = 0; i < n; ++i) {
    const Polynomial fi = Polynomial::from_ex(model.drift[i], model.states);
    transport += c.truncated(c.at_x(fi) * u(i));                                    // f(x)^T u
    compression -= c.at_x(fi.derivative(static_cast<std::uint32_t>(i)));              // -div f(x)
  }
  for (std::size_t i = 0; i < n; ++i)
    for (std::size_t j = 0; j < n; ++j) {
      diffusion += (u(i) * u(j)).scaled(model.diffusion.G[i][j] / 2);                 // 1/2 u^T G u
      if (!risk.weight[i][j].is_zero())
        risk_term += (c.Pu(i) * c.Pu(j)).scaled(risk.weight[i][j] / risk.epsilon);     // eps^-1 L(x, m)
    }
  // -1/2 h^T R^-1 h with h = A0 + A x: -(A0^T R^-1 A) x - 1/2 x^T (A^T R^-1 A) x (+ a constant).
  for (std::size_t k = 0; k < n; ++k) {
    GiNaC::ex a0_Rinv_A = 0;
    for (std::size_t r = 0; r < p; ++r) a0_Rinv_A += observation.A0[r] * obs.At_Rinv[k][r];
    observation_term -= c.x(k).scaled(a0_Rinv_A);
    for (std::size_t l = 0; l < n; ++l)
      if (!obs.At_Rinv_A[k][l].is_zero()) observation_term -= c.truncated(c.x(k) * c.x(l)).scaled(obs.At_Rinv_A[k][l] / 2);
  }
  // h^T R^-1 dy/dt: the x-dependent part x^T A^T R^-1 ydot.
  for (std::size_t k = 0; k < n; ++k)
    for (std::size_t r = 0; r < p; ++r)
      if (!obs.At_Rinv[k][r].is_zero())
        increment += (c.x(k) * Polynomial::variable(c.ydot(r))).scaled(obs.At_Rinv[k][r]);

  RiskSensitiveTerms out;
  out.gain.assign(n, std::vector<Polynomial>(p));
  for (std::size_t k = 0; k < n; ++k) {
    out.m_drift.push_back(c.linear(transport, k) + c.linear(compression, k));
    out.innovation_drift.push_back(c.linear(observation_term, k));
    for (std::size_t r = 0; r < p; ++r)
      out.gain[k][r] = c.coefficient(increment, Monomial::variable(c.u(k)) * Monomial::variable(c.ydot(r)));
  }
  for (std::size_t i = 0; i < n; ++i)
    for (std::size_t j = i; j < n; ++j) {
      out.P_moment.push_back(c.quadratic(transport, i, j));
      out.P_diffusion.push_back(c.quadratic(diffusion, i, j));
      Polynomial correction = c.quadratic(compression, i, j) + c.quadratic(risk_term, i, j) +
                              c.quadratic(observation_term, i, j);
      out.P_correction.push_back(Polynomial() - correction);
    }
  return out;
}

}  // namespace pfgen
