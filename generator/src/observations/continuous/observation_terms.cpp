#include "pfgen/observations/continuous/observation_terms.hpp"

namespace pfgen {

std::vector<Polynomial> predicted_observation(const ContinuousObservation& observation, const FilterVariables& vars,
                                              bool delayed) {
  std::vector<Polynomial> out;
  for (std::size_t r = 0; r < observation.A.size(); ++r) {
    Polynomial h = Polynomial::constant(observation.A0[r]);
    for (std::size_t k = 0; k < vars.n(); ++k)
      h.add_term(Monomial::variable(delayed ? vars.m_delayed(k) : vars.m(k)), observation.A[r][k]);
    out.push_back(h);
  }
  return out;
}

ObservationCorrection observation_correction(const ContinuousObservation& observation, const FilterVariables& vars,
                                             bool transition) {
  const std::size_t n = vars.n(), p = observation.A.size();
  // P_ik, times phi_k for the Phi* gain: (P Phi)_ik, and (Phi P)_lj = phi_l P_lj = (P Phi)_jl by
  // symmetry, so the correction's term k, l is P(i, k) * P(j, l) (P(l, j) would be P_lj phi_j).
  auto P = [&](std::size_t i, std::size_t k) {
    Monomial entry = Monomial::variable(vars.P(i, k));
    return transition ? entry * Monomial::variable(vars.phi(k)) : entry;
  };
  ObservationTerms obs = observation_terms(observation);
  ObservationCorrection out;
  out.gain.assign(n, std::vector<Polynomial>(p));
  for (std::size_t i = 0; i < n; ++i)
    for (std::size_t r = 0; r < p; ++r)
      for (std::size_t k = 0; k < n; ++k) out.gain[i][r].add_term(P(i, k), obs.At_Rinv[k][r]);
  for (std::size_t i = 0; i < n; ++i)
    for (std::size_t j = i; j < n; ++j) {
      Polynomial correction;
      for (std::size_t k = 0; k < n; ++k)
        for (std::size_t l = 0; l < n; ++l)
          if (!obs.At_Rinv_A[k][l].is_zero()) correction.add_term(P(i, k) * P(j, l), obs.At_Rinv_A[k][l]);
      out.P_correction.push_back(std::move(correction));
    }
  return out;
}

}  // namespace pfgen
