// The `pfgen` program end to end: eval against hand-computed values, derive's
// JSON, negative numbers on the command line, and byte-identical output from
// separate processes (GiNaC's term order follows memory addresses, so only
// separate runs show an order that leaks into the output).
#include <catch2/catch.hpp>

#include <cctype>
#include <cmath>
#include <cstdlib>
#include <map>
#include <memory>
#include <regex>
#include <stdexcept>
#include <string>
#include <vector>

#include "pfgen/kinds/filter_kinds.hpp"
#include "pfgen/model/model_filters.hpp"
#include "pfgen/model/yaml_model_loader.hpp"
#include "support/cli_helpers.hpp"
#include "support/json_reader.hpp"

using namespace pfgen_test;

namespace {

// ---- running eval ----

struct Evaluated {
  std::vector<double> m_drift;
  std::vector<std::vector<double>> gain;
  std::vector<std::vector<double>> P_drift;
};

std::vector<double> numbers(const JsonValue& array) {
  REQUIRE(array.kind == JsonValue::Kind::Array);
  std::vector<double> out;
  for (const auto& item : array.items) {
    REQUIRE(item.kind == JsonValue::Kind::Number);
    out.push_back(item.number);
  }
  return out;
}

// A moment filter's eval adds dP's dy terms and its higher moments (closure3, closure4).
const std::vector<std::string> kMomentFilterKeys = {"model", "filter", "m_drift", "gain", "P_drift",
                                                    "P_gain", "moments", "moment_drift", "moment_gain"};

Evaluated eval(const std::vector<std::string>& args,
               const std::vector<std::string>& keys = {"model", "filter", "m_drift", "gain", "P_drift"}) {
  std::vector<std::string> full = {"eval"};
  full.insert(full.end(), args.begin(), args.end());
  ProcessResult r = run_pfgen(full);
  INFO("stderr: " << r.err);
  REQUIRE(r.exit_code == 0);
  CHECK(r.err.empty());
  JsonValue j = parse_json(r.out);
  REQUIRE(j.kind == JsonValue::Kind::Object);
  CHECK(j.keys() == keys);
  Evaluated e;
  e.m_drift = numbers(j["m_drift"]);
  for (const auto& row : j["gain"].items) e.gain.push_back(numbers(row));
  for (const auto& row : j["P_drift"].items) e.P_drift.push_back(numbers(row));
  return e;
}

// |a - b| <= 1e-12, with a readable message.
void check_close(double actual, double expected, const std::string& what) {
  INFO(what << ": pfgen " << actual << ", by hand " << expected);
  CHECK(std::fabs(actual - expected) <= 1e-12);
}

// Every built-in kind for continuous observations, from the registry: a new kind is covered (or
// these tests fail) at once. The sampled kinds have their own cases (test_sampled_cli.cpp).
std::vector<std::string> kinds_for(pfgen::ObservationKind observation) {
  std::vector<std::string> names;
  for (const auto& info : pfgen::filter_kinds())
    for (pfgen::ObservationKind o : info.observations)
      if (o == observation) names.push_back(info.name);
  return names;
}
// The mean-square kinds (the risk-sensitive kind needs a model with a risk: section: its own case).
std::vector<std::string> mean_square_kinds_for(pfgen::ObservationKind observation) {
  std::vector<std::string> names;
  for (const std::string& name : kinds_for(observation))
    if (!pfgen::is_risk_sensitive(*pfgen::parse_filter_kind(name))) names.push_back(name);
  return names;
}
const std::vector<std::string> kAllKinds = mean_square_kinds_for(pfgen::ObservationKind::Continuous);

// The built-in kinds a model file supports, from the registry's rules (no additive diffusion:
// fewer kinds).
std::vector<std::string> supported_kinds(const std::string& file) {
  std::vector<std::string> names;
  for (pfgen::FilterKind kind : pfgen::supported_filter_kinds(pfgen::load_model_file(example(file))))
    names.push_back(pfgen::filter_kind_name(kind));
  return names;
}

}  // namespace

TEST_CASE("eval of basin2006_quadratic at a negative m matches the hand-computed filters", "[cli][integration]") {
  const std::string model = example("basin2006_quadratic.yaml");
  const double m = -1.5, P = 0.5;
  struct Expected {
    std::string kind;
    double m_drift, gain, P_drift;
  };
  // dx = 0.1 x^2 dt + 0.1 x^2 dW1, dy = x dt + dW2 (paper 000 eqs 21-22); the
  // additive kinds use 0.1 dW1; the EKF linearises f = 0.1 x^2 at m (f' = 0.2 m).
  const std::vector<Expected> cases = {
      {"optimal", 0.1 * (m * m + P), P,
       0.4 * m * P + 0.03 * P * P + 0.06 * m * m * P + 0.01 * std::pow(m, 4) - P * P},
      {"ekf", 0.1 * m * m, P, 2 * 0.2 * m * P + 0.01 * std::pow(m, 4) - P * P},
      {"additive", 0.1 * (m * m + P), P, 0.4 * m * P + 0.01 - P * P},
      {"ekf-additive", 0.1 * m * m, P, 2 * 0.2 * m * P + 0.01 - P * P},
      // The three sigma points are exact to degree 5 in one dimension: f, (x - m) f and G have
      // degrees 2, 3 and 4, so the ukf is the optimal filter here (docs/theory.md §2.8).
      {"ukf", 0.1 * (m * m + P), P, 0.4 * m * P + 0.03 * P * P + 0.06 * m * m * P + 0.01 * std::pow(m, 4) - P * P},
  };
  // The moment filters at M3 = 0.2 (and M4 = 1): with h = x, R = 1 the gain is P, and E[f], E[(x-m) f] and
  // E[G] read E[e^3] = M3, E[e^4] = M4 (3 P^2 at order 3), E[e^5] = 10 P M3 (the fifth cumulant zero):
  //   dP = 0.2 (2 m P + M3) + 0.01 (m^4 + 6 m^2 P + 4 m M3 + M4) - P^2, dP's dy term C_2 R^-1 = M3,
  //   dM3 = 0.3 (2 m M3 + M4 - P^2) + 0.03 (4 m^3 P + 6 m^2 M3 + 4 m M4 + 10 P M3) - 3 M3 P, its dy term M4 - 3 P^2.
  struct MomentCase {
    std::string kind;
    double M4;
    std::vector<std::string> moments;
  };
  const double M3 = 0.2;
  const std::vector<MomentCase> moment_cases = {{"closure3", 3 * P * P, {"--moment", "M3_111=0.2"}},
                                                {"closure4", 1.0, {"--moment", "M3_111=0.2", "--moment", "M4_1111=1"}}};
  std::vector<std::string> covered;
  for (const auto& c : cases) covered.push_back(c.kind);
  for (const auto& c : moment_cases) covered.push_back(c.kind);
  CHECK(covered == kAllKinds);  // a kind added to the registry needs its hand-computed values here
  for (const auto& c : moment_cases) {
    INFO("filter " << c.kind);
    std::vector<std::string> args = {model, "--filter", c.kind, "--m=-1.5", "--P", "0.5"};
    args.insert(args.end(), c.moments.begin(), c.moments.end());
    Evaluated e = eval(args, kMomentFilterKeys);
    check_close(e.m_drift[0], 0.1 * (m * m + P), "m_drift");
    check_close(e.gain[0][0], P, "gain");
    check_close(e.P_drift[0][0], 0.2 * (2 * m * P + M3) + 0.01 * (std::pow(m, 4) + 6 * m * m * P + 4 * m * M3 + c.M4) - P * P,
                "P_drift");
    const JsonValue j = parse_json(run_pfgen([&] {
                                     std::vector<std::string> full = {"eval"};
                                     full.insert(full.end(), args.begin(), args.end());
                                     return full;
                                   }())
                                       .out);
    check_close(j["P_gain"].items[0].items[0].items[0].number, M3, "P_gain");
    check_close(j["moment_drift"].items[0].number,
                0.3 * (2 * m * M3 + c.M4 - P * P) +
                    0.03 * (4 * std::pow(m, 3) * P + 6 * m * m * M3 + 4 * m * c.M4 + 10 * P * M3) - 3 * M3 * P,
                "M3_111's drift");
    check_close(j["moment_gain"].items[0].items[0].number, c.M4 - 3 * P * P, "M3_111's dy term");
  }
  for (const auto& c : cases) {
    INFO("filter " << c.kind);
    Evaluated e = eval({model, "--filter", c.kind, "--m=-1.5", "--P", "0.5"});
    REQUIRE(e.m_drift.size() == 1);
    REQUIRE(e.gain.size() == 1);
    REQUIRE(e.gain[0].size() == 1);
    REQUIRE(e.P_drift.size() == 1);
    REQUIRE(e.P_drift[0].size() == 1);
    check_close(e.m_drift[0], c.m_drift, "m_drift");
    check_close(e.gain[0][0], c.gain, "gain");
    check_close(e.P_drift[0][0], c.P_drift, "P_drift");
  }
  // The optimal value itself, written out: -0.3 + 0.0075 + 0.0675 + 0.050625 - 0.25.
  Evaluated optimal = eval({model, "--filter", "optimal", "--m=-1.5", "--P", "0.5"});
  check_close(optimal.P_drift[0][0], -0.424375, "optimal P_drift");
  check_close(optimal.m_drift[0], 0.275, "optimal m_drift");
}

// The risk-sensitive kind (docs/theory.md §2.7), tests/data/risk_scalar.yaml:
//   f = -x + 0.5 x^2 + 0.2 x^3, G = 0.09, A0 = 0.3, A = 2, R = 0.25, eps = 4, M = 3.
// div f = f' = -1 + x + 0.6 x^2, grad(div f) = 1 + 1.2 x, Hess(div f) = 1.2:
//   m drift = f(m) - P (1 + 1.2 m), gain = P A / R = 8 P,
//   P drift = 2 f'(m) P + 0.09 - P^2 (A^2/R + 1.2 - 2 M/eps) = 2 f'(m) P + 0.09 - 15.7 P^2.
TEST_CASE("eval of the risk-sensitive kind matches the hand-computed filter", "[cli][integration]") {
  const std::string model = test_data_dir() + "/risk_scalar.yaml";
  const double m = -1.5, P = 0.5;
  std::vector<std::string> risk_kinds;
  for (const std::string& name : kinds_for(pfgen::ObservationKind::Continuous))
    if (pfgen::is_risk_sensitive(*pfgen::parse_filter_kind(name))) risk_kinds.push_back(name);
  CHECK(risk_kinds == std::vector<std::string>{"risk-sensitive"});  // a new one needs its case here
  Evaluated e = eval({model, "--filter", "risk-sensitive", "--m=-1.5", "--P", "0.5"});
  REQUIRE(e.m_drift.size() == 1);
  REQUIRE(e.gain.size() == 1);
  REQUIRE(e.P_drift.size() == 1);
  const double f = -m + 0.5 * m * m + 0.2 * m * m * m, df = -1 + m + 0.6 * m * m;
  check_close(e.m_drift[0], f - P * (1 + 1.2 * m), "m_drift");
  check_close(e.gain[0][0], 8 * P, "gain");
  check_close(e.P_drift[0][0], 2 * df * P + 0.09 - 15.7 * P * P, "P_drift");
  // Written out: 2.35 and -4.985.
  check_close(e.m_drift[0], 2.35, "m_drift by hand");
  check_close(e.P_drift[0][0], -4.985, "P_drift by hand");
  // derive's JSON names the criterion; its text says what m is.
  ProcessResult json = run_pfgen({"derive", model, "--filter", "risk-sensitive", "--format", "json"});
  REQUIRE(json.exit_code == 0);
  const JsonValue j = parse_json(json.out);
  REQUIRE(j.has("criterion"));
  CHECK(j["criterion"]["epsilon"].text == "4");
  CHECK(j["criterion"]["weight"][0][0].text == "3");
  ProcessResult text = run_pfgen({"derive", model, "--filter", "risk-sensitive"});
  REQUIRE(text.exit_code == 0);
  CHECK(text.out.find("m1 = risk-sensitive estimate of x (the centre of the information state, not E[x])") !=
        std::string::npos);
  CHECK(text.out.find("dP11 = ") != std::string::npos);
  // Byte-identical run after run, also where coefficients are rational functions of parameters
  // (brought over one denominator by GiNaC's normal(), the coefficient was (2*r^2 - eps)/(eps*r^2)
  // in some runs and -(-2*r^2 + eps)/(eps*r^2) in others; algebra/coefficient.cpp).
  const std::string leqg = example("leqg_tracking.yaml");
  const std::string first = run_pfgen({"derive", leqg, "--filter", "risk-sensitive"}).out;
  CHECK(first.find("dP11 = (2*P12 + (-1/r^2 + 2/eps)*P11^2 + 2*P12^2/eps) dt") != std::string::npos);
  for (int k = 0; k < 6; ++k) CHECK(run_pfgen({"derive", leqg, "--filter", "risk-sensitive"}).out == first);
  // The mean-square kinds' reports of the same model have no criterion.
  ProcessResult optimal = run_pfgen({"derive", model, "--filter", "optimal", "--format", "json"});
  REQUIRE(optimal.exit_code == 0);
  CHECK(!parse_json(optimal.out).has("criterion"));
}

// Delayed observations (docs/theory.md §2.6), tests/data/delayed_scalar.yaml:
//   dx = (0.5 x^2 - x) dt + 0.2 x dW1, dy = (0.3 + 2 x(t - 0.5)) dt + 0.5 dW2, so R = 0.25.
// Gaussian closure: E[f] = 0.5 (m^2 + P) - m, E[(x-m) f] = m P - P, E[g^2] = 0.04 (m^2 + P);
// delay-optimal: gain P phi A / R = 8 P phi, correction 16 P^2 phi^2; the others: 8 P and 16 P^2;
// delay-ekf: f(m), J = m - 1, g(m)^2 = 0.04 m^2. The innovation compares dy with 0.3 + 2 md.
TEST_CASE("eval of a delayed model matches the hand-computed filters and delayed inputs", "[cli][integration]") {
  const std::string model = test_data_dir() + "/delayed_scalar.yaml";
  const double m = -1.5, P = 0.5, md = 0.25;
  struct Expected {
    std::string kind;
    double m_drift, gain, P_drift;
  };
  // At t = 1 >= h with x* = 3 and x*(t - h) = -0.75: phi = -0.25.
  const double phi = -0.25;
  const double moments = 2 * (m * P - P) + 0.04 * (m * m + P);
  const std::vector<Expected> cases = {
      {"delay-optimal", 0.5 * (m * m + P) - m, 8 * P * phi, moments - 16 * P * P * phi * phi},
      {"delay-uncorrected", 0.5 * (m * m + P) - m, 8 * P, moments - 16 * P * P},
      {"delay-ekf", 0.5 * m * m - m, 8 * P, 2 * (m - 1) * P + 0.04 * m * m - 16 * P * P},
  };
  std::vector<std::string> covered;
  for (const auto& c : cases) covered.push_back(c.kind);
  CHECK(covered == kinds_for(pfgen::ObservationKind::Delayed));  // a new delayed kind needs its case here
  auto run = [&](const std::string& kind, const std::vector<std::string>& extra) {
    std::vector<std::string> args = {"eval", model, "--filter", kind, "--m=-1.5", "--P=0.5"};
    args.insert(args.end(), extra.begin(), extra.end());
    ProcessResult r = run_pfgen(args);
    INFO("stderr: " << r.err);
    REQUIRE(r.exit_code == 0);
    CHECK(r.err.empty());
    JsonValue j = parse_json(r.out);
    REQUIRE(j.kind == JsonValue::Kind::Object);
    return j;
  };
  for (const auto& c : cases) {
    INFO("filter " << c.kind);
    const bool x_star = c.kind == "delay-optimal";
    const std::vector<std::string> extra =
        x_star ? std::vector<std::string>{"--t=1", "--m-delayed=0.25", "--x-star=3", "--x-star-delayed=-0.75"}
               : std::vector<std::string>{"--t=1", "--m-delayed=0.25"};
    JsonValue j = run(c.kind, extra);
    std::vector<std::string> keys = {"model", "filter", "m_drift", "gain", "P_drift", "predicted_observation",
                                     "delayed_inputs"};
    if (x_star) keys.push_back("x_star_drift");
    CHECK(j.keys() == keys);
    check_close(numbers(j["m_drift"])[0], c.m_drift, "m_drift");
    check_close(numbers(j["gain"].items.at(0))[0], c.gain, "gain");
    check_close(numbers(j["P_drift"].items.at(0))[0], c.P_drift, "P_drift");
    check_close(numbers(j["predicted_observation"])[0], 0.3 + 2 * md, "predicted_observation");
    const JsonValue& inputs = j["delayed_inputs"];
    CHECK(inputs.keys() == (x_star ? std::vector<std::string>{"m_delayed", "x_star", "phi"}
                                   : std::vector<std::string>{"m_delayed"}));
    check_close(numbers(inputs["m_delayed"])[0], md, "m_delayed");
    if (x_star) {
      check_close(numbers(inputs["x_star"])[0], 3, "x_star");
      check_close(numbers(inputs["phi"])[0], phi, "phi");
      check_close(numbers(j["x_star_drift"])[0], 0.5 * 9 - 3, "x_star_drift");
    }
  }
  const double optimal_moments = moments;
  {  // phi is 0 for t < h and where x*(t) = 0, and --phi is used as given
    auto gain_and_P = [&](const std::vector<std::string>& extra, double expected_phi) {
      INFO("delay-optimal with " << extra.size() << " delayed options, phi " << expected_phi);
      JsonValue j = run("delay-optimal", extra);
      check_close(numbers(j["delayed_inputs"]["phi"])[0], expected_phi, "phi");
      check_close(numbers(j["gain"].items.at(0))[0], 8 * P * expected_phi, "gain");
      check_close(numbers(j["P_drift"].items.at(0))[0], optimal_moments - 16 * P * P * expected_phi * expected_phi,
                  "P_drift");
    };
    gain_and_P({"--t=0.25", "--x-star=3", "--x-star-delayed=-0.75"}, 0);  // t < h = 0.5
    gain_and_P({"--t=0.5", "--x-star=3", "--x-star-delayed=-0.75"}, -0.25);  // t = h: the ratio
    gain_and_P({"--t=1", "--x-star=0", "--x-star-delayed=-0.75"}, 0);
    gain_and_P({"--t=0.25", "--phi=0.5"}, 0.5);  // given phi: no rule applied
  }
  {  // without delayed options: md = m, x* = m, x*(t - h) = x*, so phi = 1 from t = h on
    JsonValue j = run("delay-optimal", {"--t=1"});
    check_close(numbers(j["predicted_observation"])[0], 0.3 + 2 * m, "predicted_observation");
    check_close(numbers(j["delayed_inputs"]["m_delayed"])[0], m, "m_delayed");
    check_close(numbers(j["delayed_inputs"]["x_star"])[0], m, "x_star");
    check_close(numbers(j["delayed_inputs"]["phi"])[0], 1, "phi");
    check_close(numbers(j["x_star_drift"])[0], 0.5 * m * m - m, "x_star_drift");
    check_close(numbers(j["gain"].items.at(0))[0], 8 * P, "gain");
    // At the default t = 0 < h, phi is 0.
    check_close(numbers(run("delay-optimal", {})["delayed_inputs"]["phi"])[0], 0, "phi at t = 0");
  }
  {  // the model's own filter: its equations as given, with the delayed innovation
    JsonValue j = run("mine", {"--m-delayed=0.25"});
    CHECK(j.keys() == std::vector<std::string>{"model", "filter", "m_drift", "gain", "P_drift", "predicted_observation",
                                               "delayed_inputs"});
    check_close(numbers(j["m_drift"])[0], -m, "m_drift");
    check_close(numbers(j["gain"].items.at(0))[0], 2 * P, "gain");
    check_close(numbers(j["P_drift"].items.at(0))[0], 0.04 - 2 * P, "P_drift");
    check_close(numbers(j["predicted_observation"])[0], 0.3 + 2 * md, "predicted_observation");
  }
}

// The whole output of eval, byte for byte, against files written by the program before the sampled
// kinds came (tests/data/eval/): every key, every digit and the order of the keys. The sampled kinds
// share the evaluator, and must leave the continuous kinds' output (the gain above all) as it was.
TEST_CASE("eval of the continuous examples is byte-identical to its recorded output", "[cli][integration]") {
  struct Case {
    std::string file, filter;
    std::vector<std::string> point;
  };
  std::vector<Case> cases;
  for (const std::string filter : {"optimal", "ekf", "additive", "ekf-additive", "ekf-printed"})
    cases.push_back({"basin2006_quadratic", filter, {"--m=-1.5", "--P", "0.5", "--t=2"}});
  for (const std::string filter : {"optimal", "ekf", "ekf-printed"})
    cases.push_back({"basin_skliar_partial", filter, {"--m=-1.5,2", "--P", "0.5,0.25;0.25,3"}});
  for (const auto& c : cases) {
    INFO(c.file << " --filter " << c.filter);
    std::vector<std::string> args = {"eval", example(c.file + ".yaml"), "--filter", c.filter};
    args.insert(args.end(), c.point.begin(), c.point.end());
    ProcessResult r = run_pfgen(args);
    INFO("stderr: " << r.err);
    REQUIRE(r.exit_code == 0);
    const std::string expected = read_file(test_data_dir() + "/eval/" + c.file + "_" + c.filter + ".json");
    REQUIRE(!expected.empty());
    CHECK(r.out == expected);
    CHECK(r.out.find("\"gain\"") != std::string::npos);
  }
}

TEST_CASE("eval of the sampled examples matches the hand-computed prediction and update", "[cli][integration]") {
  // Paper 003's example 1: dx = -0.5 x dt + 6 dW + 0.1 x^gamma dS, y_k = 10 x(t_k) + v_k.
  // gamma = 1: g g^T = 36 + 0.01 x^2; gamma = 0.5: 36 + 0.01 x. At (m, P):
  //   m drift -0.5 m; P drift 2 (-0.5) P + E[g g^T] (at the mean for cd-ekf);
  //   cd-euler's dt^2 term Cov(f) = 0.25 P; S = 100 P + 1, K = 10 P / S.
  // The moment filters (gamma = 1): m and P as cd-optimal's (E[g g^T] = 36 + 0.01 (m^2 + P) needs no M3), and
  //   dM3 = 3 (E[e^2 f] - P E[f]) + 3 E[e G] = -1.47 M3 + 0.06 m P,
  //   dM4 = 4 (E[e^3 f] - M3 E[f]) + 6 E[e^2 G] = -1.94 M4 + 216 P + 0.06 m^2 P + 0.12 m M3;
  //   after the update, A = 1 - 10 K = 1/201, U = A^2 P, Q = K^2: M3 A^3 and M4 A^4 + 6 U Q + 3 Q^2.
  struct Expected {
    std::string file, kind, m, P;
    double m_drift, P_drift, P_dt2, S, K;  // P_dt2 < 0: no such term
    std::vector<std::string> moments = {};   // --moment options
    std::vector<double> moment_drift = {}, moments_after_update = {};
  };
  const double A = 1.0 / 201, Q = 400.0 / 40401, U = 2.0 / 40401;
  const std::vector<Expected> cases = {
      {"allahyani_date_example1_gamma1.yaml", "cd-optimal", "0.5", "2", -0.25, -2 + 36 + 0.01 * (0.25 + 2), -1, 201, 20.0 / 201},
      {"allahyani_date_example1_gamma1.yaml", "cd-ekf", "0.5", "2", -0.25, -2 + 36 + 0.01 * 0.25, -1, 201, 20.0 / 201},
      {"allahyani_date_example1_gamma1.yaml", "cd-euler", "0.5", "2", -0.25, 34.0225, 0.5, 201, 20.0 / 201},
      {"allahyani_date_example1_gamma1.yaml", "cd-closure3", "0.5", "2", -0.25, 34.0225, -1, 201, 20.0 / 201,
       {"--moment", "M3_111=0.3"}, {-1.47 * 0.3 + 0.06}, {0.3 * A * A * A}},
      {"allahyani_date_example1_gamma1.yaml", "cd-closure4", "0.5", "2", -0.25, 34.0225, -1, 201, 20.0 / 201,
       {"--moment", "M3_111=0.3", "--moment", "M4_1111=10"},
       {-1.47 * 0.3 + 0.06, -1.94 * 10 + 432 + 0.03 + 0.12 * 0.5 * 0.3},
       {0.3 * A * A * A, 10 * A * A * A * A + 6 * U * Q + 3 * Q * Q}},
      {"allahyani_date_example1_gamma05.yaml", "cd-optimal", "-1.5", "0.5", 0.75, -0.5 + 36 - 0.015, -1, 51, 5.0 / 51},
      {"allahyani_date_example1_gamma05.yaml", "cd-ekf", "-1.5", "0.5", 0.75, 35.485, -1, 51, 5.0 / 51},
      {"allahyani_date_example1_gamma05.yaml", "cd-euler", "-1.5", "0.5", 0.75, 35.485, 0.125, 51, 5.0 / 51},
  };
  std::vector<std::string> covered;
  for (const auto& c : cases)
    if (c.file == cases[0].file) covered.push_back(c.kind);
  CHECK(covered == kinds_for(pfgen::ObservationKind::Sampled));  // a new sampled kind needs its case here
  for (const auto& c : cases) {
    INFO(c.file << " --filter " << c.kind);
    std::vector<std::string> arguments = {"eval", example(c.file), "--filter", c.kind, "--m=" + c.m, "--P=" + c.P};
    arguments.insert(arguments.end(), c.moments.begin(), c.moments.end());
    ProcessResult r = run_pfgen(arguments);
    INFO("stderr: " << r.err);
    REQUIRE(r.exit_code == 0);
    CHECK(r.err.empty());
    JsonValue j = parse_json(r.out);
    REQUIRE(j.kind == JsonValue::Kind::Object);
    if (c.moment_drift.empty()) {
      CHECK(j.keys() == std::vector<std::string>{"model", "filter", "prediction", "update"});
    } else {
      CHECK(j.keys() == std::vector<std::string>{"model", "filter", "prediction", "update", "moments", "moment_drift",
                                                 "P_after_update", "moments_after_update"});
      const std::vector<double> drift = numbers(j["moment_drift"]), after = numbers(j["moments_after_update"]);
      REQUIRE(drift.size() == c.moment_drift.size());
      REQUIRE(after.size() == c.moments_after_update.size());
      for (std::size_t q = 0; q < drift.size(); ++q) {
        check_close(drift[q], c.moment_drift[q], "moment_drift");
        check_close(after[q], c.moments_after_update[q], "moments_after_update");
      }
    }
    const bool euler = c.P_dt2 >= 0;
    CHECK(j["prediction"].keys() == (euler ? std::vector<std::string>{"m_drift", "P_drift", "P_dt2"}
                                           : std::vector<std::string>{"m_drift", "P_drift"}));
    CHECK(j["update"].keys() == std::vector<std::string>{"innovation_covariance", "gain"});
    check_close(numbers(j["prediction"]["m_drift"])[0], c.m_drift, "m_drift");
    check_close(numbers(j["prediction"]["P_drift"].items.at(0))[0], c.P_drift, "P_drift");
    if (euler) check_close(numbers(j["prediction"]["P_dt2"].items.at(0))[0], c.P_dt2, "P_dt2");
    check_close(numbers(j["update"]["innovation_covariance"].items.at(0))[0], c.S, "S");
    check_close(numbers(j["update"]["gain"].items.at(0))[0], c.K, "K");
  }
}

TEST_CASE("eval accepts negative numbers in every spelling of the options", "[cli][integration]") {
  const std::string model = example("basin2006_quadratic.yaml");
  ProcessResult joined = run_pfgen({"eval", model, "--filter", "optimal", "--m=-1.5", "--P=0.5", "--t=-2"});
  ProcessResult separate = run_pfgen({"eval", model, "--filter", "optimal", "--m", "-1.5", "--P", "0.5", "--t", "-2"});
  INFO(joined.err << separate.err);
  REQUIRE(joined.exit_code == 0);
  REQUIRE(separate.exit_code == 0);
  CHECK(joined.out == separate.out);
  // -1.5, -15e-1 and -3/2 written as a decimal are the same exact number.
  ProcessResult exponent = run_pfgen({"eval", model, "--filter", "optimal", "--m=-15e-1", "--P=5e-1"});
  REQUIRE(exponent.exit_code == 0);
  CHECK(exponent.out == joined.out);
  CHECK(parse_json(joined.out)["m_drift"][0].number == Approx(0.275).margin(1e-15));
}

TEST_CASE("eval of basin_skliar_partial with negative entries matches the hand-computed filter", "[cli][integration]") {
  // dx1 = 0.1 (x1^2 + x2) dt, dx2 = 0.1 x2 dt, dy = x1 dt + dW2 (paper 001).
  const double m1 = -1.5, m2 = 2, P11 = 0.5, P12 = -0.2, P22 = 0.3;
  Evaluated e = eval({example("basin_skliar_partial.yaml"), "--filter", "optimal", "--m=-1.5,2",
                      "--P=0.5,-0.2;-0.2,0.3"});
  REQUIRE(e.m_drift.size() == 2);
  REQUIRE(e.gain.size() == 2);
  REQUIRE(e.P_drift.size() == 2);
  for (const auto& row : e.gain) REQUIRE(row.size() == 1);
  for (const auto& row : e.P_drift) REQUIRE(row.size() == 2);
  check_close(e.m_drift[0], 0.1 * (m1 * m1 + P11 + m2), "m_drift[1]");
  check_close(e.m_drift[1], 0.1 * m2, "m_drift[2]");
  check_close(e.gain[0][0], P11, "gain[1][1]");
  check_close(e.gain[1][0], P12, "gain[2][1]");
  // E[(x-m) f^T] + E[f (x-m)^T] - P A^T A P, A = (1 0).
  const double dP11 = 2 * (0.2 * m1 * P11 + 0.1 * P12) - P11 * P11;
  const double dP12 = 0.2 * m1 * P12 + 0.1 * P22 + 0.1 * P12 - P11 * P12;
  const double dP22 = 2 * 0.1 * P22 - P12 * P12;
  check_close(e.P_drift[0][0], dP11, "P_drift[1][1]");
  check_close(e.P_drift[0][1], dP12, "P_drift[1][2]");
  check_close(e.P_drift[1][0], dP12, "P_drift[2][1]");
  check_close(e.P_drift[1][1], dP22, "P_drift[2][2]");
  check_close(e.P_drift[0][1], 0.17, "P_drift[1][2] written out");
}

TEST_CASE("eval --set overrides parameter defaults, negative values included", "[cli][integration]") {
  TempDir dir;
  // Kalman-Bucy: dx = a x dt + s dW1, dy = c x dt + dW2.
  write_file(dir.file("kb.yaml"),
             "name: kalman_bucy_scalar\n"
             "states: [x]\n"
             "parameters: {a: -1, s: 0.5, c: 2}\n"
             "drift: [\"a*x\"]\n"
             "diffusion: [[\"s\"]]\n"
             "observation:\n"
             "  A: [[\"c\"]]\n"
             "  B: [[\"1\"]]\n");
  const double m = -0.75, P = 0.4;
  auto check = [&](const Evaluated& e, double a, double s, double c) {
    check_close(e.m_drift[0], a * m, "m_drift");
    check_close(e.gain[0][0], P * c, "gain");
    check_close(e.P_drift[0][0], 2 * a * P + s * s - c * c * P * P, "P_drift");
  };
  check(eval({dir.file("kb.yaml"), "--filter", "optimal", "--m=-0.75", "--P=0.4"}), -1, 0.5, 2);
  check(eval({dir.file("kb.yaml"), "--filter", "optimal", "--m=-0.75", "--P=0.4", "--set", "a=-0.25", "--set",
              "c=-3"}),
        -0.25, 0.5, -3);
  check(eval({dir.file("kb.yaml"), "--filter", "ekf", "--m=-0.75", "--P=0.4", "--set=s=1.5"}), -1, 1.5, 2);
}

TEST_CASE("derive --format json is a JSON object with the documented keys", "[cli][integration]") {
  struct Case {
    std::string file;
    std::vector<std::string> kinds;
    std::size_t n, p;
  };
  for (const auto& c : {Case{"basin2006_quadratic.yaml", kAllKinds, 1, 1},
                        Case{"basin_skliar_partial.yaml", supported_kinds("basin_skliar_partial.yaml"), 2, 1}}) {
    for (const auto& kind : c.kinds) {
      INFO(c.file << " --filter " << kind);
      ProcessResult r = run_pfgen({"derive", example(c.file), "--filter", kind, "--format", "json"});
      INFO("stderr: " << r.err);
      REQUIRE(r.exit_code == 0);
      CHECK(r.err.empty());
      JsonValue j = parse_json(r.out);
      REQUIRE(j.kind == JsonValue::Kind::Object);
      for (const std::string key : {"model", "filter", "description", "exactness", "variables", "m_drift", "gain",
                                    "predicted_observation", "P_drift"})
        CHECK(j.has(key));
      CHECK(j["model"].text == c.file.substr(0, c.file.size() - 5));
      CHECK(j["filter"].text == kind);
      CHECK(j["exactness"]["exact"].kind == JsonValue::Kind::Boolean);
      // A moment filter's central moments above P follow m and P.
      CHECK(j["variables"].items.size() == c.n + c.n * (c.n + 1) / 2 + (j.has("moments") ? j["moments"].items.size() : 0));
      REQUIRE(j["m_drift"].items.size() == c.n);
      for (const auto& entry : j["m_drift"].items) {
        CHECK(entry.kind == JsonValue::Kind::String);
        CHECK(!entry.text.empty());
      }
      REQUIRE(j["gain"].items.size() == c.n);
      for (const auto& row : j["gain"].items) CHECK(row.items.size() == c.p);
      REQUIRE(j["P_drift"].items.size() == c.n);
      for (std::size_t i = 0; i < c.n; ++i) {
        REQUIRE(j["P_drift"][i].items.size() == c.n);
        for (std::size_t k = 0; k < c.n; ++k) CHECK(j["P_drift"][i][k].text == j["P_drift"][k][i].text);
      }
      CHECK(j["predicted_observation"].items.size() == c.p);
    }
  }
  // The paper 000 optimal filter, as the JSON spells it.
  JsonValue j = parse_json(run_pfgen({"derive", example("basin2006_quadratic.yaml"), "--format", "json"}).out);
  CHECK(j["m_drift"][0].text == "0.1*m1^2 + 0.1*P11");
  CHECK(j["gain"][0][0].text == "P11");
  CHECK(j["exactness"]["exact"].boolean);
}

// The delayed report's additions (docs/theory.md §2.6), on tests/data/delayed_scalar.yaml: the delay,
// the observation of x(t-h), what md1 means, and for delay-optimal phi1's definition and x*'s
// equation; the comparators have neither phi nor xs.
TEST_CASE("derive of a delayed model shows h, m(t-h) and, for delay-optimal, Phi* and the x* equation",
          "[cli][integration]") {
  const std::string model = test_data_dir() + "/delayed_scalar.yaml";
  auto derive = [&](const std::string& kind, const std::string& format) {
    ProcessResult r = run_pfgen({"derive", model, "--filter", kind, "--format", format});
    INFO("stderr: " << r.err);
    REQUIRE(r.exit_code == 0);
    CHECK(r.err.empty());
    return r.out;
  };
  for (const std::string kind : {"delay-optimal", "delay-uncorrected", "delay-ekf"}) {
    INFO("filter " << kind);
    const bool x_star = kind == "delay-optimal";
    const std::string text = derive(kind, "text");
    CHECK(text.find("observation: delayed by h = 0.5, dy = (A0 + A x(t-h)) dt + B dW2") != std::string::npos);
    CHECK(text.find("delayed inputs: md1 = m1(t-h), the filter's own estimate h earlier (m0 for t < h)\n") !=
          std::string::npos);
    CHECK(text.find("(dy1 - (2*md1 + 0.3) dt)") != std::string::npos);
    CHECK((text.find("phi1 = Phi*_11") != std::string::npos || text.find("Phi* = diag(phi1)") != std::string::npos) ==
          x_star);
    CHECK((text.find("[P Phi* A^T (B B^T)^-1 A Phi* P]") != std::string::npos) == x_star);
    const std::string x_star_line = "dxs1 = (0.5*xs1^2 - xs1) dt\n";
    CHECK((text.size() >= x_star_line.size() &&
           text.compare(text.size() - x_star_line.size(), x_star_line.size(), x_star_line) == 0) == x_star);
    CHECK((text.find("xs1") != std::string::npos) == x_star);

    JsonValue j = parse_json(derive(kind, "json"));
    std::vector<std::string> keys = {"model", "filter", "description", "exactness", "variables", "m_drift", "gain",
                                     "predicted_observation", "P_drift", "delay", "delayed_variables"};
    if (x_star) keys.push_back("x_star_drift");
    CHECK(j.keys() == keys);
    CHECK(j["delay"].text == "0.5");
    CHECK(j["variables"].items.size() == 2);  // m1, P11: the state of the filter
    CHECK(j["predicted_observation"][0].text == "2*md1 + 0.3");
    CHECK(j["delayed_variables"].keys() ==
          (x_star ? std::vector<std::string>{"md1", "phi1", "xs1"} : std::vector<std::string>{"md1"}));
    CHECK(j["delayed_variables"]["md1"].text == "m1(t-h), and m1(0) for t < h");
    if (x_star) {
      CHECK(j["delayed_variables"]["phi1"].text == "xs1(t-h)/xs1(t) for t >= h, 0 where xs1(t) = 0, and 0 for t < h");
      CHECK(j["x_star_drift"][0].text == "0.5*xs1^2 - xs1");
      CHECK(j["gain"][0][0].text == "8*P11*phi1");
    }

    const std::string latex = derive(kind, "latex");
    CHECK(latex.find("\\paragraph{Delayed observation.} $dy = (A_0 + A x(t-h))\\,dt + B\\,dW_2$ with $h = 0.5$") !=
          std::string::npos);
    CHECK(latex.find("{m_{1}(t-h)}") != std::string::npos);
    CHECK((latex.find("\\frac{d{x^*_{1}}}{dt} &= 0.5\\,{x^*_{1}}^{2} - {x^*_{1}}") != std::string::npos) == x_star);
    CHECK((latex.find("{\\Phi^*_{1}}^{2}") != std::string::npos) == x_star);
  }
}

TEST_CASE("derive, latex and eval are byte-identical across separate processes", "[cli][determinism][integration]") {
  struct Case {
    std::string file;
    std::vector<std::string> kinds;
    std::string m, P;
  };
  const std::vector<Case> cases = {
      {"basin2006_quadratic.yaml", kAllKinds, "--m=-1.5", "--P=0.5"},
      {"basin_skliar_partial.yaml", supported_kinds("basin_skliar_partial.yaml"), "--m=-1.5,2", "--P=0.5,-0.2;-0.2,0.3"},
      {"allahyani_date_example1_gamma1.yaml", supported_kinds("allahyani_date_example1_gamma1.yaml"), "--m=-1.5", "--P=0.5"},
      {"allahyani_date_example1_gamma05.yaml", supported_kinds("allahyani_date_example1_gamma05.yaml"), "--m=-1.5", "--P=0.5"},
      {"delay_linear.yaml", supported_kinds("delay_linear.yaml"), "--m=-1.5", "--P=0.5"},
  };
  auto same_three_times = [](const std::vector<std::string>& args) {
    std::vector<ProcessResult> runs;
    for (int k = 0; k < 3; ++k) runs.push_back(run_pfgen(args));
    INFO("stderr: " << runs[0].err);
    REQUIRE(runs[0].exit_code == 0);
    CHECK(!runs[0].out.empty());
    for (int k = 1; k < 3; ++k) {
      CHECK(runs[k].exit_code == 0);
      CHECK(runs[k].out == runs[0].out);
      CHECK(runs[k].err == runs[0].err);
    }
  };
  for (const auto& c : cases) {
    const std::string model = example(c.file);
    for (const auto& kind : c.kinds) {
      for (const std::string format : {"text", "latex", "json"}) {
        INFO("derive " << c.file << " --filter " << kind << " --format " << format);
        same_three_times({"derive", model, "--filter", kind, "--format", format});
      }
      INFO("eval " << c.file << " --filter " << kind);
      same_three_times({"eval", model, "--filter", kind, c.m, c.P});
    }
    INFO("latex " << c.file);
    TempDir dir;
    std::vector<std::string> documents;
    for (int k = 0; k < 3; ++k) {
      const std::string out = dir.file("run" + std::to_string(k) + ".tex");
      ProcessResult r = run_pfgen({"latex", model, "-o", out});
      INFO("stderr: " << r.err);
      REQUIRE(r.exit_code == 0);
      CHECK(r.out.empty());
      CHECK(r.err.empty());
      documents.push_back(read_file(out));
    }
    CHECK(!documents[0].empty());
    CHECK(documents[1] == documents[0]);
    CHECK(documents[2] == documents[0]);
    // Only the three documents: no temporary file left behind.
    CHECK(dir.entries() == std::vector<std::string>{"run0.tex", "run1.tex", "run2.tex"});
  }
}

TEST_CASE("latex --filter writes the requested filters only, and overwrites atomically", "[cli][integration]") {
  TempDir dir;
  const std::string out = dir.file("doc.tex");
  write_file(out, "old contents\n");
  ProcessResult r = run_pfgen({"latex", example("basin2006_quadratic.yaml"), "--filter", "ekf,additive", "-o", out});
  INFO("stderr: " << r.err);
  REQUIRE(r.exit_code == 0);
  const std::string tex = read_file(out);
  CHECK(tex.find("old contents") == std::string::npos);
  CHECK(tex.find("\\section*{Filter \\texttt{ekf}}") != std::string::npos);
  CHECK(tex.find("\\section*{Filter \\texttt{additive}}") != std::string::npos);
  CHECK(tex.find("\\section*{Filter \\texttt{optimal}}") == std::string::npos);
  CHECK(tex.find("\\section*{Filter \\texttt{ekf-additive}}") == std::string::npos);
  CHECK(dir.entries() == std::vector<std::string>{"doc.tex"});
  // A failing run leaves the previous document untouched.
  ProcessResult bad = run_pfgen({"latex", test_data_dir() + "/bad/nonpoly_sin.yaml", "-o", out});
  CHECK(bad.exit_code != 0);
  CHECK(read_file(out) == tex);
  CHECK(dir.entries() == std::vector<std::string>{"doc.tex"});
  // The document is LaTeX source; an output named .pdf is refused before anything is written.
  ProcessResult pdf = run_pfgen({"latex", example("basin2006_quadratic.yaml"), "-o", out + ".pdf"});
  CHECK(pdf.exit_code == 1);
  CHECK(pdf.err.find("must end in .tex") != std::string::npos);
  CHECK_FALSE(std::filesystem::exists(out + ".pdf"));
}

TEST_CASE("derive --timing writes the phases' seconds and changes nothing else", "[cli][integration]") {
  TempDir dir;
  const std::string model = example("basin2006_quadratic.yaml");
  for (const std::string& extra : {std::string(""), std::string("--coefficients")}) {
    std::vector<std::string> plain{"derive", model, "--format", "json"};
    if (!extra.empty()) plain.push_back(extra);
    std::vector<std::string> timed = plain;
    timed.insert(timed.end(), {"--timing", dir.file("t.json")});
    ProcessResult a = run_pfgen(plain);
    ProcessResult b = run_pfgen(timed);
    REQUIRE(a.exit_code == 0);
    REQUIRE(b.exit_code == 0);
    CHECK(a.out == b.out);
    CHECK(b.err.empty());
    const std::string timing = read_file(dir.file("t.json"));
    INFO(timing);
    // {"read_seconds": x, "derive_seconds": y, "print_seconds": z}, each a non-negative number.
    CHECK(std::regex_match(timing, std::regex(R"(\{"read_seconds": [0-9.e+-]+, "derive_seconds": [0-9.e+-]+, )"
                                              R"("print_seconds": [0-9.e+-]+\}\n)")));
    CHECK(timing.find(": -") == std::string::npos);
  }
  // Refused before any work: nothing on stdout, exit non-zero, the option named.
  for (const auto& [path, why] : std::vector<std::pair<std::string, std::string>>{
           {dir.path(), "is a directory"}, {dir.file("none/t.json"), "does not exist"}, {model, "the model file"}}) {
    ProcessResult r = run_pfgen({"derive", model, "--timing", path});
    INFO(r.err);
    CHECK(r.exit_code != 0);
    CHECK(r.out.empty());
    CHECK(r.err.find(why) != std::string::npos);
  }
}

// Messages name what is wrong, in one line of reasonable length.
TEST_CASE("option values no double holds, and filters a model does not offer, are named in one short line",
          "[cli][integration]") {
  const std::string quadratic = example("basin2006_quadratic.yaml");
  TempDir dir;
  const std::string undelayed = dir.file("delay0.yaml");
  write_file(undelayed, "name: d0\nstates: [x]\ndrift: [\"-x\"]\ndiffusion: [[\"1\"]]\n"
                        "observation: {delay: 0, A: [[\"1\"]], B: [[\"1\"]]}\n");
  const std::string stratonovich = dir.file("strat.yaml");
  write_file(stratonovich, "name: strat\nnoise: stratonovich\nstates: [x]\ndrift: [\"-x\"]\n"
                           "diffusion: [[\"0.1*x^3\"]]\nobservation: {A: [[\"1\"]], B: [[\"1\"]]}\n");
  const struct {
    std::vector<std::string> args;
    std::string message;
  } cases[] = {
      {{"eval", example("delay_linear.yaml"), "--filter", "delay-optimal", "--m=1", "--P", "1", "--phi", "1e400"},
       "--phi: '1e400' is beyond the largest double"},
      {{"eval", quadratic, "--filter", "optimal", "--m=1e-400", "--P", "1"}, "--m: '1e-400' is below the smallest"},
      // An exponent too long to read exactly is out of range too, not "not a number".
      {{"eval", quadratic, "--filter", "closure4", "--m=1", "--P", "1", "--moment", "M4_1111=1e5000000000000"},
       "--moment: '1e5000000000000' is beyond the largest double"},
      {{"eval", quadratic, "--filter", "optimal", "--m=-2.5E-123456", "--P", "1"},
       "--m: '-2.5E-123456' is below the smallest normal double"},
      {{"simulate", quadratic, "--risk-epsilon", "1e-9999"}, "--risk-epsilon: '1e-9999' is outside the range of a double"},
      {{"simulate", quadratic, "--T", "1e400"}, "--T: '1e400' is outside the range of a double"},
      {{"simulate", quadratic, "--risk-epsilon", std::string(10000, '9')}, "...' (10000 characters) is outside"},
      {{"eval", quadratic, "--filter", "optimal", "--m=1", "--P", "1", "--set", std::string(5000, 'q') + "=1"},
       "has no parameter 'qqq"},
      {{"derive", example("paper003/example1_gamma0.yaml"), "--filter", "ukf"},
       "'ukf' is not derived for sampled observations in model allahyani_date_example1_gamma0 (available: "
       "cd-optimal, cd-ekf, cd-euler, cd-closure3, cd-closure4)"},
      {{"derive", undelayed, "--filter", "delay-optimal"}, "delay: 0, or none, is the undelayed model"},
      {{"derive", stratonovich, "--coefficients"},
       "drift[1] has degree 5 once the Stratonovich correction 1/2 g dg/dx is added (as written: degree 1)"},
  };
  for (const auto& c : cases) {
    const auto result = run_pfgen(c.args);
    INFO(c.args.front() << " " << c.args.at(2) << ": " << result.err);
    CHECK(result.exit_code != 0);  // 1, or CLI11's 105 for a value its validator refuses
    CHECK(result.out.empty());
    CHECK(count_lines(result.err) == 1);
    CHECK(result.err.size() < 600);
    CHECK(result.err.find(c.message) != std::string::npos);
  }
}

TEST_CASE("command-line parse errors exit 1 with one line naming the option", "[cli][integration]") {
  const std::string model = example("basin2006_quadratic.yaml");
  TempDir dir;
  const struct {
    std::vector<std::string> args;
    std::string message;
  } cases[] = {
      {{"codegen", model, "--language", "fortran"}, "--language: fortran not in {cpp,c,rust}"},  // CLI11: 105
      {{"codegen", model, "-o", ""}, "--output: the file name is empty"},                  // 105
      {{"eval", model, "--filter", "optimal", "--P", "1"}, "--m is required"},               // 106
      {{"derive", model, "--no-such-option"}, "--no-such-option"},                           // 109
      {{"simulate", model, "--batch", "0"}, "--batch"},                                      // 105
      {{"derive"}, "MODEL is required"},                                                     // 106
      {{}, "A subcommand is required"},                                                      // 106
      // An empty value after '=' took the next argument as the value: "--m is required".
      {{"eval", model, "--filter=", "--m", "0.5", "--P", "1"}, "--filter: no value after '='"},
      {{"codegen", model, "--namespace=", "-o", dir.file("out")}, "--namespace: no value after '='"},
      {{"simulate", model, "--T=", "--runs", "2"}, "--T: no value after '='"},
      // An empty list given as its own argument meant the default filters, without a word.
      {{"derive", model, "--filter", ""}, "--filter: the list is empty"},
      {{"latex", model, "-o", dir.file("m.tex"), "--filter", ""}, "--filter: the list is empty"},
      {{"codegen", model, "--stats", "--filter", ""}, "--filter: the list is empty"},
      {{"simulate", model, "--filters", "", "--runs", "1"}, "--filters: the list is empty"},
  };
  for (const auto& c : cases) {
    const auto result = run_pfgen(c.args);
    INFO((c.args.empty() ? "" : c.args.front()) << ": " << result.err);
    CHECK(result.exit_code == 1);
    CHECK(result.out.empty());
    CHECK(count_lines(result.err) == 1);
    CHECK(result.err.rfind("pfgen: error: ", 0) == 0);
    CHECK(result.err.find(c.message) != std::string::npos);
  }
  CHECK(!std::filesystem::exists(dir.file("out")));
  // --help and --version still succeed.
  CHECK(run_pfgen({"--help"}).exit_code == 0);
  CHECK(run_pfgen({"--version"}).exit_code == 0);
}
