#include "pfgen/derivation/drift_coefficients.hpp"

#include <algorithm>
#include <string>

#include "pfgen/algebra/coefficient.hpp"
#include "pfgen/algebra/polynomial.hpp"
#include "pfgen/derivation/observation_derivation.hpp"
#include "pfgen/model/model_error.hpp"

namespace pfgen {
namespace {

// The monomial's variables as a sorted multiset of indices: x1 x2^2 -> (0, 1, 1).
std::vector<std::uint32_t> index_multiset(const Monomial& monomial) {
  std::vector<std::uint32_t> out;
  for (const auto& [index, exponent] : monomial.factors()) out.insert(out.end(), exponent, index);
  return out;
}

// A monomial c x_j x_k (x_l) of degree d is spread evenly over the distinct orders of its index
// multiset: with the symmetric convention sum_jk A2_ijk x_j x_k, each of the q orders holds c / q,
// which is 1/d! times the d-th derivative (c x1 x2: d2/dx1dx2 = c, A2_i12 = A2_i21 = c/2).
void add_symmetric(TensorEntries& tensor, std::uint32_t row, const Monomial& monomial, const GiNaC::ex& c) {
  std::vector<std::uint32_t> order = index_multiset(monomial);  // sorted: the first permutation
  std::vector<std::vector<std::uint32_t>> orders;
  do {
    orders.push_back(order);
  } while (std::next_permutation(order.begin(), order.end()));
  const GiNaC::ex share = coefficient_product(c, GiNaC::numeric(1, static_cast<long>(orders.size())));
  for (auto& lower : orders) {
    std::vector<std::uint32_t> index{row};
    index.insert(index.end(), lower.begin(), lower.end());
    tensor.emplace(std::move(index), share);
  }
}

GiNaC::ex entry_or_zero(const TensorEntries& tensor, const std::vector<std::uint32_t>& index) {
  auto it = tensor.find(index);
  return it == tensor.end() ? GiNaC::ex(0) : it->second;
}

}  // namespace

GiNaC::ex DriftCoefficients::A2_at(std::uint32_t i, std::uint32_t j, std::uint32_t k) const {
  return entry_or_zero(A2, {i, j, k});
}

GiNaC::ex DriftCoefficients::A3_at(std::uint32_t i, std::uint32_t j, std::uint32_t k, std::uint32_t l) const {
  return entry_or_zero(A3, {i, j, k, l});
}

void check_coefficient_form_degree(const Model& model) {
  for (std::size_t i = 0; i < model.n(); ++i) {
    const std::uint32_t degree = Polynomial::from_ex(model.drift[i], model.states).degree();
    if (degree <= kCoefficientFormDegree) continue;
    const std::string row = std::to_string(i + 1);
    // With Stratonovich noise the degree may be the correction's, not the written drift's.
    std::string source;
    if (model.noise == NoiseCalculus::Stratonovich && i < model.stated_drift.size()) {
      const std::uint32_t written = Polynomial::from_ex(model.stated_drift[i], model.states).degree();
      if (written < degree)
        source = " once the Stratonovich correction 1/2 g dg/dx is added (as written: degree " +
                 std::to_string(written) + ")";
    }
    ModelError error("drift",
                     "drift[" + row + "] has degree " + std::to_string(degree) + source +
                         "; the coefficient form A..A3 holds degree <= " + std::to_string(kCoefficientFormDegree),
                     static_cast<int>(i + 1));
    error.set_file(model.source);
    throw error;
  }
}

DriftCoefficients extract_drift_coefficients(const Model& model) {
  check_coefficient_form_degree(model);
  const std::size_t n = model.n();
  DriftCoefficients out;
  out.n = n;
  out.A.assign(n, 0);
  out.A1.assign(n, ExVector(n, 0));
  for (std::size_t i = 0; i < n; ++i) {
    const auto row = static_cast<std::uint32_t>(i);
    const Polynomial f = Polynomial::from_ex(model.drift[i], model.states);  // named: terms() refers into it
    for (const auto& [monomial, c] : f.terms()) {
      switch (monomial.degree()) {
        case 0: out.A[i] = c; break;
        case 1: out.A1[i][monomial.factors().front().first] = c; break;
        case 2: add_symmetric(out.A2, row, monomial, c); break;
        default: add_symmetric(out.A3, row, monomial, c); break;  // 3, by the check above
      }
    }
  }
  return out;
}

ObservationCoefficients extract_observation_coefficients(const Model& model) {
  ObservationCoefficients out = observation_derivation(model.observation).coefficients(model);
  out.kind = model.observation.kind();
  return out;
}

}  // namespace pfgen
