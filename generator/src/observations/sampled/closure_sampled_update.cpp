#include "pfgen/observations/sampled/closure_sampled_update.hpp"

#include <map>

#include "pfgen/derivation/closed_expectation.hpp"
#include "pfgen/derivation/derivation_budget.hpp"

namespace pfgen {

std::vector<std::vector<std::size_t>> joint_moment_indices(std::size_t n, std::size_t r, std::size_t order) {
  std::vector<std::vector<std::size_t>> out;
  for (std::size_t k = 2; k <= order; ++k)
    for (auto& t : ascending_indices(n + r, k))
      if (t.back() >= n) out.push_back(std::move(t));
  return out;
}

SampledUpdate closure_sampled_update(const Model& model, const FilterVariables& vars, const std::string& kind,
                                     std::vector<Polynomial>& predicted) {
  const ObservationRate& rate = model.observation.rate();
  const std::size_t n = vars.n(), r = rate.p();
  const std::vector<Polynomial> c = rate.polynomials(model.states);
  const std::vector<std::vector<std::size_t>> joint = joint_moment_indices(n, r, vars.order());
  check_closure_samples_budget(model, static_cast<unsigned>(vars.order()), kind, c, joint);
  ClosedExpectation E(vars);
  SampledUpdate out;
  out.period = model.observation.samples()->period;
  out.polynomial_samples = true;
  out.closed_law = true;
  // z = (e, d): e_i the deviations, d_a = c_a(m + e) - E[c_a] - sum_k C_ak e_k, over m, P, ... and e.
  std::vector<Polynomial> z;
  for (std::size_t i = 0; i < n; ++i) z.push_back(Polynomial::variable(E.deviation(i)));
  predicted.clear();
  out.C.assign(r, std::vector<Polynomial>(n));
  std::vector<Polynomial> centred;  // c_a(m + e) - E[c_a]
  for (std::size_t a = 0; a < r; ++a) {
    const Polynomial shifted = E.shifted(c[a]);
    predicted.push_back(E.of(shifted));
    centred.push_back(shifted - predicted.back());
    Polynomial d = centred.back();
    for (std::size_t k = 0; k < n; ++k) {
      out.C[a][k] = E.of_state_polynomial(c[a].derivative(static_cast<std::uint32_t>(k)));
      d -= out.C[a][k] * z[k];
    }
    z.push_back(std::move(d));
  }
  // Cov(x, c) and Cov(c) + R, the gain's parts.
  out.PCt.assign(n, std::vector<Polynomial>(r));
  for (std::size_t i = 0; i < n; ++i)
    for (std::size_t a = 0; a < r; ++a) out.PCt[i][a] = E.of(z[i] * centred[a]);
  const ExMatrix R = multiply_by_transpose(rate.noise());
  for (std::size_t a = 0; a < r; ++a)
    for (std::size_t b = a; b < r; ++b) {
      const Polynomial noise = Polynomial::constant(R[a][b]);
      out.S.push_back(E.of(centred[a] * centred[b]) + noise);
      out.R.push_back(noise);
    }
  // The joint moments, each product built from its prefix's.
  std::map<std::vector<std::size_t>, Polynomial> products;
  auto product = [&](const std::vector<std::size_t>& t, auto& self) -> const Polynomial& {
    auto it = products.find(t);
    if (it != products.end()) return it->second;
    Polynomial value = z[t.back()];
    if (t.size() > 1) value = self(std::vector<std::size_t>(t.begin(), t.end() - 1), self) * z[t.back()];
    return products.emplace(t, std::move(value)).first->second;
  };
  out.joint_indices = joint;
  for (const auto& t : out.joint_indices) out.joint.push_back(E.of(product(t, product)));
  return out;
}

}  // namespace pfgen
