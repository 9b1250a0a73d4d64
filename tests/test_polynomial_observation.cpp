// The polynomial observation's terms (observations/polynomial/polynomial_observation_terms) against
// what they must equal: the linear observation's filter for linear h, the cubic sensor's closed
// form, Stein's identities computed by an independent Isserlis expansion, and the Bayes update of
// a Gaussian prior by one observation increment, estimated by Monte Carlo.
#include <catch2/catch.hpp>

#include <cmath>
#include <random>
#include <sstream>

#include "pfgen/observations/continuous/observation_terms.hpp"
#include "pfgen/observations/polynomial/polynomial_observation_terms.hpp"
#include "support/isserlis_reference.hpp"
#include "support/symbolic_mismatch.hpp"

using namespace pfgen;
using pfgen_test::mismatch;
using pfgen_test::IsserlisReference;

namespace {

std::vector<GiNaC::symbol> x_symbols(std::size_t n) {
  std::vector<GiNaC::symbol> x;
  for (std::size_t i = 0; i < n; ++i) x.emplace_back("x" + std::to_string(i + 1));
  return x;
}

std::vector<Polynomial> polynomials(const ExVector& h, const std::vector<GiNaC::symbol>& x) {
  std::vector<Polynomial> out;
  for (const auto& e : h) out.push_back(Polynomial::from_ex(e, x));
  return out;
}

}  // namespace

TEST_CASE("polynomial observation: linear h gives the linear observation's filter exactly",
          "[observation][polynomial][unit]") {
  const FilterVariables vars(2);
  const std::vector<GiNaC::symbol> x = x_symbols(2);
  const GiNaC::symbol a("a"), r("r"), t("t");
  AffineRate linear;
  linear.A0 = {3 * t, GiNaC::ex(0)};
  linear.A = {{1, a}, {GiNaC::numeric(1, 2), 2}};
  linear.B = {{r, 0}, {GiNaC::numeric(1, 10), 1}};
  const ExVector h = {3 * t + x[0] + a * x[1], GiNaC::numeric(1, 2) * x[0] + 2 * x[1]};
  for (bool at_mean : {false, true}) {
    const PolynomialObservationTerms terms = polynomial_observation_terms(polynomials(h, x), linear.B, vars, at_mean);
    const ObservationCorrection expected = observation_correction(linear, vars);
    CHECK(terms.predicted_observation == predicted_observation(linear, vars));
    for (std::size_t i = 0; i < 2; ++i)
      for (std::size_t k = 0; k < 2; ++k)
        CHECK(mismatch(expected.gain[i][k].to_ex(vars.symbols()), terms.gain[i][k].to_ex(vars.symbols())) == "");
    for (std::size_t u = 0; u < 3; ++u) {
      CHECK(mismatch(expected.P_correction[u].to_ex(vars.symbols()), terms.P_correction[u].to_ex(vars.symbols())) == "");
      for (const Polynomial& L : terms.P_gain[u]) CHECK(L.is_zero());
    }
  }
}

TEST_CASE("polynomial observation: the cubic sensor's filter in closed form", "[observation][polynomial][unit]") {
  // dy = x^3 dt + rho dV: E[h] = m^3 + 3 m P, K = 3 P (m^2 + P) / rho^2, correction
  // 9 P^2 (m^2 + P)^2 / rho^2, dnu's coefficient in dP 6 m P^2 / rho^2; the extended filter:
  // h(m) = m^3, K = 3 m^2 P / rho^2, correction 9 m^4 P^2 / rho^2, no dnu term.
  const FilterVariables vars(1);
  const std::vector<GiNaC::symbol> x = x_symbols(1);
  const GiNaC::symbol rho("rho");
  const GiNaC::ex m = vars.symbols()[0], P = vars.symbols()[1];
  const PolynomialObservationTerms optimal =
      polynomial_observation_terms(polynomials({pow(x[0], 3)}, x), {{rho}}, vars, false);
  CHECK(mismatch(pow(m, 3) + 3 * m * P, optimal.predicted_observation[0].to_ex(vars.symbols())) == "");
  CHECK(mismatch(3 * P * (m * m + P) / pow(rho, 2), optimal.gain[0][0].to_ex(vars.symbols())) == "");
  CHECK(mismatch(9 * P * P * pow(m * m + P, 2) / pow(rho, 2), optimal.P_correction[0].to_ex(vars.symbols())) == "");
  CHECK(mismatch(6 * m * P * P / pow(rho, 2), optimal.P_gain[0][0].to_ex(vars.symbols())) == "");
  const PolynomialObservationTerms extended =
      polynomial_observation_terms(polynomials({pow(x[0], 3)}, x), {{rho}}, vars, true);
  CHECK(mismatch(pow(m, 3), extended.predicted_observation[0].to_ex(vars.symbols())) == "");
  CHECK(mismatch(3 * m * m * P / pow(rho, 2), extended.gain[0][0].to_ex(vars.symbols())) == "");
  CHECK(mismatch(9 * pow(m, 4) * P * P / pow(rho, 2), extended.P_correction[0].to_ex(vars.symbols())) == "");
  CHECK(extended.P_gain[0][0].is_zero());
}

TEST_CASE("polynomial observation: Stein's forms equal the covariances an Isserlis expansion computes",
          "[observation][polynomial][isserlis][unit]") {
  // With R = I the gain is Cov(x, h), the correction Cov(x, h) Cov(x, h)^T and L_ij,r the third
  // central co-moment E[(x_i - m_i)(x_j - m_j)(h_r - E h_r)], each computed here from its
  // definition by the Isserlis reference, for observations of degree 1 to 4 with a parameter and t.
  const FilterVariables vars(2);
  const std::vector<GiNaC::symbol> x = x_symbols(2);
  const GiNaC::symbol a("a"), t("t");
  const ExVector h = {pow(x[0], 3) - 2 * x[0] * x[1] + GiNaC::numeric(1, 2) * pow(x[1], 2) + 3,
                      a * x[0] * pow(x[1], 2) + t * x[1], pow(x[0], 2) * pow(x[1], 2) - x[0]};
  const ExMatrix identity = {{1, 0, 0}, {0, 1, 0}, {0, 0, 1}};
  const PolynomialObservationTerms terms = polynomial_observation_terms(polynomials(h, x), identity, vars, false);
  IsserlisReference E({x[0], x[1]}, vars);
  const auto& s = vars.symbols();
  auto m = [&](std::size_t i) { return E.m(i); };
  std::vector<std::vector<GiNaC::ex>> cov(2, std::vector<GiNaC::ex>(3));
  for (std::size_t r = 0; r < 3; ++r) {
    const GiNaC::ex Eh = E.expectation(h[r]);
    CHECK(mismatch(Eh, terms.predicted_observation[r].to_ex(s)) == "");
    for (std::size_t i = 0; i < 2; ++i) {
      cov[i][r] = E.expectation((x[i] - m(i)) * h[r]);
      CHECK(mismatch(cov[i][r], terms.gain[i][r].to_ex(s)) == "");
    }
  }
  std::size_t upper = 0;
  for (std::size_t i = 0; i < 2; ++i)
    for (std::size_t j = i; j < 2; ++j, ++upper) {
      GiNaC::ex correction = 0;
      for (std::size_t r = 0; r < 3; ++r) correction += cov[i][r] * cov[j][r];
      CHECK(mismatch(correction, terms.P_correction[upper].to_ex(s)) == "");
      for (std::size_t r = 0; r < 3; ++r) {
        const GiNaC::ex comoment =
            E.expectation((x[i] - m(i)) * (x[j] - m(j)) * h[r]) - E.P(i, j) * E.expectation(h[r]);
        CHECK(mismatch(comoment, terms.P_gain[upper][r].to_ex(s)) == "");
      }
    }
}

namespace {

// The covariance of x ~ N(m, P) reweighted by the likelihood of one observation increment at dt -> 0,
// exp(h(x)^T R^-1 dnu): Bayes' update of the prior by dnu. Its derivative in dnu_r at 0 is what the
// filter's dP gains per unit of dnu_r. Estimated by a central difference on one sample.
struct Sample {
  std::vector<std::vector<double>> x;  // N draws of n states
  std::vector<std::vector<double>> h;  // h(x) per draw
};

std::vector<double> reweighted_covariance(const Sample& sample, const std::vector<double>& weight_exponent_per_draw) {
  const std::size_t n = sample.x[0].size();
  double total = 0;
  std::vector<double> mean(n, 0.0), cov(n * (n + 1) / 2, 0.0);
  for (std::size_t d = 0; d < sample.x.size(); ++d) {
    const double w = std::exp(weight_exponent_per_draw[d]);
    total += w;
    for (std::size_t i = 0; i < n; ++i) mean[i] += w * sample.x[d][i];
  }
  for (double& v : mean) v /= total;
  for (std::size_t d = 0; d < sample.x.size(); ++d) {
    const double w = std::exp(weight_exponent_per_draw[d]) / total;
    std::size_t u = 0;
    for (std::size_t i = 0; i < n; ++i)
      for (std::size_t j = i; j < n; ++j, ++u) cov[u] += w * (sample.x[d][i] - mean[i]) * (sample.x[d][j] - mean[j]);
  }
  return cov;
}

}  // namespace

TEST_CASE("polynomial observation: dnu's term in dP is the Bayes update's covariance increment (Monte Carlo)",
          "[observation][polynomial][statistical]") {
  // Range-squared h = x1^2 + x2^2 and a cubic h = x1^3 - x1 x2, R = diag(0.25, 0.5), at m = (0.4, -0.3) and a
  // full P: the derivative of the reweighted covariance in dnu_r (central difference, step 0.005, on
  // 400000 draws, the same draws for both signs) against L_ij,r; the tolerance is 5 standard errors
  // of the difference over 20 batches of draws.
  const FilterVariables vars(2);
  const std::vector<GiNaC::symbol> x = x_symbols(2);
  const ExVector h = {pow(x[0], 2) + pow(x[1], 2), pow(x[0], 3) - x[0] * x[1]};
  const ExMatrix B = {{GiNaC::numeric(1, 2), 0}, {0, GiNaC::sqrt(GiNaC::numeric(1, 2))}};
  const double R_inverse[2] = {4.0, 2.0};
  const double m[2] = {0.4, -0.3}, P[2][2] = {{0.3, 0.1}, {0.1, 0.2}};
  const PolynomialObservationTerms terms = polynomial_observation_terms(polynomials(h, x), B, vars, false);

  GiNaC::exmap point;
  point[vars.symbols()[0]] = m[0];
  point[vars.symbols()[1]] = m[1];
  point[vars.symbols()[vars.P(0, 0)]] = P[0][0];
  point[vars.symbols()[vars.P(0, 1)]] = P[0][1];
  point[vars.symbols()[vars.P(1, 1)]] = P[1][1];

  constexpr std::size_t draws = 400000, batches = 20;
  std::mt19937_64 rng(20261127);
  std::normal_distribution<double> normal;
  const double l11 = std::sqrt(P[0][0]), l21 = P[0][1] / l11, l22 = std::sqrt(P[1][1] - l21 * l21);
  Sample sample;
  for (std::size_t d = 0; d < draws; ++d) {
    const double z1 = normal(rng), z2 = normal(rng);
    const double x1 = m[0] + l11 * z1, x2 = m[1] + l21 * z1 + l22 * z2;
    sample.x.push_back({x1, x2});
    sample.h.push_back({x1 * x1 + x2 * x2, x1 * x1 * x1 - x1 * x2});
  }
  constexpr double step = 0.005;
  for (std::size_t r = 0; r < 2; ++r) {
    // Batch by batch: the derivative's estimate in each, then their mean and standard error.
    std::vector<std::vector<double>> estimates;
    for (std::size_t b = 0; b < batches; ++b) {
      Sample batch;
      for (std::size_t d = b; d < draws; d += batches) {
        batch.x.push_back(sample.x[d]);
        batch.h.push_back(sample.h[d]);
      }
      std::vector<double> up, down;
      for (const auto& hd : batch.h) {
        up.push_back(hd[r] * R_inverse[r] * step);
        down.push_back(-hd[r] * R_inverse[r] * step);
      }
      const std::vector<double> plus = reweighted_covariance(batch, up), minus = reweighted_covariance(batch, down);
      std::vector<double> derivative;
      for (std::size_t u = 0; u < 3; ++u) derivative.push_back((plus[u] - minus[u]) / (2 * step));
      estimates.push_back(derivative);
    }
    double largest = 0, largest_error = 0;
    for (std::size_t u = 0; u < 3; ++u) {
      double mean = 0, square = 0;
      for (const auto& e : estimates) mean += e[u] / batches;
      for (const auto& e : estimates) square += (e[u] - mean) * (e[u] - mean);
      const double standard_error = std::sqrt(square / (batches - 1) / batches);
      const double derived =
          GiNaC::ex_to<GiNaC::numeric>(terms.P_gain[u][r].to_ex(vars.symbols()).subs(point).evalf()).to_double();
      INFO("L_" << u << "," << r << ": derived " << derived << ", Monte Carlo " << mean << " +- " << standard_error);
      CHECK(std::abs(derived - mean) < 5 * standard_error + 1e-3 * std::abs(derived));
      if (std::abs(derived) > largest) largest = std::abs(derived), largest_error = standard_error;
    }
    // The check can fail: each r's largest entry is resolved to better than a tenth of its size.
    CHECK(largest > 10 * largest_error);
  }
}
