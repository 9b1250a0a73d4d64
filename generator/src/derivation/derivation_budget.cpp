#include "pfgen/derivation/derivation_budget.hpp"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <map>
#include <set>

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

// The rows of an observation that the gain's R^-1 = (B B^T)^-1 may couple: group[r] == group[s]
// when R links r to s, directly or through others (R^-1 is block-diagonal on those groups).
std::vector<std::size_t> noise_groups(const ExMatrix& noise, std::size_t p) {
  const ExMatrix R = multiply_by_transpose(noise);
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
  return group;
}

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
    const std::vector<std::size_t> group = noise_groups(observation.noise, p);
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



// The moment filters' budget (closure3, closure4).
namespace {

// A count that would take more steps than this (points of the box times blocks) is of a moment
// with far more terms than any limit: g has many factors over many states (x1^5 ... x5^5 times a
// moment's indices), and the recursion that would compute it visits as many (moment, block) pairs,
// each a product of polynomials. It is taken as beyond the limit rather than counted.
constexpr double kMaxCountSteps = 2e7;

// Ways to split a multiset of factors (`shape`: each state's exponent, all > 0) into blocks of 2..k
// factors, the order of the blocks aside: the coefficient of z^shape in the product over block
// types b of 1 / (1 - z^b), by dynamic programming over the box of sub-multisets (mixed radix).
double block_partitions(const std::vector<std::uint32_t>& shape, unsigned order, double stop_above) {
  const std::size_t s = shape.size();
  std::vector<std::size_t> stride(s);
  double box = 1;
  for (std::size_t i = 0; i < s; ++i) {
    stride[i] = static_cast<std::size_t>(box);
    box *= shape[i] + 1.0;
    if (box > kMaxCountSteps) return std::max(stop_above, kMaxCountSteps) + 1;
  }
  // The block types: every b <= shape with 2 <= |b| <= k, as exponents and as an offset in the box.
  std::vector<std::vector<std::uint32_t>> blocks;
  std::vector<std::size_t> offsets;
  std::vector<std::uint32_t> b(s, 0);
  auto enumerate = [&](auto& self, std::size_t at, unsigned size, std::size_t offset) -> void {
    if (at == s) {
      if (size >= 2) {
        blocks.push_back(b);
        offsets.push_back(offset);
      }
      return;
    }
    for (std::uint32_t e = 0; e <= shape[at] && size + e <= order; ++e) {
      b[at] = e;
      self(self, at + 1, size + e, offset + e * stride[at]);
    }
    b[at] = 0;
  };
  enumerate(enumerate, 0, 0, 0);
  if (box * static_cast<double>(blocks.size()) > kMaxCountSteps) return std::max(stop_above, kMaxCountSteps) + 1;
  const std::size_t points = static_cast<std::size_t>(box);
  std::vector<double> ways(points, 0.0);
  ways[0] = 1;
  std::vector<std::uint32_t> digit(s);
  for (std::size_t t = 0; t < blocks.size(); ++t) {
    // Ascending, so that ways[v - b] already counts any number of blocks b.
    std::fill(digit.begin(), digit.end(), 0);
    for (std::size_t v = 0; v < points; ++v) {
      bool fits = true;
      for (std::size_t i = 0; i < s && fits; ++i) fits = digit[i] >= blocks[t][i];
      if (fits) ways[v] += ways[v - offsets[t]];
      for (std::size_t i = 0; i < s && ++digit[i] > shape[i]; ++i) digit[i] = 0;
    }
  }
  return ways[points - 1];
}

// A monomial's (state, exponent) pairs, states ascending: e^b, e^d, e^g.
using Exponents = std::vector<std::pair<std::uint32_t, std::uint32_t>>;

std::uint32_t size_of(const Exponents& g) {
  std::uint32_t size = 0;
  for (const auto& [state, exponent] : g) size += exponent;
  return size;
}

Exponents minus_one(Exponents a, std::uint32_t state) {
  for (auto it = a.begin(); it != a.end(); ++it)
    if (it->first == state) {
      if (--it->second == 0) a.erase(it);
      break;
    }
  return a;
}

// e^a e^b as one exponent list (both sorted by state): a state in both is one factor.
Exponents merged(const Exponents& a, const Exponents& b) {
  Exponents g;
  std::merge(a.begin(), a.end(), b.begin(), b.end(), std::back_inserter(g));
  for (std::size_t k = 1; k < g.size(); ++k)
    if (g[k].first == g[k - 1].first) {
      g[k - 1].second += g[k].second;
      g.erase(g.begin() + static_cast<std::ptrdiff_t>(k--));
    }
  return g;
}

// The terms m^c e^d of q(m + e), grouped by d: each monomial x^alpha gives one for every d <= alpha,
// so d's count is the number of q's monomials above it.
std::vector<std::pair<Exponents, double>> deviation_parts(const Polynomial& q) {
  std::map<Exponents, double> parts;
  for (const auto& [monomial, coefficient] : q.terms()) {
    const auto& factors = monomial.factors();
    std::vector<std::uint32_t> d(factors.size(), 0);
    for (;;) {
      Exponents key;
      for (std::size_t i = 0; i < d.size(); ++i)
        if (d[i]) key.emplace_back(factors[i].first, d[i]);
      parts[key] += 1;
      std::size_t i = 0;
      while (i < d.size() && ++d[i] > factors[i].second) d[i++] = 0;
      if (i == d.size()) break;
    }
  }
  return {parts.begin(), parts.end()};
}

// The derivation's work, counted as moment_closure_terms does it (see closure_derivation_work).
class ClosureCount {
 public:
  ClosureCount(unsigned order, double stop_above) : order_(order), stop_above_(stop_above) {}

  // Terms of E[e^g] (closed_moment_terms), memoised by the sorted exponents, which alone decide it.
  double moment(const Exponents& g) {
    std::vector<std::uint32_t> shape;
    for (const auto& [state, exponent] : g) shape.push_back(exponent);
    std::sort(shape.begin(), shape.end(), std::greater<>());
    const auto [it, added] = moments_.emplace(shape, 0.0);
    if (added) it->second = closed_moment_terms(shape, order_, stop_above_);
    return it->second;
  }
  // Products E[e^b q] takes: for each term m^c e^d of q(m + e), the terms of E[e^(b+d)], and those
  // of the recursion that computes E[e^(b+d)] the first time. The first part bounds E[e^b q]'s terms.
  double expectation(const Exponents& b, const std::vector<std::pair<Exponents, double>>& q) {
    double products = 0;
    for (const auto& [d, count] : q) {
      const Exponents g = merged(b, d);
      products += count * moment(g) + recursion(g);
    }
    return products;
  }

 private:
  // Products ClosedExpectation::central takes to compute E[e^g] and the moments on its way that it
  // does not hold yet (memoised by g as it is): with i g's first state, for each b <= g - e_i with
  // 1 <= |b| <= k - 1, the cumulant of e_i + b (one term, or four for an M4 less three pairs of P's)
  // times E[e^(g - e_i - b)].
  double recursion(const Exponents& g) {
    if (size_of(g) <= order_ || !computed_.insert(g).second) return 0;
    const Exponents rest = minus_one(g, g.front().first);
    double products = 0;
    Exponents b, remaining;
    auto visit = [&](auto& self, std::size_t at, unsigned size) -> void {
      if (at == rest.size()) {
        if (size == 0) return;
        remaining.clear();
        for (std::size_t t = 0; t < rest.size(); ++t) {
          const std::uint32_t left = rest[t].second - b[t].second;
          if (left) remaining.emplace_back(rest[t].first, left);
        }
        products += (size + 1 == 4 ? 4 : 1) * moment(remaining) + recursion(remaining);
        return;
      }
      for (std::uint32_t e = 0; e <= rest[at].second && size + e < order_; ++e) {
        b[at].second = e;
        self(self, at + 1, size + e);
      }
      b[at].second = 0;
    };
    b = rest;
    for (auto& factor : b) factor.second = 0;
    visit(visit, 0, 0);
    return products;
  }

  unsigned order_;
  double stop_above_;
  std::map<std::vector<std::uint32_t>, double> moments_;
  std::set<Exponents> computed_;
};

}  // namespace

double closed_moment_terms(const std::vector<std::uint32_t>& g, unsigned order, double stop_above) {
  std::vector<std::uint32_t> shape;
  std::uint32_t size = 0;
  for (std::uint32_t exponent : g)
    if (exponent) {
      shape.push_back(exponent);
      size += exponent;
    }
  if (size == 1) return 0;
  if (size <= order) return 1;  // 1, or the carried moment's variable
  std::sort(shape.begin(), shape.end(), std::greater<>());
  return block_partitions(shape, order, stop_above);
}

ClosureWork closure_derivation_work(const Model& model, const ClosureInputs& inputs, double stop_above) {
  const std::size_t n = model.n(), p = inputs.observation.size();
  const unsigned k = inputs.order;
  ClosureCount count(k, stop_above);
  ClosureWork work;
  auto over = [&] { return work.total() > stop_above; };
  using Parts = std::vector<std::pair<Exponents, double>>;
  std::vector<Parts> f, h;
  std::vector<std::vector<Parts>> G(n, std::vector<Parts>(n));
  std::uint32_t degree_f = 0, degree_G = 0, degree_h = 0;
  for (const Polynomial& fi : inputs.drift) {
    f.push_back(deviation_parts(fi));
    degree_f = std::max(degree_f, fi.degree());
  }
  for (std::size_t i = 0; i < n; ++i)
    for (std::size_t j = 0; j < n; ++j) {
      const Polynomial Gij = Polynomial::from_ex(model.diffusion.G[i][j], model.states);
      if (Gij.is_zero()) continue;
      G[i][j] = deviation_parts(Gij);
      degree_G = std::max(degree_G, Gij.degree());
    }
  for (const Polynomial& hr : inputs.observation) {
    h.push_back(deviation_parts(hr));
    degree_h = std::max(degree_h, hr.degree());
  }
  // m and the central moments of orders 2..k: C(n + k, k) - 1 equations. The derivation writes each
  // moment's indices as a vector of n exponents and finds it, its neighbours and their C_b in maps
  // keyed by those vectors: a cost of n for each, which is most of the work when the drift is
  // linear (64 states, closure3: 47904 equations, 3.4 s).
  double equations = -1;
  for (unsigned r = 0; r <= k; ++r) equations += std::round(std::exp(std::lgamma(n + r) - std::lgamma(n) - std::lgamma(r + 1.0)));
  work.equations = equations;
  work.bookkeeping = equations * static_cast<double>(n);
  if (over()) return work;
  work.moment_order = std::max({k - 1 + degree_f, k - 2 + degree_G, p ? k + degree_h : 0});

  // E[f], E[h] (the frame's and the gain's), once.
  std::vector<double> Ef(n), Eh(p);
  for (std::size_t i = 0; i < n; ++i) work.drift += Ef[i] = count.expectation({}, f[i]);
  for (std::size_t r = 0; r < p; ++r) work.observation += Eh[r] = count.expectation({}, h[r]);
  // C_b = E[e^b h] - mu_b E[h], once for each b (mu_b is one variable for |b| >= 2, zero for |b| = 1);
  // a row's terms times R^-1 (sums of rows R^-1 couples, each term scaled); a dot product of two.
  using Row = std::vector<double>;
  std::map<Exponents, Row> C;
  auto C_of = [&](const Exponents& b) -> const Row& {
    if (auto it = C.find(b); it != C.end()) return it->second;
    Row row(p);
    for (std::size_t r = 0; r < p; ++r)
      work.observation += row[r] = count.expectation(b, h[r]) + (size_of(b) >= 2 ? Eh[r] : 0);
    return C.emplace(b, std::move(row)).first->second;
  };
  const std::vector<std::size_t> group = p ? noise_groups(inputs.noise, p) : std::vector<std::size_t>{};
  auto times_R_inverse = [&](const Row& row) {
    Row out(p, 0.0);
    for (std::size_t s = 0; s < p; ++s)
      for (std::size_t r = 0; r < p; ++r)
        if (group[r] == group[s]) out[s] += row[r];
    for (double terms : out) work.observation += terms;
    return out;
  };
  auto dot = [&](const Row& a, const Row& b) {
    double products = 0;
    for (std::size_t s = 0; s < p; ++s) products += a[s] * b[s];
    return products;
  };
  auto unit = [](std::size_t i) { return Exponents{{static_cast<std::uint32_t>(i), 1}}; };
  std::vector<Row> K;  // K_i = C_(e_i) R^-1
  for (std::size_t i = 0; i < n && p; ++i) K.push_back(times_R_inverse(C_of(unit(i))));

  // Each central moment a of order 2..k, indices i1 <= ... <= ir (moment_parts).
  auto moment_equation = [&](const Exponents& a) {
    Row innovation = p ? C_of(a) : Row{};
    for (const auto& [state, exponent] : a) {
      const Exponents b = minus_one(a, state);
      const bool carried = size_of(b) >= 2;  // mu_b a variable, not zero
      work.drift += count.expectation(b, f[state]) + (carried ? Ef[state] : 0);
      for (const auto& [other, e] : b) {
        const Exponents c = minus_one(b, other);
        if (!G[state][other].empty()) work.diffusion += count.expectation(c, G[state][other]);
        if (p) work.observation += dot(K[state], C_of(unit(other))) * (size_of(c) == 1 ? 1 : 2);
      }
      if (p) {
        work.observation += dot(times_R_inverse(C_of(b)), C_of(unit(state)));
        if (carried)
          for (std::size_t r = 0; r < p; ++r) work.observation += C_of(unit(state))[r], innovation[r] += C_of(unit(state))[r];
      }
    }
    if (p) times_R_inverse(innovation);
  };
  for (unsigned r = 2; r <= k && !over(); ++r) {
    std::vector<std::uint32_t> indices(r, 0);
    for (;;) {
      Exponents a;
      for (std::uint32_t i : indices)
        if (!a.empty() && a.back().first == i) ++a.back().second;
        else a.emplace_back(i, 1);
      moment_equation(a);
      if (over()) break;
      // The next i1 <= ... <= ir in lexicographic order.
      std::size_t at = r;
      while (at > 0 && indices[at - 1] == n - 1) --at;
      if (at == 0) break;
      const std::uint32_t next = indices[at - 1] + 1;
      for (std::size_t t = at - 1; t < r; ++t) indices[t] = next;
    }
  }
  return work;
}

void check_closure_budget(const Model& model, const ClosureInputs& inputs) {
  // Counted on to four times the limit, to say how far beyond it a model is (the count takes about
  // 0.1 s per 10 million products it counts, on the dense cubic models).
  const double counted = 4 * kMaxClosureProducts;
  const ClosureWork work = closure_derivation_work(model, inputs, counted);
  if (work.total() <= kMaxClosureProducts) return;
  // The field whose terms take most of the work.
  std::string field = "drift";
  if (work.diffusion > std::max(work.drift, work.observation)) field = inputs.diffusion_field;
  if (work.observation > std::max(work.drift, work.diffusion)) field = inputs.observation_field;
  if (work.bookkeeping > std::max({work.drift, work.diffusion, work.observation})) field = "states";
  std::uint32_t degree = 0;
  for (const Polynomial& fi : inputs.drift) degree = std::max(degree, fi.degree());
  ModelError error(field,
                   "filter " + inputs.kind + " of a " + std::to_string(model.n()) + "-state model with a drift of degree " +
                       std::to_string(degree) + " would take " + (work.total() > counted ? "more than " + count_text(counted) : "up to " + count_text(work.total())) +
                       " products of terms (limit " + count_text(kMaxClosureProducts) + "): its " +
                       count_text(work.equations) + " equations (m and the central moments of orders 2 to " +
                       std::to_string(inputs.order) + ") read the closed law's moments up to order " +
                       std::to_string(work.moment_order) + "; use " +
                       (inputs.order > 3 ? "closure" + std::to_string(inputs.order - 1) + ", " : std::string()) +
                       "fewer states or lower degrees");
  error.set_file(model.source);
  throw error;
}

void check_closure_samples_budget(const Model& model, unsigned order, const std::string& kind,
                                  const std::vector<Polynomial>& c,
                                  const std::vector<std::vector<std::size_t>>& joint_moments) {
  // Each joint moment is E of a product of its factors, e_i or d_a (whose terms are at most those of c_a(m + e)).
  // The product's terms m^c e^g, grouped by g with their count, are the parts of each factor's multiplied out;
  // ClosureCount then counts, as for the continuous moment filters, the terms of each E[e^g] and the products of
  // the recursion that computes it. Counting stops above four times the limit.
  using Parts = std::map<Exponents, double>;
  const std::size_t n = model.n();
  const double stop_above = 4 * kMaxClosureProducts;
  std::vector<Parts> factor(n + c.size());
  for (std::size_t i = 0; i < n; ++i) factor[i][Exponents{{static_cast<std::uint32_t>(i), 1}}] = 1;
  std::uint32_t degree = 0;
  for (std::size_t a = 0; a < c.size(); ++a) {
    for (const auto& [d, count] : deviation_parts(c[a])) factor[n + a][d] += count;
    degree = std::max(degree, c[a].degree());
  }
  // One line naming the field: what the update reads with this c, why it is refused, what to use instead.
  auto refuse = [&](const std::string& why, const std::string& instead) {
    ModelError error("observation.sampled.c",
                     "filter " + kind + " updates each sample from the joint moments of x - m and c of orders up to " +
                         std::to_string(order) + ", which with c of degree " + std::to_string(degree) + why + "; use " +
                         (order > 3 ? "cd-closure" + std::to_string(order - 1) + (instead.empty() ? " or " : ", ")
                                    : std::string()) +
                         (instead.empty() ? "a c of lower degree" : instead));
    error.set_file(model.source);
    throw error;
  };
  // A single state's high power costs more per product than the count says (its coefficients are binomials of
  // many digits, its closed moments long): x^48 under cd-closure3 takes 8 s and 1.7 GB for 1.6 million products.
  // So the order of the moments read is capped as well (x^32 under cd-closure3: 1.2 s, 270 MB).
  if (order * degree > kMaxSampledMomentOrder)
    refuse(" read the closed law's moments up to order " + std::to_string(order * degree) + " (limit " +
               std::to_string(kMaxSampledMomentOrder) + ")",
           "");
  ClosureCount count(order, stop_above);
  double work = 0;
  for (const auto& t : joint_moments) {
    Parts product = {{Exponents{}, 1.0}};
    for (std::size_t index : t) {
      Parts next;
      double terms = 0;
      for (const auto& [a, x] : product)
        for (const auto& [b, y] : factor[index]) {
          next[merged(a, b)] += x * y;
          terms += x * y;
        }
      work += terms;  // the product's own multiplications
      product.swap(next);
      if (work > stop_above) break;
    }
    if (work > stop_above) break;
    work += count.expectation({}, {product.begin(), product.end()});
    if (work > stop_above) break;
  }
  if (work <= kMaxClosureProducts) return;
  refuse(" would take " + (work > stop_above ? "more than " + count_text(stop_above) : "up to " + count_text(work)) +
             " products of terms (limit " + count_text(kMaxClosureProducts) +
             "; they read the closed law's moments up to order " + std::to_string(order * degree) + ")",
         "fewer states or a c with fewer terms or of lower degree");
}

}  // namespace pfgen
