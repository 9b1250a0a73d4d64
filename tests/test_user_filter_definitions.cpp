// A user filter's auxiliary names (`filters.NAME.define`). The check is a known special case: the
// Kalman-Bucy filter of a linear model written in its information form S = P^-1, with every
// matrix product named under `define:` and the gain read through S^-1 = adj(S)/det S, is the
// built-in `optimal` filter (which is Kalman-Bucy there). Substituting the definitions must give
// optimal's polynomials exactly; `pfgen eval` must give its values; the generated code must
// compute what optimal's generated code computes. The reports list the definitions in order.
#include <catch2/catch.hpp>

#include <algorithm>
#include <cmath>
#include <random>

#include "pfgen/derivation/filter_equations.hpp"
#include "pfgen/evaluation/point_evaluator.hpp"
#include "pfgen/model/model_builder.hpp"
#include "pfgen/model/yaml_model_loader.hpp"
#include "support/cli_helpers.hpp"

using namespace pfgen;
using namespace pfgen_test;
using Catch::Matchers::Contains;

namespace {

// dx = (A x + (0, sin t)) dt + g dW, dy = C x dt + r dV with A = [a, 1; -1, -b], g = [s, 0; 1/2, 1],
// C = (1, 0). The information filter: dS = -(S A + A^T S) + C^T C / r^2 - S W S, W = g g^T,
// dP = -P dS P, gain S^-1 C^T / r^2.
const char* const kInformationModel = R"yaml(name: information
states: [x1, x2]
parameters: {a: -0.5, b: 0.25, s: 0.75, r: 0.5}
drift: ["a*x1 + x2", "-x1 - b*x2 + sin(t)"]
diffusion: [["s", "0"], ["1/2", "1"]]
observation:
  A: [["1", "0"]]
  B: [["r"]]
initial: {m0: [0.5, -0.25], P0: [[1, 0.1], [0.1, 0.5]]}
filters:
  information:
    description: "Kalman-Bucy in the information S = P^-1"
    define:
      detP: "P11*P22 - P12^2"
      S11: "P22/detP"
      S12: "-P12/detP"
      S22: "P11/detP"
      W11: "s^2"
      W12: "s/2"
      W22: "5/4"
      SA11: "S11*a - S12"
      SA12: "S11 - S12*b"
      SA21: "S12*a - S22"
      SA22: "S12 - S22*b"
      SW11: "S11*W11 + S12*W12"
      SW12: "S11*W12 + S12*W22"
      SW21: "S12*W11 + S22*W12"
      SW22: "S12*W12 + S22*W22"
      dS11: "-2*SA11 + 1/r^2 - (SW11*S11 + SW12*S12)"
      dS12: "-(SA12 + SA21) - (SW11*S12 + SW12*S22)"
      dS22: "-2*SA22 - (SW21*S12 + SW22*S22)"
      detS: "S11*S22 - S12^2"
    m_drift: ["a*m1 + m2", "-m1 - b*m2 + sin(t)"]
    P_drift:
      - ["-(P11*(dS11*P11 + dS12*P12) + P12*(dS12*P11 + dS22*P12))",
         "-(P11*(dS11*P12 + dS12*P22) + P12*(dS12*P12 + dS22*P22))"]
      - ["-(P11*(dS11*P12 + dS12*P22) + P12*(dS12*P12 + dS22*P22))",
         "-(P12*(dS11*P12 + dS12*P22) + P22*(dS12*P12 + dS22*P22))"]
    gain: [["S22/detS/r^2"], ["-S12/detS/r^2"]]
)yaml";

// The definitions substituted into e, last first, until none is left.
GiNaC::ex substituted(const FilterEquations& eq, const GiNaC::ex& e) {
  GiNaC::ex out = e;
  for (auto d = eq.definitions.rbegin(); d != eq.definitions.rend(); ++d) out = out.subs(d->name == d->value);
  return out;
}

bool same(const GiNaC::ex& a, const GiNaC::ex& b) { return (a - b).normal().is_zero(); }

EvaluationPoint random_point(std::mt19937& rng) {
  std::uniform_int_distribution<int> k(-1000, 1000);
  auto r = [&] { return GiNaC::numeric(k(rng), 1000); };
  EvaluationPoint at;
  at.t = GiNaC::abs(r()) * 3;
  at.m = {r(), r()};
  const GiNaC::numeric l11 = 1 + GiNaC::abs(r()), l21 = r(), l22 = GiNaC::numeric(1, 10) + GiNaC::abs(r());
  at.P = {{l11 * l11, l11 * l21}, {l11 * l21, l21 * l21 + l22 * l22}};
  at.parameters["a"] = r();
  at.parameters["s"] = 1 + r() / 2;
  return at;
}

}  // namespace

TEST_CASE("user filter definitions: Kalman-Bucy in information form is the built-in optimal filter",
          "[userfilter][definitions][kalman-bucy][unit]") {
  const Model model = load_model_text(kInformationModel, "information.yaml");
  const FilterEquations user = derive_named_filter(model, "information");
  const FilterEquations optimal = derive_filter(model, FilterKind::Optimal);
  REQUIRE(user.definitions.size() == 19);
  CHECK(user.definitions.front().name.get_name() == "detP");
  CHECK(user.definitions.back().name.get_name() == "detS");
  const auto& v = user.variables.symbols();

  SECTION("the definitions substituted give optimal's equations exactly") {
    for (std::size_t i = 0; i < 2; ++i) {
      INFO("row " << i + 1);
      CHECK(same(substituted(user, user.m_drift[i].to_ex(v)), optimal.m_drift[i].to_ex(v)));
      CHECK(same(substituted(user, user.gain[i][0].to_ex(v)), optimal.gain[i][0].to_ex(v)));
      for (std::size_t j = 0; j < 2; ++j)
        CHECK(same(substituted(user, user.P_drift(i, j).to_ex(v)), optimal.P_drift(i, j).to_ex(v)));
    }
    // Without them the equations are polynomials in m and P whose coefficients hold the names.
    CHECK(user.P_drift(0, 0).to_ex(v).has(user.definitions[15].name));  // dS11
  }

  SECTION("eval computes the definitions in order and agrees with optimal at random points") {
    std::mt19937 rng(5);
    for (int sample = 0; sample < 25; ++sample) {
      const EvaluationPoint at = random_point(rng);
      const EvaluatedFilter a = evaluate_at(model, user, at);
      const EvaluatedFilter b = evaluate_at(model, optimal, at);
      double scale = 1;
      for (const auto& row : b.P_drift) for (double x : row) scale = std::max(scale, std::abs(x));
      for (std::size_t i = 0; i < 2; ++i) {
        CHECK(a.m_drift[i] == Approx(b.m_drift[i]).epsilon(1e-14).margin(1e-14));
        CHECK(a.gain[i][0] == Approx(b.gain[i][0]).epsilon(1e-13).margin(1e-13));
        for (std::size_t j = 0; j < 2; ++j) CHECK(std::abs(a.P_drift[i][j] - b.P_drift[i][j]) <= 1e-13 * scale);
      }
    }
  }

  SECTION("a point where a definition divides by zero is refused, naming the definition") {
    EvaluationPoint singular;
    singular.m = {0, 0};
    singular.P = {{1, 1}, {1, 1}};  // positive semi-definite, det P = 0
    CHECK_THROWS_WITH(evaluate_at(model, user, singular),
                      Contains("definition 'S11' cannot be computed at this point"));
  }
}

TEST_CASE("user filter definitions: listed before the equations in text, LaTeX and JSON",
          "[userfilter][definitions][cli][integration]") {
  TempDir dir;
  write_file(dir.file("information.yaml"), kInformationModel);
  const ProcessResult text = run_pfgen({"derive", dir.file("information.yaml"), "--filter", "information"});
  REQUIRE(text.exit_code == 0);
  CHECK_THAT(text.out, Contains("definitions (computed in this order before the equations):\n"
                                "  detP = P11*P22 - P12^2\n  S11 = P22/detP\n"));
  CHECK(text.out.find("  detS = ") < text.out.find("dm1 = (a*m1 + m2) dt + K1_1 (dy1 - m1 dt)"));
  CHECK_THAT(text.out, Contains("K1_1 = S22/(detS*r^2)"));
  const ProcessResult latex = run_pfgen({"derive", dir.file("information.yaml"), "--filter", "information", "--format", "latex"});
  REQUIRE(latex.exit_code == 0);
  CHECK_THAT(latex.out, Contains("\\mathrm{detP} &= P_{11}\\,P_{22} - P_{12}^{2} \\\\\n"));
  const ProcessResult json = run_pfgen({"derive", dir.file("information.yaml"), "--filter", "information", "--format", "json"});
  REQUIRE(json.exit_code == 0);
  CHECK_THAT(json.out, Contains("\"definitions\": [\n    {\n      \"name\": \"detP\",\n      \"value\": \"P11*P22 - P12^2\"\n    },"));
  // A filter without definitions has no such key or block.
  const ProcessResult optimal = run_pfgen({"derive", dir.file("information.yaml"), "--filter", "optimal", "--format", "json"});
  REQUIRE(optimal.exit_code == 0);
  CHECK(optimal.out.find("definitions") == std::string::npos);
  // Separate processes, the same bytes (the definitions' symbols are made afresh in each).
  CHECK(run_pfgen({"derive", dir.file("information.yaml"), "--filter", "information"}).out == text.out);
}

TEST_CASE("user filter definitions: the generated code computes what optimal's generated code computes",
          "[userfilter][definitions][compiler]") {
  TempDir dir;
  write_file(dir.file("information.yaml"), kInformationModel);
  ProcessResult r = run_pfgen({"codegen", dir.file("information.yaml"), "-o", dir.path(), "--scalar", "double",
                               "--filter", "optimal,information"});
  INFO(r.err);
  REQUIRE(r.exit_code == 0);
  write_file(dir.file("compare.cpp"), R"cpp(#include <algorithm>
#include <array>
#include <cmath>
#include <cstdio>
#include <random>
#include "information/information.hpp"
#include "information/optimal.hpp"
namespace a = pfgen_models::information::optimal;
namespace b = pfgen_models::information::information;
static_assert(a::state_size == b::state_size && a::n == b::n && a::p == b::p, "layout");
int main() {
  std::mt19937 rng(3);
  std::uniform_real_distribution<double> u(-1, 1);
  double worst = 0;
  a::Params<double> pa{};
  b::Params<double> pb{};
  for (int sample = 0; sample < 200; ++sample) {
    const double t = 3 * std::abs(u(rng));
    const double l11 = 1 + std::abs(u(rng)), l21 = u(rng), l22 = 0.1 + std::abs(u(rng));
    std::array<double, a::state_size> s{u(rng), u(rng), l11 * l11, l11 * l21, l21 * l21 + l22 * l22};
    std::array<double, a::state_size> da{}, db{}, sa = s, sb = s;
    std::array<double, a::n * a::p> Ka{}, Kb{};
    a::derivatives(t, s.data(), pa, da.data());
    b::derivatives(t, s.data(), pb, db.data());
    a::gain(t, s.data(), pa, Ka.data());
    b::gain(t, s.data(), pb, Kb.data());
    const double dy[1] = {0.01 * u(rng)};
    a::step(sa.data(), t, 0.01, dy, pa);
    b::step(sb.data(), t, 0.01, dy, pb);
    for (std::size_t k = 0; k < a::state_size; ++k) {
      worst = std::max(worst, std::abs(da[k] - db[k]) / std::max(1.0, std::abs(da[k])));
      worst = std::max(worst, std::abs(sa[k] - sb[k]) / std::max(1.0, std::abs(sa[k])));
    }
    for (std::size_t k = 0; k < a::n * a::p; ++k) worst = std::max(worst, std::abs(Ka[k] - Kb[k]));
  }
  std::printf("%.3g\n", worst);
  return worst <= 1e-12 ? 0 : 1;
}
)cpp");
  const std::string exe = dir.file("compare");
  ProcessResult built = run_process("g++ -std=c++17 -O1 -Wall -Wextra -Werror -I " + shell_quote(dir.path()) + " " +
                                    shell_quote(dir.file("compare.cpp")) + " -o " + shell_quote(exe));
  INFO(built.err.substr(0, 4000));
  REQUIRE(built.exit_code == 0);
  ProcessResult ran = run_process(shell_quote(exe));
  INFO("largest relative difference: " << ran.out);
  CHECK(ran.exit_code == 0);
}

TEST_CASE("user filter definitions: ModelBuilder takes them with the same checks", "[userfilter][definitions][api][unit]") {
  ModelBuilder b("api_definitions");
  GiNaC::symbol x = b.state("x");
  b.drift({-x});
  b.diffusion({{1}});
  b.observation({0}, {{1}}, {{1}});
  const auto& v = b.filter_variables();  // m1, P11
  GiNaC::symbol S("S"), T("T");
  SECTION("a value that reads a name defined after it is refused") {
    b.user_filter("mine", {-v[0]}, {{1 - S * GiNaC::pow(v[1], 2)}}, {{v[1]}}, "", {{S, 2 * T}, {T, 1 / v[1]}});
    CHECK_THROWS_WITH(b.build(), Contains("field 'filters.mine.define.S': reads 'T', which is not defined before it"));
  }
  SECTION("in order, the filter is Kalman-Bucy: dP = 1 - 2 P - P^2 written as -P^2 (2 S + 1 - S^2)") {
    b.user_filter("mine", {-v[0]}, {{-GiNaC::pow(v[1], 2) * T}}, {{v[1]}}, "", {{S, 1 / v[1]}, {T, 2 * S + 1 - S * S}});
    const Model model = b.build();
    const FilterEquations eq = derive_named_filter(model, "mine");
    EvaluationPoint at;
    at.m = {GiNaC::numeric(1, 2)};
    at.P = {{GiNaC::numeric(3, 10)}};
    CHECK(evaluate_at(model, eq, at).P_drift[0][0] == Approx(1 - 0.6 - 0.09).epsilon(1e-15));
  }
}
