#include "pfgen/observations/sampled/sampled_update.hpp"

#include "pfgen/derivation/gaussian_expectation.hpp"
#include "pfgen/model/model.hpp"

namespace pfgen {

SampledUpdate sampled_update(const SampleTimes& times, const AffineRate& observation, const FilterVariables& vars) {
  const std::size_t n = vars.n(), r = observation.A.size();
  auto P = [&](std::size_t i, std::size_t j) { return Monomial::variable(vars.P(i, j)); };
  SampledUpdate out;
  out.period = times.period;
  out.C.assign(r, std::vector<Polynomial>(n));
  for (std::size_t a = 0; a < r; ++a)
    for (std::size_t k = 0; k < n; ++k) out.C[a][k] = Polynomial::constant(observation.A[a][k]);
  const ExMatrix R = multiply_by_transpose(observation.B);
  for (std::size_t a = 0; a < r; ++a)
    for (std::size_t b = a; b < r; ++b) out.R.push_back(Polynomial::constant(R[a][b]));
  // (P C^T)_ia = sum_k P_ik C_ak
  out.PCt.assign(n, std::vector<Polynomial>(r));
  for (std::size_t i = 0; i < n; ++i)
    for (std::size_t a = 0; a < r; ++a)
      for (std::size_t k = 0; k < n; ++k)
        if (!observation.A[a][k].is_zero()) out.PCt[i][a].add_term(P(i, k), observation.A[a][k]);
  // S_ab = sum_kl C_ak P_kl C_bl + R_ab
  for (std::size_t a = 0; a < r; ++a)
    for (std::size_t b = a; b < r; ++b) {
      Polynomial s = Polynomial::constant(R[a][b]);
      for (std::size_t k = 0; k < n; ++k)
        for (std::size_t l = 0; l < n; ++l)
          if (!observation.A[a][k].is_zero() && !observation.A[b][l].is_zero())
            s.add_term(P(k, l), observation.A[a][k] * observation.A[b][l]);
      out.S.push_back(std::move(s));
    }
  return out;
}

std::vector<Polynomial> predicted_sample(const AffineRate& observation, const FilterVariables& vars) {
  std::vector<Polynomial> out;
  for (std::size_t a = 0; a < observation.A.size(); ++a) {
    Polynomial h = Polynomial::constant(observation.A0[a]);
    for (std::size_t k = 0; k < vars.n(); ++k) h.add_term(Monomial::variable(vars.m(k)), observation.A[a][k]);
    out.push_back(h);
  }
  return out;
}

}  // namespace pfgen

namespace pfgen {

SampledUpdate polynomial_sampled_update(const Model& model, const FilterVariables& vars, bool at_mean,
                                        std::vector<Polynomial>& predicted) {
  const ObservationRate& rate = model.observation.rate();
  const std::size_t n = vars.n(), r = rate.p();
  const std::vector<Polynomial> c = rate.polynomials(model.states);
  // State x_i and mean m_i share variable index i (FilterVariables): c read as it is is c(m).
  GaussianExpectation E(vars);
  auto expectation = [&](const Polynomial& q) { return at_mean ? q : E.of(q); };
  auto P = [&](std::size_t i, std::size_t j) { return Monomial::variable(vars.P(i, j)); };

  SampledUpdate out;
  out.period = model.observation.samples()->period;
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
  const ExMatrix R = multiply_by_transpose(rate.noise());
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
