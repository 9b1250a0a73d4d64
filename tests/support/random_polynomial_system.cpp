#include "support/random_polynomial_system.hpp"

#include <cmath>

#include "pfgen/model/model_builder.hpp"

namespace pfgen_test {
namespace {

int uniform(std::mt19937& rng, int lo, int hi) { return std::uniform_int_distribution<int>(lo, hi)(rng); }

// A non-zero rational with small numerator and denominator.
GiNaC::numeric random_rational(std::mt19937& rng) {
  int numerator = 0;
  while (numerator == 0) numerator = uniform(rng, -6, 6);
  return GiNaC::numeric(numerator, uniform(rng, 1, 5));
}

// Exponents of total degree `degree` spread at random over n variables.
std::vector<unsigned> random_exponents(std::mt19937& rng, std::size_t n, unsigned degree) {
  std::vector<unsigned> exponents(n, 0);
  for (unsigned k = 0; k < degree; ++k) ++exponents[static_cast<std::size_t>(uniform(rng, 0, static_cast<int>(n) - 1))];
  return exponents;
}

// All exponent vectors of n variables with total degree <= max_degree.
void all_exponents(std::size_t n, unsigned max_degree, std::vector<unsigned>& current,
                   std::vector<std::vector<unsigned>>& out) {
  if (current.size() == n) {
    out.push_back(current);
    return;
  }
  for (unsigned e = 0; e <= max_degree; ++e) {
    current.push_back(e);
    all_exponents(n, max_degree - e, current, out);
    current.pop_back();
  }
}

RandomTerm random_term(std::mt19937& rng, std::vector<unsigned> exponents, const RandomSystemOptions& options) {
  RandomTerm term;
  term.coefficient = random_rational(rng);
  if (options.symbolic_coefficients) {
    term.times_parameter = uniform(rng, 0, 5) == 0;
    term.times_sin_t = uniform(rng, 0, 7) == 0;
  }
  term.exponents = std::move(exponents);
  return term;
}

RandomPolynomial random_polynomial(std::mt19937& rng, std::size_t n, unsigned max_degree, bool force_max_degree,
                                   const RandomSystemOptions& options) {
  RandomPolynomial poly;
  if (options.dense) {
    std::vector<unsigned> current;
    std::vector<std::vector<unsigned>> exponents;
    all_exponents(n, max_degree, current, exponents);
    for (auto& e : exponents) poly.terms.push_back(random_term(rng, std::move(e), options));
    return poly;
  }
  const int count = uniform(rng, 1, static_cast<int>(options.max_terms));
  for (int k = 0; k < count; ++k) {
    const unsigned degree =
        (k == 0 && force_max_degree) ? max_degree : static_cast<unsigned>(uniform(rng, 0, static_cast<int>(max_degree)));
    poly.terms.push_back(random_term(rng, random_exponents(rng, n, degree), options));
  }
  return poly;
}

}  // namespace

unsigned RandomPolynomial::degree() const {
  unsigned d = 0;
  for (const auto& term : terms) {
    unsigned td = 0;
    for (unsigned e : term.exponents) td += e;
    d = std::max(d, td);
  }
  return d;
}

GiNaC::ex RandomPolynomial::to_ex(const std::vector<GiNaC::symbol>& x, const GiNaC::ex& a, const GiNaC::ex& t) const {
  GiNaC::ex sum = 0;
  for (const auto& term : terms) {
    GiNaC::ex value = term.coefficient;
    if (term.times_parameter) value *= a;
    if (term.times_sin_t) value *= GiNaC::sin(t);
    for (std::size_t i = 0; i < x.size(); ++i) value *= GiNaC::pow(x[i], term.exponents[i]);
    sum += value;
  }
  return sum;
}

double RandomPolynomial::evaluate(const double* x, double a, double t) const {
  double sum = 0;
  for (const auto& term : terms) {
    double value = term.coefficient.to_double();
    if (term.times_parameter) value *= a;
    if (term.times_sin_t) value *= std::sin(t);
    for (std::size_t i = 0; i < term.exponents.size(); ++i)
      for (unsigned k = 0; k < term.exponents[i]; ++k) value *= x[i];
    sum += value;
  }
  return sum;
}

pfgen::ExVector RandomSystem::f_ex() const {
  pfgen::ExVector out;
  for (const auto& fi : f) out.push_back(fi.to_ex(x, a, t));
  return out;
}

pfgen::ExMatrix RandomSystem::g_ex() const {
  pfgen::ExMatrix out(n, pfgen::ExVector(q));
  for (std::size_t i = 0; i < n; ++i)
    for (std::size_t k = 0; k < q; ++k) out[i][k] = g[i][k].to_ex(x, a, t);
  return out;
}

RandomSystem make_random_system(std::mt19937& rng, const RandomSystemOptions& options, const std::string& name) {
  RandomSystem s;
  s.n = options.n;
  s.q = options.q;
  pfgen::ModelBuilder builder(name);
  for (std::size_t i = 0; i < s.n; ++i) s.x.push_back(builder.state("x" + std::to_string(i + 1)));
  s.a_default = GiNaC::numeric(uniform(rng, 1, 9), 4);
  s.a = builder.parameter("a", s.a_default);
  s.t = builder.time();

  for (std::size_t i = 0; i < s.n; ++i) s.f.push_back(random_polynomial(rng, s.n, options.drift_degree, i == 0, options));
  s.g.assign(s.n, std::vector<RandomPolynomial>(s.q));
  for (std::size_t i = 0; i < s.n; ++i)
    for (std::size_t k = 0; k < s.q; ++k) {
      const bool first = i == 0 && k == 0;
      // About a third of the other entries are zero, so g has structure as real models do.
      if (!first && uniform(rng, 0, 2) == 0) continue;
      s.g[i][k] = random_polynomial(rng, s.n, options.diffusion_degree, first, options);
    }

  if (options.identity_observation) {
    s.p = s.n;
    s.A.assign(s.p, pfgen::ExVector(s.n, 0));
    for (std::size_t i = 0; i < s.n; ++i) s.A[i][i] = 1;
  } else {
    s.p = static_cast<std::size_t>(uniform(rng, 1, static_cast<int>(s.n) + 1));
    s.A.assign(s.p, pfgen::ExVector(s.n, 0));
    for (auto& row : s.A) {
      bool nonzero = false;
      while (!nonzero)
        for (auto& entry : row) {
          entry = uniform(rng, -2, 2);
          nonzero = nonzero || !entry.is_zero();
        }
    }
  }
  for (std::size_t r = 0; r < s.p; ++r) s.A0.push_back(GiNaC::numeric(uniform(rng, -3, 3), 2));
  s.B.assign(s.p, pfgen::ExVector(s.p, 0));
  for (std::size_t r = 0; r < s.p; ++r) s.B[r][r] = 1;

  builder.drift(s.f_ex());
  builder.diffusion(s.g_ex());
  builder.observation(s.A0, s.A, s.B);
  s.model = builder.build();
  return s;
}

}  // namespace pfgen_test
