#include "pfgen/codegen/correction_factor.hpp"

namespace pfgen::codegen {

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

std::optional<std::vector<std::vector<GiNaC::ex>>> gain_factor(const FilterEquations& eq) {
  const std::size_t n = eq.n();
  const FilterVariables& vars = eq.variables;
  if (eq.is_user_filter() || eq.p == 0 || eq.gain.size() != n || n == 0) return std::nullopt;
  for (const auto& row : eq.gain)
    if (row.size() != eq.p) return std::nullopt;
  // G^T read off row 0 (gain_0r = sum_k G_kr P_0k), then checked against every row.
  std::vector<std::vector<GiNaC::ex>> Gt(eq.p, std::vector<GiNaC::ex>(n, 0));
  for (std::size_t r = 0; r < eq.p; ++r) {
    for (const auto& [monomial, coefficient] : eq.gain[0][r].terms()) {
      const auto& factors = monomial.factors();
      if (factors.size() != 1 || factors[0].second != 1 || vars.is_mean(factors[0].first) ||
          factors[0].first >= vars.count())
        return std::nullopt;
      const auto [row, column] = vars.P_entry(factors[0].first);
      if (row != 0) return std::nullopt;
      Gt[r][column] = coefficient;
    }
  }
  for (std::size_t i = 0; i < n; ++i) {
    for (std::size_t r = 0; r < eq.p; ++r) {
      Polynomial product;
      for (std::size_t k = 0; k < n; ++k)
        if (!Gt[r][k].is_zero()) product += Polynomial::variable(vars.P(i, k)).scaled(Gt[r][k]);
      if (product != eq.gain[i][r]) return std::nullopt;
    }
  }
  return Gt;
}

std::optional<std::vector<std::vector<GiNaC::ex>>> gain_weight(const std::vector<std::vector<GiNaC::ex>>& Gt,
                                                               const std::vector<std::vector<GiNaC::ex>>& A) {
  const std::size_t p = A.size();
  if (p == 0 || Gt.size() != p) return std::nullopt;
  const std::size_t n = A[0].size();
  // p columns of A that are independent, taken greedily in column order.
  std::vector<std::size_t> columns;
  for (std::size_t j = 0; j < n && columns.size() < p; ++j) {
    GiNaC::matrix block(static_cast<unsigned>(p), static_cast<unsigned>(columns.size() + 1));
    for (std::size_t r = 0; r < p; ++r) {
      for (std::size_t c = 0; c < columns.size(); ++c) block(r, c) = A[r][columns[c]];
      block(r, columns.size()) = A[r][j];
    }
    if (block.rank() == columns.size() + 1) columns.push_back(j);
  }
  if (columns.size() != p) return std::nullopt;
  GiNaC::matrix A_S(static_cast<unsigned>(p), static_cast<unsigned>(p)), Gt_S(static_cast<unsigned>(p), static_cast<unsigned>(p));
  for (std::size_t r = 0; r < p; ++r)
    for (std::size_t c = 0; c < p; ++c) {
      A_S(r, c) = A[r][columns[c]];
      Gt_S(r, c) = Gt[r][columns[c]];
    }
  const GiNaC::matrix M = Gt_S.mul(A_S.inverse());
  std::vector<std::vector<GiNaC::ex>> weight(p, std::vector<GiNaC::ex>(p));
  for (std::size_t r = 0; r < p; ++r)
    for (std::size_t s = 0; s < p; ++s) weight[r][s] = M(r, s).normal();
  // Used only where M A is G^T exactly, every column.
  for (std::size_t r = 0; r < p; ++r)
    for (std::size_t j = 0; j < n; ++j) {
      GiNaC::ex product = 0;
      for (std::size_t s = 0; s < p; ++s) product += weight[r][s] * A[s][j];
      if (!(product - Gt[r][j]).normal().is_zero()) return std::nullopt;
    }
  return weight;
}

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
