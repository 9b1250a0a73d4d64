#include "pfgen/observations/polynomial/polynomial_observation_terms.hpp"

#include "pfgen/algebra/coefficient.hpp"
#include "pfgen/derivation/gaussian_expectation.hpp"
#include "pfgen/model/model.hpp"

namespace pfgen {
namespace {

// sum_k P_ik M_kj for M a matrix of polynomials (M_kj = 0 skipped).
Polynomial P_times(const FilterVariables& vars, const std::vector<std::vector<Polynomial>>& M, std::size_t i,
                   std::size_t j) {
  Polynomial out;
  for (std::size_t k = 0; k < vars.n(); ++k)
    if (!M[k][j].is_zero()) out += M[k][j].times_monomial(Monomial::variable(vars.P(i, k)));
  return out;
}

// The gain C R^-1 and the correction C R^-1 C^T of a cross covariance C = Cov(x, h) (n x p),
// however its moments were computed; P_gain all zero.
PolynomialObservationTerms terms_from_cross(std::vector<Polynomial> predicted,
                                            const std::vector<std::vector<Polynomial>>& cross,
                                            const ExMatrix& R_inverse) {
  const std::size_t n = cross.size(), p = predicted.size();
  PolynomialObservationTerms out;
  out.predicted_observation = std::move(predicted);
  out.gain.assign(n, std::vector<Polynomial>(p));
  for (std::size_t i = 0; i < n; ++i)
    for (std::size_t s = 0; s < p; ++s)
      for (std::size_t r = 0; r < p; ++r)
        if (!R_inverse[r][s].is_zero()) out.gain[i][s] += cross[i][r].scaled(R_inverse[r][s]);
  for (std::size_t i = 0; i < n; ++i)
    for (std::size_t j = i; j < n; ++j) {
      Polynomial correction;
      for (std::size_t s = 0; s < p; ++s) correction += out.gain[i][s] * cross[j][s];
      out.P_correction.push_back(std::move(correction));
    }
  out.P_gain.assign(n * (n + 1) / 2, std::vector<Polynomial>(p));
  return out;
}

}  // namespace

PolynomialObservationTerms observation_terms_from_moments(std::vector<Polynomial> predicted,
                                                          const std::vector<std::vector<Polynomial>>& cross,
                                                          const ExMatrix& B) {
  return terms_from_cross(std::move(predicted), cross, inverse_noise_covariance(B));
}

PolynomialObservationTerms polynomial_observation_terms(const std::vector<Polynomial>& h, const ExMatrix& B,
                                                        const FilterVariables& vars, bool at_mean) {
  const std::size_t n = vars.n(), p = h.size();
  const ExMatrix R_inverse = inverse_noise_covariance(B);
  // State x_i and mean m_i share variable index i (FilterVariables): a polynomial in x read as
  // it is is that polynomial at the mean (the extended filter's h(m), J(m)).
  GaussianExpectation E(vars);
  auto expectation = [&](const Polynomial& q) { return at_mean ? q : E.of(q); };

  // EJt[k][r] = E[d h_r / d x_k]: E[J]^T, n x p.
  std::vector<Polynomial> predicted;
  std::vector<std::vector<Polynomial>> EJt(n, std::vector<Polynomial>(p));
  for (std::size_t r = 0; r < p; ++r) {
    predicted.push_back(expectation(h[r]));
    for (std::size_t k = 0; k < n; ++k) EJt[k][r] = expectation(h[r].derivative(static_cast<std::uint32_t>(k)));
  }
  // Cov(x, h) = P E[J]^T (Stein), so the gain is P E[J]^T R^-1 and the correction K E[J] P.
  std::vector<std::vector<Polynomial>> PEJt(n, std::vector<Polynomial>(p));
  for (std::size_t i = 0; i < n; ++i)
    for (std::size_t r = 0; r < p; ++r) PEJt[i][r] = P_times(vars, EJt, i, r);
  PolynomialObservationTerms out = terms_from_cross(std::move(predicted), PEJt, R_inverse);
  // L_ij,r = sum_k (P E[H_k] P)_ij (R^-1)_kr; zero at the mean and for linear h.
  if (at_mean) return out;
  for (std::size_t k = 0; k < p; ++k) {
    if (h[k].degree() < 2) continue;
    std::vector<std::vector<Polynomial>> EH(n, std::vector<Polynomial>(n));  // E[H_k]
    for (std::size_t a = 0; a < n; ++a)
      for (std::size_t b = 0; b < n; ++b)
        EH[a][b] = E.of(h[k].derivative(static_cast<std::uint32_t>(a)).derivative(static_cast<std::uint32_t>(b)));
    std::vector<std::vector<Polynomial>> EH_P(n, std::vector<Polynomial>(n));  // E[H_k] P
    for (std::size_t a = 0; a < n; ++a)
      for (std::size_t j = 0; j < n; ++j)
        for (std::size_t b = 0; b < n; ++b)
          if (!EH[a][b].is_zero()) EH_P[a][j] += EH[a][b].times_monomial(Monomial::variable(vars.P(b, j)));
    std::size_t upper = 0;
    for (std::size_t i = 0; i < n; ++i)
      for (std::size_t j = i; j < n; ++j, ++upper) {
        const Polynomial PHP = P_times(vars, EH_P, i, j);
        if (PHP.is_zero()) continue;
        for (std::size_t r = 0; r < p; ++r)
          if (!R_inverse[k][r].is_zero()) out.P_gain[upper][r] += PHP.scaled(R_inverse[k][r]);
      }
  }
  return out;
}

}  // namespace pfgen
