#include "pfgen/observations/sampled/sampled_update.hpp"

#include "pfgen/derivation/gaussian_expectation.hpp"
#include "pfgen/model/model.hpp"

namespace pfgen {

SampledUpdate sampled_update(const SampledObservation& observation, const FilterVariables& vars) {
  const std::size_t n = vars.n(), r = observation.C.size();
  auto P = [&](std::size_t i, std::size_t j) { return Monomial::variable(vars.P(i, j)); };
  SampledUpdate out;
  out.period = observation.period;
  out.C.assign(r, std::vector<Polynomial>(n));
  for (std::size_t a = 0; a < r; ++a)
    for (std::size_t k = 0; k < n; ++k) out.C[a][k] = Polynomial::constant(observation.C[a][k]);
  const ExMatrix R = multiply_by_transpose(observation.Uv);
  for (std::size_t a = 0; a < r; ++a)
    for (std::size_t b = a; b < r; ++b) out.R.push_back(Polynomial::constant(R[a][b]));
  // (P C^T)_ia = sum_k P_ik C_ak
  out.PCt.assign(n, std::vector<Polynomial>(r));
  for (std::size_t i = 0; i < n; ++i)
    for (std::size_t a = 0; a < r; ++a)
      for (std::size_t k = 0; k < n; ++k)
        if (!observation.C[a][k].is_zero()) out.PCt[i][a].add_term(P(i, k), observation.C[a][k]);
  // S_ab = sum_kl C_ak P_kl C_bl + R_ab
  for (std::size_t a = 0; a < r; ++a)
    for (std::size_t b = a; b < r; ++b) {
      Polynomial s = Polynomial::constant(R[a][b]);
      for (std::size_t k = 0; k < n; ++k)
        for (std::size_t l = 0; l < n; ++l)
          if (!observation.C[a][k].is_zero() && !observation.C[b][l].is_zero())
            s.add_term(P(k, l), observation.C[a][k] * observation.C[b][l]);
      out.S.push_back(std::move(s));
    }
  return out;
}

std::vector<Polynomial> predicted_sample(const SampledObservation& observation, const FilterVariables& vars) {
  std::vector<Polynomial> out;
  for (std::size_t a = 0; a < observation.C.size(); ++a) {
    Polynomial h = Polynomial::constant(observation.C0[a]);
    for (std::size_t k = 0; k < vars.n(); ++k) h.add_term(Monomial::variable(vars.m(k)), observation.C[a][k]);
    out.push_back(h);
  }
  return out;
}

}  // namespace pfgen

namespace pfgen {

std::vector<Polynomial> sample_polynomials(const Model& model) {
  std::vector<Polynomial> c;
  for (const GiNaC::ex& entry : model.observation.sampled().c) c.push_back(Polynomial::from_ex(entry, model.states));
  return c;
}

SampledUpdate polynomial_sampled_update(const Model& model, const FilterVariables& vars, bool at_mean,
                                        std::vector<Polynomial>& predicted) {
  const SampledObservation& observation = model.observation.sampled();
  const std::size_t n = vars.n(), r = observation.c.size();
  const std::vector<Polynomial> c = sample_polynomials(model);
  // State x_i and mean m_i share variable index i (FilterVariables): c read as it is is c(m).
  GaussianExpectation E(vars);
  auto expectation = [&](const Polynomial& q) { return at_mean ? q : E.of(q); };
  auto P = [&](std::size_t i, std::size_t j) { return Monomial::variable(vars.P(i, j)); };

  SampledUpdate out;
  out.period = observation.period;
  out.polynomial_samples = true;
  out.at_mean = at_mean;
  predicted.clear();
  out.C.assign(r, std::vector<Polynomial>(n));  // E[J_c], or J_c(m)
  for (std::size_t a = 0; a < r; ++a) {
    predicted.push_back(expectation(c[a]));
    for (std::size_t k = 0; k < n; ++k) out.C[a][k] = expectation(c[a].derivative(static_cast<std::uint32_t>(k)));
  }
  // Cov(x, c) = P E[J_c]^T
  out.PCt.assign(n, std::vector<Polynomial>(r));
  for (std::size_t i = 0; i < n; ++i)
    for (std::size_t a = 0; a < r; ++a)
      for (std::size_t k = 0; k < n; ++k)
        if (!out.C[a][k].is_zero()) out.PCt[i][a] += out.C[a][k].times_monomial(P(i, k));
  const ExMatrix R = multiply_by_transpose(observation.Uv);
  for (std::size_t a = 0; a < r; ++a)
    for (std::size_t b = a; b < r; ++b) {
      // C P C^T, the linear part of Cov(c); the rest (zero at the mean) is what R_c adds to R.
      Polynomial CPCt;
      for (std::size_t k = 0; k < n; ++k)
        if (!out.C[a][k].is_zero()) CPCt += out.C[a][k] * out.PCt[k][b];
      const Polynomial noise = Polynomial::constant(R[a][b]);
      if (at_mean) {
        out.S.push_back(CPCt + noise);
        out.R.push_back(noise);
        continue;
      }
      const Polynomial covariance = E.of(c[a] * c[b]) - predicted[a] * predicted[b];
      out.S.push_back(covariance + noise);
      out.R.push_back(covariance - CPCt + noise);
    }
  return out;
}

}  // namespace pfgen
