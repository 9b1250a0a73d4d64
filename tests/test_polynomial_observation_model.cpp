// Polynomial observations through the model file and the derivation: a linear h gives every
// filter of the continuous observation byte for byte; the cubic sensor's filters print the closed
// form; eval's numbers; what the model file refuses, and that code generation refuses at once.
#include <catch2/catch.hpp>

#include "pfgen/codegen/filter_codegen.hpp"
#include "pfgen/derivation/drift_coefficients.hpp"
#include "pfgen/derivation/filter_equations.hpp"
#include "pfgen/evaluation/point_evaluator.hpp"
#include "pfgen/model/model_error.hpp"
#include "pfgen/model/model_filters.hpp"
#include "pfgen/model/yaml_model_loader.hpp"
#include "pfgen/printing/equation_report.hpp"
#include "pfgen/printing/noise_report.hpp"
#include "support/test_paths.hpp"

using namespace pfgen;

namespace {

// The model with its observation A0 + A x written as h = A0 + A x.
Model written_polynomial(const Model& model) {
  const AffineRate& linear = *model.observation.rate().affine();
  ExVector h;
  for (std::size_t r = 0; r < linear.A.size(); ++r) {
    GiNaC::ex row = linear.A0[r];
    for (std::size_t k = 0; k < model.n(); ++k) row += linear.A[r][k] * model.states[k];
    h.push_back(row);
  }
  Model out = model;
  out.observation = ObservationModel(ObservationRate::of_rows(h, linear.B, model.states), std::nullopt, std::nullopt);
  return out;
}

Model cubic_sensor() { return load_model_file(pfgen_test::example("polynomial/cubic_sensor.yaml")); }

std::string refusal(const std::string& observation) {
  const std::string text = "name: m\nstates: [x, y]\ndrift: [\"-x\", \"-y\"]\ndiffusion: [[\"1\", \"0\"], [\"0\", \"1\"]]\n"
                           "observation: " + observation + "\n";
  try {
    load_model_text(text, "m.yaml");
  } catch (const ModelError& e) {
    return e.what();
  }
  return "accepted";
}

}  // namespace

TEST_CASE("polynomial observation: a linear h prints every filter exactly as A0 + A x does",
          "[observation][polynomial][unit]") {
  for (const char* file : {"van_der_pol.yaml", "basin2006_quadratic.yaml", "basin_skliar_partial.yaml",
                                  "leqg_tracking.yaml"}) {
    const Model model = load_model_file(pfgen_test::example(file));
    const Model polynomial = written_polynomial(model);
    for (FilterKind kind : supported_filter_kinds(polynomial)) {
      INFO(file << " " << filter_kind_name(kind));
      const FilterEquations expected = derive_filter(model, kind), derived = derive_filter(polynomial, kind);
      CHECK(equations_text(polynomial, derived) == equations_text(model, expected));
      CHECK(equations_latex(polynomial, derived) == equations_latex(model, expected));
      CHECK(equations_json(polynomial, derived).dump() == equations_json(model, expected).dump());
      // A moment filter's dP has a dy term (its third moments) for a linear h too.
      CHECK(derived.P_gain.empty() == !uses_cumulant_closure(kind));
    }
  }
}

TEST_CASE("polynomial observation: the cubic sensor's filters as printed", "[observation][polynomial][unit]") {
  const Model model = cubic_sensor();
  CHECK(default_filter_names(model) == std::vector<std::string>{"optimal", "ekf", "additive", "ekf-additive"});
  const std::string optimal = equations_text(model, derive_filter(model, FilterKind::Optimal));
  CHECK_THAT(optimal, Catch::Contains("dm1 = (-a*m1) dt + K1_1 (dy1 - (m1^3 + 3*m1*P11) dt)\n"
                                      "K1_1 = 3*m1^2*P11/rho^2 + 3*P11^2/rho^2\n"
                                      "dP11 = (-2*a*P11 + sigma^2 - 9*m1^4*P11^2/rho^2 - 18*m1^2*P11^3/rho^2 - "
                                      "9*P11^4/rho^2) dt + L11_1 (dy1 - (m1^3 + 3*m1*P11) dt)\n"
                                      "L11_1 = 6*m1*P11^2/rho^2\n"));
  CHECK_THAT(optimal, Catch::Contains("exactness: approximation: for a nonlinear observation (h has degree 3)"));
  const std::string ekf = equations_text(model, derive_filter(model, FilterKind::Ekf));
  CHECK_THAT(ekf, Catch::Contains("dm1 = (-a*m1) dt + K1_1 (dy1 - m1^3 dt)\nK1_1 = 3*m1^2*P11/rho^2\n"
                                  "dP11 = (-2*a*P11 + sigma^2 - 9*m1^4*P11^2/rho^2) dt\n"));
  CHECK_THAT(equations_json(model, derive_filter(model, FilterKind::Optimal)).dump(),
             Catch::Contains("\"P_gain\": [\n    [\n      [\"6*m1*P11^2/rho^2\"]"));
}

TEST_CASE("polynomial observation: eval gives the closed form's numbers", "[observation][polynomial][unit]") {
  // m = 0.4, P = 0.3, rho = 0.5: E[h] = 0.424, K = 3 P (m^2 + P)/rho^2 = 1.656, L = 6 m P^2/rho^2 = 0.864,
  // P drift -2 P + 1/4 - 9 P^2 (m^2 + P)^2/rho^2 = -1.035584.
  const Model model = cubic_sensor();
  EvaluationPoint point;
  point.m = {GiNaC::numeric(2, 5)};
  point.P = {{GiNaC::numeric(3, 10)}};
  const EvaluatedFilter value = evaluate_at(model, derive_filter(model, FilterKind::Optimal), point);
  CHECK(value.predicted_observation == std::vector<double>{0.424});
  CHECK(value.gain[0][0] == Approx(1.656).epsilon(1e-15));
  CHECK(value.P_drift[0][0] == Approx(-1.035584).epsilon(1e-15));
  REQUIRE(value.P_gain.size() == 1);
  CHECK(value.P_gain[0][0][0] == Approx(0.864).epsilon(1e-15));
}

TEST_CASE("polynomial observation: what the model file refuses", "[observation][polynomial][unit]") {
  // Each at its line and column, with the field and the entry.
  CHECK(refusal("{h: [\"x^2\"]}") == "m.yaml:5:1: error: field 'observation.B': missing required field");
  CHECK(refusal("{h: [\"sin(x)\"], B: [[1]]}") ==
        "m.yaml:5:19: error: field 'observation.h', row 1: 'sin(x)' is not polynomial in the states (only "
        "non-negative integer powers of states are allowed; sin(x), 1/x, x^0.5 are not)");
  CHECK(refusal("{h: [\"x*y\"], A: [[1, 0]], B: [[1]]}") ==
        "m.yaml:5:27: error: field 'observation.A': a polynomial observation dy = h(x, t) dt + B dW2 has the fields "
        "h and B only (A0 + A x is h written as a linear polynomial)");
  CHECK(refusal("{h: [\"x*y\", \"y\"], B: [[1]]}") ==
        "m.yaml:5:35: error: field 'observation.B': expected 2 rows (one per observation, as in h), found 1");
  CHECK(refusal("{h: [\"x*y\"], B: [[\"x\"]]}") ==
        "m.yaml:5:32: error: field 'observation.B', row 1, column 1: 'x' must not depend on the states");
  CHECK(refusal("{h: [], B: []}") == "m.yaml:5:18: error: field 'observation.h': at least one observation is required");
  CHECK(refusal("{h: [\"x*y\"], B: [[0]]}") ==
        "m.yaml:5:31: error: field 'observation.B', row 1: row is zero at the parameter defaults and t = 0, so "
        "observation 1 has no noise and B B^T is not positive definite");
  // Not zero, but 1e-600 is 0 in double: said so, not called zero.
  CHECK(refusal("{h: [\"x*y\"], B: [[1e-300]]}") ==
        "m.yaml:5:31: error: field 'observation.B', row 1: row is too small: its squared norm is 0 in double at the "
        "parameter defaults and t = 0, so observation 1 has no noise and B B^T is not positive definite");
  CHECK(refusal("{h: [\"x*y + x^2\"], B: [[2]]}") == "accepted");
  // A large noise is positive definite: the check's tolerance must not overflow (B B^T = 1e200).
  CHECK(refusal("{h: [\"x*y\"], B: [[1e100]]}") == "accepted");
  CHECK(refusal("{h: [\"x*y\"], B: [[1e155]]}") ==
        "m.yaml:5:30: error: field 'observation.B': B B^T overflows double at the parameter values (an entry is "
        "beyond about 1.8e308): the noise is too large for the filters to compute with");
}

TEST_CASE("polynomial observation: the coefficient form refuses a nonlinear h, at the model file",
          "[observation][polynomial][unit]") {
  const Model model = cubic_sensor();
  CHECK_THROWS_WITH(extract_observation_coefficients(model),
                    Catch::EndsWith("cubic_sensor.yaml: error: field 'observation.h': the coefficient form's "
                                    "observation is linear, E + E1 x; h has degree 3"));
}

TEST_CASE("polynomial observation: the ukf sends h through its sigma points", "[observation][polynomial][unit]") {
  // In one dimension the sigma points (c = 3) match the Gaussian's moments to order 5, so for the
  // cubic sensor the ukf's E[h] = m^3 + 3 m L^2 and C = 3 m^2 L^2 + 3 L^4 are the optimal filter's
  // with L^2 = P: at a point the two give the same gain and drifts; the ukf's dP has no dy term.
  const Model model = cubic_sensor();
  CHECK(available_filter_names(model) ==
        std::vector<std::string>{"optimal", "ekf", "additive", "ekf-additive", "ukf", "closure3", "closure4"});
  const FilterEquations ukf = derive_filter(model, FilterKind::Ukf);
  CHECK(ukf.P_gain.empty());
  const std::string text = equations_text(model, ukf);
  CHECK_THAT(text, Catch::Contains("K1_1 = 3*L11^2*m1^2/rho^2 + 3*L11^4/rho^2"));
  CHECK_THAT(text, Catch::Contains("- [C (B B^T)^-1 C^T, C = sum_i w_i (X_i-m) h(X_i)^T]"));
  EvaluationPoint point;
  point.m = {GiNaC::numeric(2, 5)};
  point.P = {{GiNaC::numeric(3, 10)}};
  const EvaluatedFilter sigma = evaluate_at(model, ukf, point);
  const EvaluatedFilter gaussian = evaluate_at(model, derive_filter(model, FilterKind::Optimal), point);
  CHECK(sigma.gain[0][0] == Approx(gaussian.gain[0][0]).epsilon(1e-14));
  CHECK(sigma.m_drift[0] == Approx(gaussian.m_drift[0]).epsilon(1e-14));
  CHECK(sigma.P_drift[0][0] == Approx(gaussian.P_drift[0][0]).epsilon(1e-14));
  CHECK(sigma.predicted_observation[0] == Approx(gaussian.predicted_observation[0]).epsilon(1e-14));
  CHECK(sigma.P_gain.empty());
}
