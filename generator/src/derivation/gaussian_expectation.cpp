#include "pfgen/derivation/gaussian_expectation.hpp"

#include "pfgen/algebra/coefficient.hpp"

namespace pfgen {

Polynomial GaussianExpectation::of(const Polynomial& p) {
  // The products in the order add_term would add them, summed by one sort (Polynomial::sum_of).
  std::vector<std::pair<Monomial, GiNaC::ex>> products;
  for (const auto& [monomial, coefficient] : p.terms()) {
    const Polynomial& moment = of_monomial(monomial);
    for (const auto& [m, c] : moment.terms()) products.emplace_back(m, coefficient_product(c, coefficient));
  }
  return Polynomial::sum_of(std::move(products));
}

const Polynomial& GaussianExpectation::of_monomial(const Monomial& monomial) {
  if (auto it = memo_.find(monomial); it != memo_.end()) return it->second;
  Polynomial value;
  if (monomial.is_one()) {
    value = Polynomial::constant(1);
  } else {
    const std::uint32_t i = monomial.factors().front().first;
    const Polynomial& rest = of_monomial(peeled(monomial));  // std::map references stay valid
    value = rest.times_monomial(Monomial::variable(variables_.m(i)));
    for (std::size_t j = 0; j < variables_.n(); ++j) {
      Polynomial d = rest.derivative(variables_.m(j));
      if (!d.is_zero()) value += d.times_monomial(Monomial::variable(variables_.P(i, j)));
    }
  }
  return memo_.emplace(monomial, std::move(value)).first->second;
}

}  // namespace pfgen
