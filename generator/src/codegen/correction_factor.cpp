#include "pfgen/codegen/correction_factor.hpp"

namespace pfgen::codegen {
namespace {

// A (p × n) of a predicted observation A0 + A m, or nothing when an entry is not affine in m.
std::optional<std::vector<std::vector<GiNaC::ex>>> observation_matrix(const FilterEquations& eq) {
  const FilterVariables& vars = eq.variables;
  std::vector<std::vector<GiNaC::ex>> A(eq.p, std::vector<GiNaC::ex>(eq.n(), 0));
  if (eq.predicted_observation.size() != eq.p) return std::nullopt;
  for (std::size_t r = 0; r < eq.p; ++r)
    for (const auto& [monomial, coefficient] : eq.predicted_observation[r].terms()) {
      if (monomial.is_one()) continue;  // A0
      const auto& factors = monomial.factors();
      if (factors.size() != 1 || factors[0].second != 1 || !vars.is_mean(factors[0].first)) return std::nullopt;
      A[r][factors[0].first] = coefficient;
    }
  return A;
}

}  // namespace

std::optional<std::vector<std::vector<Polynomial>>> correction_factor(const FilterEquations& eq) {
  const std::size_t n = eq.n();
  // The checks below admit only a correction built from a predicted observation A0 + A m and a gain
  // of that A: a sampled filter has no gain (its update is apart), a delayed one predicts from
  // md = m(t - h), not m, so neither passes them, whatever its observation module.
  if (eq.is_user_filter() || eq.p == 0) return std::nullopt;
  if (eq.gain.size() != n || eq.P_correction.size() != n * (n + 1) / 2) return std::nullopt;
  const auto A = observation_matrix(eq);
  if (!A) return std::nullopt;
  const FilterVariables& vars = eq.variables;
  std::vector<std::vector<Polynomial>> H(eq.p, std::vector<Polynomial>(n));
  for (std::size_t r = 0; r < eq.p; ++r)
    for (std::size_t j = 0; j < n; ++j)
      for (std::size_t k = 0; k < n; ++k)
        if (!(*A)[r][k].is_zero()) H[r][j] += Polynomial::variable(vars.P(k, j)).scaled((*A)[r][k]);
  for (std::size_t i = 0; i < n; ++i) {
    if (eq.gain[i].size() != eq.p) return std::nullopt;
    for (std::size_t j = i; j < n; ++j) {
      Polynomial product;
      for (std::size_t r = 0; r < eq.p; ++r)
        if (!eq.gain[i][r].is_zero() && !H[r][j].is_zero()) product += eq.gain[i][r] * H[r][j];
      if (product != eq.P_correction[vars.upper_index(i, j)]) return std::nullopt;
    }
  }
  return H;
}

}  // namespace pfgen::codegen
