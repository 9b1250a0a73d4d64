#include "pfgen/derivation/moment_closure.hpp"

#include <algorithm>

#include "pfgen/derivation/closed_expectation.hpp"

namespace pfgen {
namespace {

using Exponents = std::vector<std::uint32_t>;
using Row = std::vector<Polynomial>;  // 1 x p

Exponents exponents_of(const std::vector<std::size_t>& indices, std::size_t n) {
  Exponents a(n, 0);
  for (std::size_t i : indices) ++a[i];
  return a;
}

Exponents minus(Exponents a, std::size_t i) {
  --a[i];
  return a;
}

// The closure's quantities, each taken once: the shifted f, G and h, and C_b.
class ClosureTerms {
 public:
  ClosureTerms(const Model& model, const FilterVariables& vars, const std::vector<Polynomial>& h, const ExMatrix& B)
      : E_(vars), n_(vars.n()) {
    for (const auto& fi : model.drift) f_.push_back(E_.shifted(Polynomial::from_ex(fi, model.states)));
    G_.assign(n_, std::vector<Polynomial>(n_));
    for (std::size_t i = 0; i < n_; ++i)
      for (std::size_t j = 0; j < n_; ++j) G_[i][j] = E_.shifted(Polynomial::from_ex(model.diffusion.G[i][j], model.states));
    for (const auto& hr : h) h_.push_back(E_.shifted(hr));
    if (!h.empty()) R_inverse_ = inverse_noise_covariance(B);
    for (const auto& fi : f_) Ef_.push_back(E_.of(fi));
    for (const auto& hr : h_) Eh_.push_back(E_.of(hr));
  }

  const std::vector<Polynomial>& Ef() const { return Ef_; }
  const std::vector<Polynomial>& Eh() const { return Eh_; }
  bool observed() const { return !h_.empty(); }

  // E[e^b q], q shifted.
  Polynomial expectation(const Exponents& b, const Polynomial& q) { return E_.of(q.times_monomial(E_.deviations(b))); }
  const Polynomial& mu(const Exponents& b) { return E_.central(b); }

  // C_b = E[e^b h] - mu_b E[h].
  const Row& C(const Exponents& b) {
    if (auto it = C_.find(b); it != C_.end()) return it->second;
    Row row;
    const Polynomial mu_b = mu(b);
    for (std::size_t r = 0; r < h_.size(); ++r) row.push_back(expectation(b, h_[r]) - mu_b * Eh_[r]);
    return C_.emplace(b, std::move(row)).first->second;
  }
  const Row& C(std::size_t i) { return C(exponents_of({i}, n_)); }

  Row times_R_inverse(const Row& row) const {
    Row out(row.size());
    for (std::size_t s = 0; s < row.size(); ++s)
      for (std::size_t r = 0; r < row.size(); ++r)
        if (!R_inverse_[r][s].is_zero() && !row[r].is_zero()) out[s] += row[r].scaled(R_inverse_[r][s]);
    return out;
  }
  static Polynomial dot(const Row& a, const Row& b) {
    Polynomial out;
    for (std::size_t r = 0; r < a.size(); ++r)
      if (!a[r].is_zero() && !b[r].is_zero()) out += a[r] * b[r];
    return out;
  }
  // K_i = C_(e_i) R^-1.
  const Row& K(std::size_t i) {
    if (K_.empty())
      for (std::size_t k = 0; k < n_; ++k) K_.push_back(times_R_inverse(C(k)));
    return K_[i];
  }

  // The three parts of dmu_a's dt coefficient (the f terms, the G terms, the observation's, subtracted) and its
  // dnu coefficient.
  struct Parts {
    Polynomial moment, diffusion, correction;
    Row gain;
  };
  Parts moment_parts(const Exponents& a) {
    Parts out;
    for (std::size_t i = 0; i < n_; ++i) {
      if (!a[i]) continue;
      const GiNaC::numeric ai(a[i]);
      const Exponents a_i = minus(a, i);
      out.moment += (expectation(a_i, f_[i]) - mu(a_i) * Ef_[i]).scaled(ai);
      for (std::size_t j = 0; j < n_; ++j) {
        const std::uint32_t aj = a_i[j];  // a_j - [i = j]
        if (!aj) continue;
        const Exponents a_ij = minus(a_i, j);
        const GiNaC::numeric weight = ai * aj / 2;
        if (!G_[i][j].is_zero()) out.diffusion += expectation(a_ij, G_[i][j]).scaled(weight);
        if (observed()) out.correction -= (mu(a_ij) * dot(K(i), C(j))).scaled(weight);
      }
      if (observed()) out.correction += dot(times_R_inverse(C(a_i)), C(i)).scaled(ai);
    }
    if (observed()) {
      Row innovation = C(a);
      for (std::size_t i = 0; i < n_; ++i) {
        if (!a[i]) continue;
        const Polynomial weight = mu(minus(a, i)).scaled(GiNaC::numeric(a[i]));
        if (weight.is_zero()) continue;
        for (std::size_t r = 0; r < innovation.size(); ++r) innovation[r] -= weight * C(i)[r];
      }
      out.gain = times_R_inverse(innovation);
    }
    return out;
  }

 private:
  ClosedExpectation E_;
  std::size_t n_;
  std::vector<Polynomial> f_, h_, Ef_, Eh_;
  std::vector<std::vector<Polynomial>> G_;
  ExMatrix R_inverse_;
  std::map<Exponents, Row> C_;
  std::vector<Row> K_;
};

}  // namespace

MomentClosureTerms moment_closure_terms(const Model& model, const FilterVariables& vars, const std::vector<Polynomial>& h,
                                        const ExMatrix& B) {
  const std::size_t n = vars.n();
  ClosureTerms terms(model, vars, h, B);
  MomentClosureTerms out;
  out.m_drift = terms.Ef();
  if (terms.observed()) {
    out.predicted_observation = terms.Eh();
    for (std::size_t i = 0; i < n; ++i) out.gain.push_back(terms.K(i));
  }
  for (std::size_t i = 0; i < n; ++i)
    for (std::size_t j = i; j < n; ++j) {
      auto parts = terms.moment_parts(exponents_of({i, j}, n));
      out.P_moment.push_back(std::move(parts.moment));
      out.P_diffusion.push_back(std::move(parts.diffusion));
      out.P_correction.push_back(std::move(parts.correction));
      if (terms.observed()) out.P_gain.push_back(std::move(parts.gain));
    }
  for (const auto& indices : vars.higher_moments()) {
    auto parts = terms.moment_parts(exponents_of(indices, n));
    out.higher_drift.push_back(parts.moment + parts.diffusion - parts.correction);
    if (terms.observed()) out.higher_gain.push_back(std::move(parts.gain));
  }
  return out;
}

namespace {

// det of P's leading principal block of size r (Laplace expansion along the first row; r <= 4).
Polynomial leading_minor(const FilterVariables& vars, std::vector<std::size_t> rows, std::vector<std::size_t> columns) {
  if (rows.size() == 1) return Polynomial::variable(vars.P(rows[0], columns[0]));
  Polynomial det;
  const std::vector<std::size_t> rest(rows.begin() + 1, rows.end());
  for (std::size_t k = 0; k < columns.size(); ++k) {
    std::vector<std::size_t> minor_columns = columns;
    minor_columns.erase(minor_columns.begin() + static_cast<std::ptrdiff_t>(k));
    const Polynomial term = Polynomial::variable(vars.P(rows[0], columns[k])) * leading_minor(vars, rest, minor_columns);
    det += k % 2 ? term.scaled(-1) : term;
  }
  return det;
}

}  // namespace

RealisabilityMargins realisability_margins(const FilterVariables& vars, const std::vector<std::string>& state_names) {
  RealisabilityMargins out;
  ClosedExpectation E(vars);
  for (std::size_t i = 0; i < vars.n(); ++i) {
    out.margins.push_back(Polynomial::variable(vars.P(i, i)));
    out.meaning.push_back("variance of " + state_names.at(i));
  }
  // P positive definite (Sylvester): its leading principal minors, up to size 4; larger P are the runtime's PSD
  // check, which stops a moment filter as well.
  for (std::size_t r = 2; r <= std::min<std::size_t>(vars.n(), 4); ++r) {
    std::vector<std::size_t> first(r);
    for (std::size_t k = 0; k < r; ++k) first[k] = k;
    out.margins.push_back(leading_minor(vars, first, first));
    out.meaning.push_back("P's leading " + std::to_string(r) + " x " + std::to_string(r) + " minor");
  }
  // Pearson's bound of each state, mu4 P - P^3 - mu3^2 >= 0, with mu4 the closed law's (3 P^2 at order 3, where the
  // bound reads M3^2 <= 2 P^3).
  for (std::size_t i = 0; i < vars.n(); ++i) {
    std::vector<std::uint32_t> g(vars.n(), 0);
    g[i] = 3;
    const Polynomial mu3 = E.central(g);
    g[i] = 4;
    const Polynomial mu4 = E.central(g);
    const Polynomial P = Polynomial::variable(vars.P(i, i));
    out.margins.push_back(mu4 * P - P * P * P - mu3 * mu3);
    out.meaning.push_back("Pearson's bound of " + state_names.at(i));
  }
  return out;
}

}  // namespace pfgen
