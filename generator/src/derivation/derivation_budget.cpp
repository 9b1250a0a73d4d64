#include "pfgen/derivation/derivation_budget.hpp"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <set>

#include "pfgen/derivation/gaussian_expectation.hpp"
#include "pfgen/model/model_error.hpp"

namespace pfgen {
namespace {

// Counts the monomials m^beta P^K of E[x^alpha]: symmetric K >= 0 whose row sums, with a
// diagonal entry counted twice, stay within alpha (beta takes the rest). Dynamic programming over
// the pairs (i, j), i <= j, on the vector of factors left, stored densely in mixed radix.
double count_pairings(const std::vector<std::uint32_t>& alpha) {
  const std::size_t s = alpha.size();
  std::vector<std::size_t> stride(s);
  std::size_t states = 1;
  for (std::size_t i = 0; i < s; ++i) {
    stride[i] = states;
    states *= alpha[i] + 1;
  }
  // ways[v]: pairings so far that leave v's factors (v in mixed radix).
  std::vector<double> ways(states, 0.0), next(states);
  ways[states - 1] = 1;  // nothing paired: all of alpha left
  std::vector<std::uint32_t> left(s);
  for (std::size_t i = 0; i < s; ++i)
    for (std::size_t j = i; j < s; ++j) {
      std::fill(next.begin(), next.end(), 0.0);
      for (std::size_t v = 0; v < states; ++v) {
        if (ways[v] == 0) continue;
        const std::uint32_t li = static_cast<std::uint32_t>(v / stride[i] % (alpha[i] + 1));
        const std::uint32_t lj = static_cast<std::uint32_t>(v / stride[j] % (alpha[j] + 1));
        // k copies of P_ij use k factors of each (2k of one state when i == j).
        const std::uint32_t most = i == j ? li / 2 : std::min(li, lj);
        const std::size_t step = i == j ? 2 * stride[i] : stride[i] + stride[j];
        for (std::uint32_t k = 0; k <= most; ++k) next[v - k * step] += ways[v];
      }
      std::swap(ways, next);
    }
  double total = 0;
  for (double w : ways) total += w;
  return total;
}

// Work so far, and the monomials whose expectation the recursion would already hold.
class ExpectationCount {
 public:
  // Terms of E[p], adding those of the recursion's intermediate expectations to the total.
  double add(const Polynomial& p) {
    double terms = 0;
    for (const auto& [monomial, coefficient] : p.terms()) {
      terms += count(monomial);
      // GaussianExpectation reaches each monomial through the same chain of smaller ones.
      for (Monomial m = monomial; !m.is_one(); ) {
        m = GaussianExpectation::peeled(m);
        if (!count(m)) break;  // already held, and so is the rest of its chain
      }
    }
    return terms;
  }
  double total() const { return total_; }

 private:
  // The terms of E[m], when the recursion would compute it now; 0 when it already holds it.
  double count(const Monomial& m) {
    if (!held_.insert(m).second) return 0;
    const double terms = gaussian_moment_terms(m, kMaxExpectationTerms - total_);
    total_ += terms;
    return terms;
  }
  std::set<Monomial> held_;
  double total_ = 0;
};

}  // namespace

double gaussian_moment_terms(const Monomial& alpha, double stop_above) {
  std::vector<std::uint32_t> exponents;
  double box = 1;
  for (const auto& [index, exponent] : alpha.factors()) {
    exponents.push_back(exponent);
    box *= exponent + 1.0;
  }
  // Every r <= alpha with an even number of factors can be paired, and leaves a different m^beta:
  // at least half of the box's points are terms. Beyond the limit, that is answer enough.
  if (std::floor(box / 2) > stop_above) return std::floor(box / 2);
  return count_pairings(exponents);
}

void check_derivation_budget(const Model& model, const DerivationInputs& inputs) {
  const std::size_t n = model.n();
  auto refuse = [&](const std::string& field, std::optional<int> row, std::optional<int> column,
                    const std::string& message) {
    ModelError error(field, message, row, column);
    error.set_file(model.source);
    throw error;
  };
  // Terms of E[J_ik] (or J_ik itself), row sums for the covariance bound below.
  std::vector<double> jacobian_row_terms(n, 0.0);
  if (inputs.gaussian) {
    ExpectationCount E;
    auto check = [&](const std::string& field, std::optional<int> row, std::optional<int> column,
                     const std::string& what) {
      if (E.total() > kMaxExpectationTerms)
        refuse(field, row, column,
               "the Gaussian expectations of " + what + " need more than " + count_text(kMaxExpectationTerms) +
                   " terms in all (the expectation E[x^a] of every monomial on the way is kept); lower the "
                   "degrees or the number of states multiplied together");
    };
    for (std::size_t i = 0; i < n; ++i) {
      E.add(inputs.drift[i]);
      check("drift", static_cast<int>(i + 1), std::nullopt, "the drift up to this row");
    }
    for (std::size_t i = 0; i < n; ++i)
      for (std::size_t k = 0; k < n; ++k) {
        jacobian_row_terms[i] += E.add(inputs.jacobian[i][k]);
        check("drift", static_cast<int>(i + 1), std::nullopt, "the drift and its derivatives up to this row");
      }
    std::size_t u = 0;
    for (std::size_t i = 0; i < n; ++i)
      for (std::size_t j = i; j < n; ++j, ++u) {
        E.add(inputs.diffusion_upper[u]);
        check(inputs.diffusion_field, static_cast<int>(i + 1), static_cast<int>(j + 1),
              "the drift and the diffusion covariance up to this entry");
      }
  } else {
    for (std::size_t i = 0; i < n; ++i)
      for (std::size_t k = 0; k < n; ++k) jacobian_row_terms[i] += inputs.jacobian[i][k].terms().size();
  }
  // Entry (i, j) of the covariance equation: sum_k P_ik E[J_jk] + E[J_ik] P_kj, and the
  // observation term P A^T R^-1 A P with one term per pair of observed states.
  double equations = 0;
  for (std::size_t i = 0; i < n; ++i) equations += jacobian_row_terms[i] * static_cast<double>(n + 1);
  const double observed = static_cast<double>(inputs.observed_states);
  equations += static_cast<double>(n) * static_cast<double>(n + 1) / 2 * observed * observed;
  if (equations > kMaxEquationTerms)
    refuse("states", std::nullopt, std::nullopt,
           "with " + std::to_string(n) + " states (" + std::to_string(inputs.observed_states) +
               " observed), the covariance equations would have up to " + count_text(equations) +
               " terms, above the limit of " + count_text(kMaxEquationTerms));
}

}  // namespace pfgen
