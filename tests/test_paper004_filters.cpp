// Paper 004's example filters (section 5) written out by hand against what pfgen derives for
// examples/paper004/: eqs 17-18 (with Phi*), 19-20 (without), the textbook EKF that eqs 21-22
// misprint, and the printed EKF run as the user filter `ekf-printed`. A = B = 1, no state noise,
// so the gain P Phi* A^T (B B^T)^-1 is P phi and the correction P^2 phi^2
// (docs/paper-discrepancies.md, rows 6-9).
#include <ginac/ginac.h>

#include <catch2/catch.hpp>
#include <string>

#include "pfgen/derivation/filter_equations.hpp"
#include "pfgen/model/yaml_model_loader.hpp"
#include "support/test_paths.hpp"

namespace {

struct Expected {
  GiNaC::ex m_drift, gain, P_drift, predicted_observation;
};

// m1, P11, md1, phi1, xs1 of a delayed scalar filter, in FilterVariables' order. Each derivation
// has its own symbols, so the expected forms are written in the symbols of the one checked.
struct Names {
  GiNaC::ex m, P, md, phi, xs;
};

template <class Build>
void check_filter(const pfgen::Model& model, const std::string& name, Build expected_of) {
  const pfgen::FilterEquations equations = pfgen::derive_named_filter(model, name);
  const auto& s = equations.variables.symbols();
  INFO("filter " << name);
  REQUIRE(equations.observation == pfgen::ObservationKind::Delayed);
  REQUIRE(s.size() == 5);
  const Expected expected = expected_of(Names{s[0], s[1], s[2], s[3], s[4]});
  CHECK((equations.m_drift.at(0).to_ex(s) - expected.m_drift).expand().is_zero());
  CHECK((equations.gain.at(0).at(0).to_ex(s) - expected.gain).expand().is_zero());
  CHECK((equations.P_drift(0, 0).to_ex(s) - expected.P_drift).expand().is_zero());
  CHECK((equations.predicted_observation.at(0).to_ex(s) - expected.predicted_observation).expand().is_zero());
}

}  // namespace

TEST_CASE("paper 004: eqs 17-20 are pfgen's delay-optimal and delay-uncorrected for dx = x^2 dt", "[paper004][unit]") {
  const pfgen::Model model = pfgen::load_model_file(pfgen_test::example("paper004/as_printed.yaml"));
  using GiNaC::pow;
  // (17) dm = (m^2 + P) dt + P Phi* (dy - m(t - 0.8) dt);  (18) dP = (4 P m - P^2 Phi*^2) dt.
  check_filter(model, "delay-optimal", [&](const Names& v) -> Expected {
    return {pow(v.m, 2) + v.P, v.P * v.phi, 4 * v.P * v.m - pow(v.P, 2) * pow(v.phi, 2), v.md};
  });
  // x* integrates the noise-free drift: dx* = x*^2 dt from m0.
  const pfgen::FilterEquations optimal = pfgen::derive_named_filter(model, "delay-optimal");
  REQUIRE(optimal.uses_x_star());
  const GiNaC::ex xs = optimal.variables.symbols().at(4);
  CHECK((optimal.x_star_drift.at(0).to_ex(optimal.variables.symbols()) - pow(xs, 2)).expand().is_zero());
  CHECK(optimal.delay == GiNaC::numeric(4, 5));
  // (19) dm1 = (m1^2 + P1) dt + P1 (dy - m1(t - 0.8) dt);  (20) dP1 = (4 P1 m1 - P1^2) dt.
  check_filter(model, "delay-uncorrected", [&](const Names& v) -> Expected {
    return {pow(v.m, 2) + v.P, v.P, 4 * v.P * v.m - pow(v.P, 2), v.md};
  });
  // The textbook EKF: 2 J P with J = 2 m, where eq 22 prints 2 P (row 6).
  check_filter(model, "delay-ekf", [&](const Names& v) -> Expected {
    return {pow(v.m, 2), v.P, 4 * v.m * v.P - pow(v.P, 2), v.md};
  });
  // (21)-(22) as printed, through `filters:`; the delayed innovation comes with the model.
  check_filter(model, "ekf-printed", [&](const Names& v) -> Expected {
    return {pow(v.m, 2), v.P, 2 * v.P - pow(v.P, 2), v.md};
  });
}

TEST_CASE("paper 004: the 0.09 x^2 variant's filters are eqs 17-22 with x^2 scaled to 0.09 x^2", "[paper004][unit]") {
  const pfgen::Model model = pfgen::load_model_file(pfgen_test::example("paper004/quadratic_009.yaml"));
  using GiNaC::pow;
  const GiNaC::ex a = GiNaC::numeric(9, 100);
  check_filter(model, "delay-optimal", [&](const Names& v) -> Expected {
    return {a * (pow(v.m, 2) + v.P), v.P * v.phi, 4 * a * v.P * v.m - pow(v.P, 2) * pow(v.phi, 2), v.md};
  });
  check_filter(model, "delay-uncorrected", [&](const Names& v) -> Expected {
    return {a * (pow(v.m, 2) + v.P), v.P, 4 * a * v.P * v.m - pow(v.P, 2), v.md};
  });
  check_filter(model, "delay-ekf", [&](const Names& v) -> Expected {
    return {a * pow(v.m, 2), v.P, 4 * a * v.m * v.P - pow(v.P, 2), v.md};
  });
  check_filter(model, "ekf-printed", [&](const Names& v) -> Expected {
    return {a * pow(v.m, 2), v.P, 2 * a * v.P - pow(v.P, 2), v.md};
  });
  check_filter(model, "ekf-printed-2p", [&](const Names& v) -> Expected {
    return {a * pow(v.m, 2), v.P, 2 * v.P - pow(v.P, 2), v.md};
  });
}
