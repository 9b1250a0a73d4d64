// The Ito-Stratonovich correction of a filter driven by a polynomial observation
// (observations/polynomial/ito_stratonovich_correction): its closed form for the cubic sensor, and
// what it is for, on one Brownian path: Heun's step with the observed increment given converges
// at first order to the Ito filter when it steps the corrected drift, and to another filter
// without the correction; Euler-Maruyama (the Ito filter's own scheme, order 1/2) agrees with the
// corrected limit.
#include <catch2/catch.hpp>

#include <cmath>
#include <random>
#include <sstream>

#include "pfgen/observations/polynomial/ito_stratonovich_correction.hpp"
#include "pfgen/observations/polynomial/polynomial_observation_terms.hpp"

#include "support/symbolic_mismatch.hpp"

using namespace pfgen;
using pfgen_test::mismatch;

namespace {

// A polynomial with numeric coefficients, evaluated in double at the filter variables' values.
class Compiled {
 public:
  explicit Compiled(const Polynomial& p) {
    for (const auto& [monomial, coefficient] : p.terms()) {
      Term term{GiNaC::ex_to<GiNaC::numeric>(coefficient.evalf()).to_double(), {}};
      for (const auto& [variable, exponent] : monomial.factors()) term.factors.emplace_back(variable, exponent);
      terms_.push_back(term);
    }
  }
  double operator()(const std::vector<double>& s) const {
    double sum = 0;
    for (const Term& term : terms_) {
      double product = term.coefficient;
      for (const auto& [variable, exponent] : term.factors) product *= std::pow(s[variable], exponent);
      sum += product;
    }
    return sum;
  }

 private:
  struct Term {
    double coefficient;
    std::vector<std::pair<std::uint32_t, std::uint32_t>> factors;
  };
  std::vector<Term> terms_;
};

// The cubic sensor dx = -a x dt + sigma dW, dy = x^3 dt + rho dV, a = 1, sigma = 0.5, rho = 0.5:
// its Gaussian-closure filter in s = (m, P), ds = F dt + noise dnu, dnu = dy - yhat dt.
struct CubicSensorFilter {
  Compiled F_m, F_P, yhat, noise_m, noise_P, c_m, c_P;
};

CubicSensorFilter cubic_sensor_filter(const FilterVariables& vars) {
  const GiNaC::symbol x("x");
  const GiNaC::numeric rho(1, 2);
  const PolynomialObservationTerms terms =
      polynomial_observation_terms({Polynomial::from_ex(pow(x, 3), {x})}, {{rho}}, vars, false);
  const Polynomial m = Polynomial::variable(vars.m(0)), P = Polynomial::variable(vars.P(0, 0));
  const Polynomial F_m = m.scaled(-1);                                                   // E[f] = -a m
  const Polynomial F_P = P.scaled(-2) + Polynomial::constant(GiNaC::numeric(1, 4)) - terms.P_correction[0];
  const std::vector<Polynomial> c =
      ito_stratonovich_correction({{terms.gain[0][0]}, {terms.P_gain[0][0]}}, {{rho}}, vars);
  return {Compiled(F_m), Compiled(F_P), Compiled(terms.predicted_observation[0]), Compiled(terms.gain[0][0]),
          Compiled(terms.P_gain[0][0]), Compiled(c[0]), Compiled(c[1])};
}

enum class Scheme { CorrectedHeun, PlainHeun, EulerMaruyama };

// (m, P) at T = 1 from m0 = 0.5, P0 = 0.5, stepping `steps` steps of the observed increments dy
// (given on the finest grid, summed to the step).
std::vector<double> integrate(const CubicSensorFilter& f, const std::vector<double>& dy, std::size_t steps,
                              Scheme scheme) {
  const std::size_t per_step = dy.size() / steps;
  const double h = 1.0 / static_cast<double>(steps);
  std::vector<double> s = {0.5, 0.5};
  // Drift and noise of the equation the scheme steps: the Ito one, or its Stratonovich form
  // (corrected) or the Ito drift read as Stratonovich (plain).
  auto increment = [&](const std::vector<double>& at, double dY) {
    const double yhat = f.yhat(at), km = f.noise_m(at), kP = f.noise_P(at);
    double dm = f.F_m(at) * h + km * (dY - yhat * h), dP = f.F_P(at) * h + kP * (dY - yhat * h);
    if (scheme == Scheme::CorrectedHeun) dm -= f.c_m(at) * h, dP -= f.c_P(at) * h;
    return std::vector<double>{dm, dP};
  };
  for (std::size_t k = 0; k < steps; ++k) {
    double dY = 0;
    for (std::size_t j = k * per_step; j < (k + 1) * per_step; ++j) dY += dy[j];
    const std::vector<double> k1 = increment(s, dY);
    if (scheme == Scheme::EulerMaruyama) {
      s = {s[0] + k1[0], s[1] + k1[1]};
      continue;
    }
    const std::vector<double> k2 = increment({s[0] + k1[0], s[1] + k1[1]}, dY);
    s = {s[0] + 0.5 * (k1[0] + k2[0]), s[1] + 0.5 * (k1[1] + k2[1])};
  }
  return s;
}

double distance(const std::vector<double>& a, const std::vector<double>& b) {
  return std::hypot(a[0] - b[0], a[1] - b[1]);
}

}  // namespace

TEST_CASE("polynomial observation: the cubic sensor's Ito-Stratonovich correction in closed form",
          "[observation][polynomial][unit]") {
  // sigma_m = 3 P (m^2 + P) / rho^2, sigma_P = 6 m P^2 / rho^2, R = rho^2:
  // c_m = 9 m P^2 (2 m^2 + 3 P) / rho^2, c_P = 9 P^3 (5 m^2 + P) / rho^2.
  const FilterVariables vars(1);
  const GiNaC::symbol x("x"), rho("rho");
  const PolynomialObservationTerms terms =
      polynomial_observation_terms({Polynomial::from_ex(pow(x, 3), {x})}, {{rho}}, vars, false);
  const std::vector<Polynomial> c =
      ito_stratonovich_correction({{terms.gain[0][0]}, {terms.P_gain[0][0]}}, {{rho}}, vars);
  const GiNaC::ex m = vars.symbols()[0], P = vars.symbols()[1];
  CHECK(mismatch(9 * m * P * P * (2 * m * m + 3 * P) / pow(rho, 2), c[0].to_ex(vars.symbols())) == "");
  CHECK(mismatch(9 * pow(P, 3) * (5 * m * m + P) / pow(rho, 2), c[1].to_ex(vars.symbols())) == "");
  // A linear observation's filter: the gain reads P only and P has no dnu term, so c = 0.
  const PolynomialObservationTerms linear =
      polynomial_observation_terms({Polynomial::from_ex(2 * x, {x})}, {{rho}}, vars, false);
  for (const Polynomial& entry : ito_stratonovich_correction({{linear.gain[0][0]}, {linear.P_gain[0][0]}}, {{rho}}, vars))
    CHECK(entry.is_zero());
}

TEST_CASE("polynomial observation: Heun with the correction converges at first order to the Ito filter on one path",
          "[observation][polynomial][statistical]") {
  const FilterVariables vars(1);
  const CubicSensorFilter filter = cubic_sensor_filter(vars);
  // One path of the truth and its observations on 2^16 steps of [0, 1] (Euler-Maruyama, x0 = 0.8).
  constexpr std::size_t finest = std::size_t{1} << 16;
  std::mt19937_64 rng(29);
  std::normal_distribution<double> normal;
  const double dt = 1.0 / finest;
  double x = 0.8;
  std::vector<double> dy(finest);
  for (std::size_t k = 0; k < finest; ++k) {
    dy[k] = x * x * x * dt + 0.5 * std::sqrt(dt) * normal(rng);
    x += -x * dt + 0.5 * std::sqrt(dt) * normal(rng);
  }
  const std::vector<double> reference = integrate(filter, dy, finest, Scheme::CorrectedHeun);
  std::vector<double> corrected, plain;
  for (std::size_t steps : {std::size_t{1} << 8, std::size_t{1} << 10, std::size_t{1} << 12}) {
    corrected.push_back(distance(integrate(filter, dy, steps, Scheme::CorrectedHeun), reference));
    plain.push_back(distance(integrate(filter, dy, steps, Scheme::PlainHeun), reference));
  }
  const double euler = distance(integrate(filter, dy, finest, Scheme::EulerMaruyama), reference);
  INFO("corrected Heun, 2^8 2^10 2^12 steps: " << corrected[0] << " " << corrected[1] << " " << corrected[2]);
  INFO("plain Heun: " << plain[0] << " " << plain[1] << " " << plain[2] << "; Euler-Maruyama at 2^16: " << euler);
  // First order: 16 times the steps, at least 8 times closer (order 3/4 or better on this path).
  CHECK(corrected[0] > 8 * corrected[2]);
  // Without the correction Heun converges elsewhere: its distance stops shrinking.
  CHECK(plain[2] > 0.5 * plain[0]);
  CHECK(plain[2] > 20 * corrected[2]);
  // The Ito filter's own scheme, at the finest step, lands near the corrected limit, far from Heun's.
  CHECK(euler < 0.2 * plain[2]);
}
