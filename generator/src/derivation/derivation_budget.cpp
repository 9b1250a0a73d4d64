#include "pfgen/derivation/derivation_budget.hpp"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <map>

#include "pfgen/derivation/gaussian_expectation.hpp"
#include "pfgen/model/model_error.hpp"

namespace pfgen {
namespace {

// Counts the monomials m^beta P^K of E[x^alpha]: symmetric K >= 0 whose row sums, with a
// diagonal entry counted twice, stay within alpha (beta takes the rest). The diagonal P_ii are
// free once the cross pairs are chosen: a state with r factors left takes P_ii^0 .. P_ii^(r/2),
// r/2 + 1 ways. So the count is a sum over the cross pairs P_ij, i < j, of the product of those
// ways: in closed form for one or two states (the cost of a monomial of degree 1000 in x and y is
// a loop of at most 500), by dynamic programming over the cross pairs on the vector of factors
// left (dense, mixed radix) for more.
double count_pairings(const std::vector<std::uint32_t>& alpha) {
  const std::size_t s = alpha.size();
  auto diagonal_ways = [](std::uint32_t left) { return static_cast<double>(left / 2 + 1); };
  if (s == 0) return 1;
  if (s == 1) return diagonal_ways(alpha[0]);
  if (s == 2) {
    double total = 0;
    for (std::uint32_t k = 0; k <= std::min(alpha[0], alpha[1]); ++k)
      total += diagonal_ways(alpha[0] - k) * diagonal_ways(alpha[1] - k);
    return total;
  }
  std::vector<std::size_t> stride(s);
  std::size_t states = 1;
  for (std::size_t i = 0; i < s; ++i) {
    stride[i] = states;
    states *= alpha[i] + 1;
  }
  auto left_of = [&](std::size_t v, std::size_t i) { return static_cast<std::uint32_t>(v / stride[i] % (alpha[i] + 1)); };
  // ways[v]: choices of cross pairs so far that leave v's factors (v in mixed radix).
  std::vector<double> ways(states, 0.0), next(states);
  ways[states - 1] = 1;  // nothing paired: all of alpha left
  for (std::size_t i = 0; i < s; ++i)
    for (std::size_t j = i + 1; j < s; ++j) {
      std::fill(next.begin(), next.end(), 0.0);
      const std::size_t step = stride[i] + stride[j];
      for (std::size_t v = 0; v < states; ++v) {
        if (ways[v] == 0) continue;
        // k copies of P_ij use k factors of each.
        const std::uint32_t most = std::min(left_of(v, i), left_of(v, j));
        for (std::uint32_t k = 0; k <= most; ++k) next[v - k * step] += ways[v];
      }
      std::swap(ways, next);
    }
  double total = 0;
  for (std::size_t v = 0; v < states; ++v) {
    if (ways[v] == 0) continue;
    double diagonal = 1;
    for (std::size_t i = 0; i < s; ++i) diagonal *= diagonal_ways(left_of(v, i));
    total += ways[v] * diagonal;
  }
  return total;
}

// Work so far, and the monomials whose expectation the recursion would already hold.
class ExpectationCount {
 public:
  // Terms of E[p] not held before (the drift's bounds were set on this count), adding those of
  // the recursion's intermediate expectations to the total.
  double add(const Polynomial& p) {
    double terms = 0;
    for (const auto& [monomial, coefficient] : p.terms()) {
      if (total_ > kMaxExpectationTerms) break;  // refused anyway: counting on costs time for nothing
      terms += count(monomial);
      // GaussianExpectation reaches each monomial through the same chain of smaller ones.
      for (Monomial m = monomial; !m.is_one(); ) {
        m = GaussianExpectation::peeled(m);
        if (!count(m) || total_ > kMaxExpectationTerms) break;  // already held, and so is the rest of its chain
      }
    }
    return terms;
  }
  // Terms of E[p] (at most: the sum of its monomials' expectations', held before or not), after
  // add(p): what a product with E[p] multiplies.
  double terms(const Polynomial& p) {
    add(p);
    double terms = 0;
    for (const auto& [monomial, coefficient] : p.terms()) {
      const auto held = held_.find(monomial);
      if (held != held_.end()) terms += held->second;
    }
    return terms;
  }
  double total() const { return total_; }

 private:
  // The terms of E[m], when the recursion would compute it now; 0 when it already holds it.
  double count(const Monomial& m) {
    const auto [it, added] = held_.emplace(m, 0.0);
    if (!added) return 0;
    it->second = gaussian_moment_terms(m, kMaxExpectationTerms - total_);
    total_ += it->second;
    return it->second;
  }
  std::map<Monomial, double> held_;  // each monomial's E[m] terms
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

void check_observation_budget(const Model& model, const ObservationPolynomials& observation, bool gaussian) {
  if (observation.rows.empty()) return;
  const std::size_t n = model.n(), p = observation.rows.size();
  auto refuse = [&](std::optional<int> row, const std::string& message) {
    ModelError error(observation.field, message, row);
    error.set_file(model.source);
    throw error;
  };
  ExpectationCount E;
  auto check = [&](std::size_t r) {
    if (E.total() > kMaxExpectationTerms)
      refuse(static_cast<int>(r + 1),
             "the Gaussian expectations of the observation up to this row need more than " +
                 count_text(kMaxExpectationTerms) + " terms in all (the expectation E[x^a] of every monomial on the "
                 "way is kept); lower the degrees or the number of states multiplied together");
  };
  // The sampled update is Gaussian at every kind (the extended kind's is computed besides).
  const bool expectations = gaussian || observation.sampled;
  std::vector<double> predicted(p, 0.0), cross(p, 0.0), hessian(p, 0.0);
  for (std::size_t r = 0; r < p; ++r) {
    const Polynomial& row = observation.rows[r];
    predicted[r] = E.terms(row);  // every filter's frame: E[h]
    check(r);
    for (std::size_t k = 0; k < n; ++k) {
      const Polynomial d = row.derivative(static_cast<std::uint32_t>(k));
      // A cross-covariance entry sum_k P_ik E[J_rk] has their terms.
      cross[r] += expectations ? E.terms(d) : static_cast<double>(d.terms().size());
      check(r);
      if (observation.sampled || !gaussian || row.degree() < 2) continue;
      for (std::size_t b = 0; b < n; ++b) {
        hessian[r] += E.terms(d.derivative(static_cast<std::uint32_t>(b)));
        check(r);
      }
    }
  }
  double equations = 0;
  const double upper = static_cast<double>(n) * static_cast<double>(n + 1) / 2;
  if (observation.sampled) {
    // S_ab = E[c_a c_b] - E[c_a] E[c_b] (+ C P C^T at the mean): products of whole rows.
    for (std::size_t a = 0; a < p; ++a)
      for (std::size_t b = a; b < p; ++b) {
        const double product = static_cast<double>(observation.rows[a].terms().size()) *
                               static_cast<double>(observation.rows[b].terms().size());
        equations += predicted[a] * predicted[b] + cross[a] * cross[b] + product;
        if (equations > kMaxObservationProducts) break;
        E.add(observation.rows[a] * observation.rows[b]);
        check(a);
      }
  } else {
    // The correction K E[J] P, entry (i, j): sum_s gain_is cross_js, the gain entry gain_is a sum
    // of cross_ir over the rows r that R^-1 = (B B^T)^-1 couples with s (those R links to s,
    // directly or through others); dP's dy term P E[H_r] P for each such pair.
    const ExMatrix R = multiply_by_transpose(observation.noise);
    std::vector<std::size_t> group(p);
    for (std::size_t r = 0; r < p; ++r) group[r] = r;
    for (bool merged = true; merged;) {
      merged = false;
      for (std::size_t r = 0; r < p; ++r)
        for (std::size_t s = 0; s < p; ++s)
          if (!R[r][s].is_zero() && group[r] != group[s]) {
            group[r] = group[s] = std::min(group[r], group[s]);
            merged = true;
          }
    }
    for (std::size_t s = 0; s < p; ++s)
      for (std::size_t r = 0; r < p; ++r)
        if (group[r] == group[s]) equations += upper * (cross[r] * cross[s] + hessian[r]);
  }
  if (equations > kMaxObservationProducts)
    refuse(std::nullopt, "with " + std::to_string(n) + " states, the filter's " +
                             (observation.sampled ? "update" : "gain and correction") + " would take up to " +
                             count_text(equations) + " products of terms, above the limit of " +
                             count_text(kMaxObservationProducts) + "; lower the degrees or the number of states multiplied "
                             "together");
}

std::size_t observed_states(const ExMatrix& observation_matrix) {
  std::size_t count = 0;
  for (std::size_t k = 0; k < observation_matrix.at(0).size(); ++k) {
    bool observed = false;
    for (const auto& row : observation_matrix) observed = observed || !row[k].is_zero();
    count += observed;
  }
  return count;
}

std::size_t observed_states(const std::vector<Polynomial>& observation, std::size_t n) {
  std::vector<bool> read(n, false);
  for (const Polynomial& row : observation)
    for (const auto& [monomial, coefficient] : row.terms())
      for (const auto& [variable, exponent] : monomial.factors()) read[variable] = true;
  return static_cast<std::size_t>(std::count(read.begin(), read.end(), true));
}

}  // namespace pfgen
