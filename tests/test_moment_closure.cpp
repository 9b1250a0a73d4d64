// The moment filters (closure3, closure4; derivation/moment_closure.hpp): at order 2 the equations are
// the optimal kind's, polynomial for polynomial; the closed law's central moments match hand-computed
// moment-cumulant relations; and on a linear model with additive noise the Gaussian family is
// invariant (the Kalman-Bucy special case). tests/closure/check_closure_moments.py checks orders 3
// and 4 against a second derivation in SymPy.
#include <catch2/catch.hpp>

#include <sstream>

#include "pfgen/derivation/closed_expectation.hpp"
#include "pfgen/derivation/filter_equations.hpp"
#include "pfgen/derivation/moment_closure.hpp"
#include "pfgen/evaluation/point_evaluator.hpp"
#include "pfgen/model/yaml_model_loader.hpp"
#include "support/test_paths.hpp"

using namespace pfgen;

namespace {

std::string text(const Polynomial& p, const FilterVariables& vars) {
  std::ostringstream out;
  out << p.to_ex(vars.symbols());
  return out.str();
}

void require_equal(const Polynomial& expected, const Polynomial& derived, const FilterVariables& vars,
                   const std::string& what) {
  INFO(what << "\n  optimal: " << text(expected, vars) << "\n  closure: " << text(derived, vars));
  REQUIRE(expected == derived);
}

}  // namespace

TEST_CASE("the moment filter of order 2 is the optimal kind's filter, term by term", "[closure][unit]") {
  for (const std::string& file :
       {pfgen_test::example("polynomial/cubic_sensor.yaml"), pfgen_test::example("basin2006_quadratic.yaml"),
        pfgen_test::example("reference/double_well.yaml"), pfgen_test::example("polynomial/van_der_pol_energy.yaml"),
        pfgen_test::example("van_der_pol.yaml"), pfgen_test::example("paper002/satellite.yaml"),
        pfgen_test::source_dir() + "/tests/closure/two_sensor_multiplicative.yaml"}) {
    INFO(file);
    const Model model = load_model_file(file);
    const FilterEquations optimal = derive_filter(model, FilterKind::Optimal);
    const FilterVariables& vars = optimal.variables;
    const ObservationRate& rate = model.observation.rate();
    const MomentClosureTerms closure = moment_closure_terms(model, vars, rate.polynomials(model.states), rate.noise());
    REQUIRE(closure.higher_drift.empty());
    for (std::size_t i = 0; i < model.n(); ++i) {
      require_equal(optimal.m_drift[i], closure.m_drift[i], vars, "m_drift " + std::to_string(i + 1));
      for (std::size_t r = 0; r < model.p(); ++r)
        require_equal(optimal.gain[i][r], closure.gain[i][r], vars, "gain " + std::to_string(i + 1));
    }
    for (std::size_t r = 0; r < model.p(); ++r)
      require_equal(optimal.predicted_observation[r], closure.predicted_observation[r], vars, "predicted observation");
    for (std::size_t i = 0; i < model.n(); ++i)
      for (std::size_t j = i; j < model.n(); ++j) {
        const std::size_t u = vars.upper_index(i, j);
        const std::string entry = "P" + std::to_string(i + 1) + std::to_string(j + 1);
        require_equal(optimal.P_moment[u], closure.P_moment[u], vars, entry + " moment part");
        require_equal(optimal.P_diffusion[u], closure.P_diffusion[u], vars, entry + " diffusion part");
        require_equal(optimal.P_correction[u], closure.P_correction[u], vars, entry + " correction part");
        for (std::size_t r = 0; r < model.p(); ++r)
          require_equal(optimal.P_gain.empty() ? Polynomial() : optimal.P_gain[u][r], closure.P_gain[u][r], vars,
                        entry + " dy term");
      }
  }
}

TEST_CASE("the closed law's central moments are the moment-cumulant relations", "[closure][unit]") {
  // Scalar: mu5 = 10 kappa2 kappa3; mu6 = 15 kappa2^3 + 15 kappa2 kappa4 + 10 kappa3^2, kappa4 = M4 - 3 P^2.
  for (std::size_t order : {3u, 4u}) {
    const FilterVariables vars(1, false, order);
    ClosedExpectation E(vars);
    const Polynomial P = Polynomial::variable(vars.P(0, 0)), M3 = Polynomial::variable(vars.higher_moment({0, 0, 0}));
    const Polynomial M4 = order == 4 ? Polynomial::variable(vars.higher_moment({0, 0, 0, 0})) : (P * P).scaled(3);
    const Polynomial kappa4 = M4 - (P * P).scaled(3);
    REQUIRE(E.central({1}).is_zero());
    REQUIRE(E.central({2}) == P);
    REQUIRE(E.central({3}) == M3);
    REQUIRE(E.central({4}) == M4);
    REQUIRE(E.central({5}) == (P * M3).scaled(10));
    REQUIRE(E.central({6}) == (P * P * P).scaled(15) + (P * kappa4).scaled(15) + (M3 * M3).scaled(10));
  }
  // Two states at order 3: E[e1^2 e2^2] = P11 P22 + 2 P12^2 (no fourth cumulant); E[e1^3 e2^2] =
  // kappa3 terms: M3_111 P22 + 6 M3_112 P12 + 3 M3_122 P11 (Leonov-Shiryaev: set partitions into a pair and a triple).
  const FilterVariables vars(2, false, 3);
  ClosedExpectation E(vars);
  auto v = [](std::uint32_t index) { return Polynomial::variable(index); };
  const Polynomial P11 = v(vars.P(0, 0)), P12 = v(vars.P(0, 1)), P22 = v(vars.P(1, 1));
  REQUIRE(E.central({2, 2}) == P11 * P22 + (P12 * P12).scaled(2));
  REQUIRE(E.central({3, 2}) == v(vars.higher_moment({0, 0, 0})) * P22 + (v(vars.higher_moment({0, 0, 1})) * P12).scaled(6) +
                                   (v(vars.higher_moment({0, 1, 1})) * P11).scaled(3));
  // E[q(x)] through the shift x = m + e: E[x^3] = m^3 + 3 m P + M3.
  const Polynomial x1 = Polynomial::variable(0);
  const Polynomial m1 = v(vars.m(0));
  REQUIRE(E.of_state_polynomial(x1 * x1 * x1) == m1 * m1 * m1 + (m1 * P11).scaled(3) + v(vars.higher_moment({0, 0, 0})));
}

TEST_CASE("a linear model with additive noise keeps the moment filters on the Gaussian family", "[closure][unit]") {
  // From a Gaussian law (M3 = 0, M4 = 3 P^2) the Kalman-Bucy filter's law stays Gaussian, so M3 stays 0 (no drift,
  // no gain) and M4 moves as 3 P^2 does, d(3 P^2) = 6 P dP (P has no dy term there), and m and P are Kalman-Bucy's.
  const Model model = load_model_text(R"(name: linear_scalar
states: [x]
parameters: {a: 0.7, s: 0.4, r: 0.3}
drift: ["-a*x + 1"]
diffusion: [["s"]]
observation:
  A0: ["0.5"]
  A: [["2"]]
  B: [["r"]]
initial: {x0: prior, m0: [0], P0: [[1]]}
)",
                                      "linear_scalar.yaml");
  const FilterEquations kalman = derive_filter(model, FilterKind::Optimal);
  for (FilterKind kind : {FilterKind::Closure3, FilterKind::Closure4}) {
    const FilterEquations eq = derive_filter(model, kind);
    REQUIRE(eq.exactness.exact);
    EvaluationPoint point;
    point.t = GiNaC::numeric(3, 10);
    point.m = {GiNaC::numeric(-4, 5)};
    point.P = {{GiNaC::numeric(7, 10)}};
    const EvaluatedFilter closure = evaluate_at(model, eq, point), reference = evaluate_at(model, kalman, point);
    REQUIRE(closure.m_drift == reference.m_drift);
    REQUIRE(closure.gain == reference.gain);
    REQUIRE(closure.P_drift == reference.P_drift);
    REQUIRE(closure.P_gain == std::vector<std::vector<std::vector<double>>>{{{0.0}}});
    REQUIRE(closure.moment_drift[0] == 0.0);  // M3_111
    REQUIRE(closure.moment_gain[0] == std::vector<double>{0.0});
    if (kind == FilterKind::Closure4) {
      REQUIRE(closure.moment_drift[1] == Approx(6 * 0.7 * reference.P_drift[0][0]).epsilon(1e-14));
      REQUIRE(closure.moment_gain[1] == std::vector<double>{0.0});
    }
  }
}
