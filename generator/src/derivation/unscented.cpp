#include "pfgen/derivation/unscented.hpp"

#include <set>
#include <string>

#include "pfgen_support/variable_names.hpp"

namespace pfgen {
namespace {

// The prefix of L's names: "L", or "L_", "L__", ... while one of L's names is a name of the model
// (its states, parameters and time are the other symbols its equations can hold).
std::string cholesky_prefix(const Model& model) {
  std::set<std::string> taken(model.state_names.begin(), model.state_names.end());
  for (const auto& p : model.parameters) taken.insert(p.name);
  taken.insert(model.time.get_name());
  const std::size_t n = model.n();
  for (std::string prefix = "L";; prefix += "_") {
    bool clear = true;
    for (std::size_t i = 0; i < n && clear; ++i)
      for (std::size_t j = 0; j <= i && clear; ++j)
        clear = !taken.count(prefix + pfgen_support::covariance_name(i, j, n).substr(1));
    if (clear) return prefix;
  }
}

// The expansion of h(m + s L_j) in powers of s = sqrt(c), the states read as the means (state x_i
// and m_i share variable index i): coefficient k is the s^k term.
std::vector<GiNaC::ex> directional_expansion(const GiNaC::ex& h, const Model& model,
                                             const std::vector<std::vector<GiNaC::ex>>& L, std::size_t j,
                                             const GiNaC::symbol& s) {
  GiNaC::exmap shift;
  for (std::size_t i = j; i < model.n(); ++i) shift[model.states[i]] = model.states[i] + s * L[i][j];
  const GiNaC::ex e = h.subs(shift).expand();
  std::vector<GiNaC::ex> coefficients;
  for (int k = 0; k <= e.degree(s); ++k) coefficients.push_back(e.coeff(s, k));
  return coefficients;
}

// h(m + s L_j) + h(m - s L_j), with s^2 = c: twice the even terms.
GiNaC::ex symmetric_sum(const std::vector<GiNaC::ex>& a, const GiNaC::numeric& c) {
  GiNaC::ex sum = 0;
  for (std::size_t k = 0; k < a.size(); k += 2) sum += 2 * GiNaC::pow(c, static_cast<int>(k / 2)) * a[k];
  return sum;
}

// s (h(m + s L_j) - h(m - s L_j)), with s^2 = c: twice the odd terms, times s.
GiNaC::ex antisymmetric_sum(const std::vector<GiNaC::ex>& a, const GiNaC::numeric& c) {
  GiNaC::ex sum = 0;
  for (std::size_t k = 1; k < a.size(); k += 2) sum += 2 * GiNaC::pow(c, static_cast<int>((k + 1) / 2)) * a[k];
  return sum;
}

}  // namespace

SigmaPointWeights sigma_point_weights(std::size_t n) {
  const GiNaC::numeric dimension(static_cast<long>(n));
  // kappa = 3 - n keeps c = 3 for n <= 3: along each sigma axis the points then match the standard
  // Gaussian's moments to order 5 (E[u^4] = 3 = c); mixed moments only to order 3, for any c. Above
  // n = 3 that kappa would make w_0 negative, so kappa = 0 there.
  const GiNaC::numeric kappa = n <= 3 ? GiNaC::numeric(3) - dimension : GiNaC::numeric(0);
  const GiNaC::numeric c = dimension + kappa;
  return SigmaPointWeights{c, kappa / c, GiNaC::numeric(1) / (2 * c)};
}

UnscentedTerms unscented_terms(const Model& model, const FilterVariables& vars) {
  const std::size_t n = model.n();
  const SigmaPointWeights weights = sigma_point_weights(n);
  UnscentedTerms out;

  // L's symbols and their definitions, column by column, so each reads only entries before it.
  const std::string prefix = cholesky_prefix(model);
  std::vector<std::vector<GiNaC::ex>> L(n, std::vector<GiNaC::ex>(n, 0));
  for (std::size_t j = 0; j < n; ++j)
    for (std::size_t i = j; i < n; ++i) L[i][j] = GiNaC::symbol(prefix + pfgen_support::covariance_name(i, j, n).substr(1));
  auto P = [&](std::size_t i, std::size_t j) { return vars.symbols().at(vars.P(i, j)); };
  for (std::size_t j = 0; j < n; ++j) {
    GiNaC::ex diagonal = P(j, j);
    for (std::size_t k = 0; k < j; ++k) diagonal -= GiNaC::pow(L[j][k], 2);
    // sqrt(max(0, d)), written (d + |d|) / 2: a positive semidefinite P whose pivot is 0 (paper 001's
    // singular P0, kept singular by a noise-free state) is computed a rounding error below 0, and its
    // factor's entry is 0, not the square root of a negative number. A P that is really indefinite is
    // the filter's failure, which the runtime's guards report from P itself.
    out.cholesky.push_back(FilterDefinition{GiNaC::ex_to<GiNaC::symbol>(L[j][j]), GiNaC::sqrt((diagonal + GiNaC::abs(diagonal)) / 2)});
    for (std::size_t i = j + 1; i < n; ++i) {
      GiNaC::ex entry = P(i, j);
      for (std::size_t k = 0; k < j; ++k) entry -= L[i][k] * L[j][k];
      // Below a zero pivot the column is 0: P positive semi-definite with a zero pivot has entry 0
      // there too, and 0/0 would stop the filter at a prior such as P0 = diag(0, 5).
      out.cholesky.push_back(FilterDefinition{GiNaC::ex_to<GiNaC::symbol>(L[i][j]), entry / L[j][j], L[j][j]});
    }
  }

  // sum_i w_i h(X_i) = w_0 h(m) + w sum_j [h(m + s L_j) + h(m - s L_j)], h(X_0) = h(m) because the
  // states are read as the means.
  const GiNaC::symbol s("sqrt_c");
  auto weighted_sum = [&](const GiNaC::ex& h, const std::vector<std::vector<GiNaC::ex>>& along) {
    GiNaC::ex sum = weights.w0 * h;
    for (std::size_t j = 0; j < n; ++j) sum += weights.w * symmetric_sum(along[j], weights.c);
    return Polynomial::from_ex(sum, model.states);
  };
  auto expansions = [&](const GiNaC::ex& h) {
    std::vector<std::vector<GiNaC::ex>> along;
    for (std::size_t j = 0; j < n; ++j) along.push_back(directional_expansion(h, model, L, j, s));
    return along;
  };
  std::vector<std::vector<std::vector<GiNaC::ex>>> drift_along;  // [b][j]: f_b along L_j
  for (const auto& fb : model.drift) drift_along.push_back(expansions(fb));
  for (std::size_t b = 0; b < n; ++b) out.m_drift.push_back(weighted_sum(model.drift[b], drift_along[b]));
  for (std::size_t a = 0; a < n; ++a)
    for (std::size_t b = a; b < n; ++b) {
      const GiNaC::ex& G = model.diffusion.G[a][b];
      out.P_diffusion.push_back(weighted_sum(G, expansions(G)));
    }

  // sum_i w_i (X_i - m) f(X_i)^T: the centre point adds nothing (X_0 - m = 0); X_j - m = +-s L_j, so
  // entry (a, b) is w sum_j L_aj s [f_b(m + s L_j) - f_b(m - s L_j)].
  std::vector<std::vector<GiNaC::ex>> cross(n, std::vector<GiNaC::ex>(n, 0));  // [a][b]
  for (std::size_t j = 0; j < n; ++j)
    for (std::size_t b = 0; b < n; ++b) {
      const GiNaC::ex odd = weights.w * antisymmetric_sum(drift_along[b][j], weights.c);
      for (std::size_t a = j; a < n; ++a) cross[a][b] += L[a][j] * odd;
    }
  for (std::size_t a = 0; a < n; ++a)
    for (std::size_t b = a; b < n; ++b) out.P_moment.push_back(Polynomial::from_ex(cross[a][b] + cross[b][a], model.states));
  return out;
}

SigmaPointMoments sigma_point_moments(const GiNaC::ex& h, const Model& model,
                                      const std::vector<FilterDefinition>& cholesky) {
  const std::size_t n = model.n();
  const SigmaPointWeights weights = sigma_point_weights(n);
  // L from its entries, column by column as unscented_terms defines them.
  std::vector<std::vector<GiNaC::ex>> L(n, std::vector<GiNaC::ex>(n, 0));
  std::size_t next = 0;
  for (std::size_t j = 0; j < n; ++j)
    for (std::size_t i = j; i < n; ++i) L[i][j] = cholesky.at(next++).name;
  const GiNaC::symbol s("sqrt_c");
  SigmaPointMoments out;
  GiNaC::ex mean = weights.w0 * h;
  std::vector<GiNaC::ex> cross(n, 0);
  for (std::size_t j = 0; j < n; ++j) {
    const std::vector<GiNaC::ex> along = directional_expansion(h, model, L, j, s);
    mean += weights.w * symmetric_sum(along, weights.c);
    const GiNaC::ex odd = weights.w * antisymmetric_sum(along, weights.c);
    for (std::size_t a = j; a < n; ++a) cross[a] += L[a][j] * odd;
  }
  out.mean = Polynomial::from_ex(mean, model.states);
  for (const GiNaC::ex& c : cross) out.cross.push_back(Polynomial::from_ex(c, model.states));
  return out;
}

}  // namespace pfgen
