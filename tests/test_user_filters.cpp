// Filters given by their equations in the model file (`filters:`) and the model
// file's `simulation:` defaults. A user filter must flow through every command
// (derive, latex, eval, codegen) exactly as written: the papers' printed
// comparators evaluate to hand-computed values, and a user filter holding the
// textbook EKF equations generates code that computes what the built-in `ekf`
// kind's code computes.
#include <catch2/catch.hpp>

#include <algorithm>
#include <cmath>
#include <random>

#include "generated/basin2006_quadratic/ekf_printed.hpp"
#include "generated/basin_skliar_partial/ekf_printed.hpp"
#include "pfgen/derivation/filter_equations.hpp"
#include "pfgen/evaluation/point_evaluator.hpp"
#include "pfgen/model/model_builder.hpp"
#include "pfgen/model/model_error.hpp"
#include "pfgen/model/model_validator.hpp"
#include "pfgen/model/yaml_model_loader.hpp"
#include "pfgen/notation/text_printer.hpp"
#include "support/cli_helpers.hpp"

using namespace pfgen;
using namespace pfgen_test;
using Catch::Matchers::Contains;

namespace {

GiNaC::numeric q(int numerator, int denominator = 1) { return GiNaC::numeric(numerator, denominator); }

EvaluationPoint point(std::vector<GiNaC::numeric> m, std::vector<std::vector<GiNaC::numeric>> P) {
  EvaluationPoint at;
  at.m = std::move(m);
  at.P = std::move(P);
  return at;
}

// Polynomial in the filter variables of `eq` from model-file text, for exact comparisons.
Polynomial poly(const FilterEquations& eq, const std::string& text) {
  GiNaC::symtab table;
  std::vector<GiNaC::symbol> symbols;
  for (std::uint32_t v = 0; v < eq.variables.count(); ++v) {
    symbols.emplace_back(eq.variables.text_name(v));
    table[eq.variables.text_name(v)] = symbols.back();
  }
  return Polynomial::from_ex(GiNaC::parser(table)(text), symbols);
}

const char* const kRichModel = R"yaml(name: rich
states: [x1, x2]
parameters: {a: 0.3, s: 0.2}
drift: ["a*x1^2 - x2*sin(t)", "x1*x2 - 0.5*x2 + 1"]
diffusion: [["s*x1", "0"], ["0.2", "0.1*x2^2"]]
observation:
  A0: ["cos(t)", "0"]
  A: [["1", "0"], ["1", "a"]]
  B: [["1", "0"], ["0.5", "2"]]
initial: {m0: [0.5, -0.25], P0: [[1, 0.1], [0.1, 0.5]]}
)yaml";

// The model file `base` with a user filter NAME holding exactly the equations of `eq`,
// written as pfgen's text output writes them (model-file syntax).
std::string with_equations_as_user_filter(const std::string& base, const std::string& name, const FilterEquations& eq) {
  TextPrinter printer;
  auto var = [&](std::uint32_t v) { return eq.variables.text_name(v); };
  std::string out = base + "filters:\n  " + name + ":\n    m_drift: [";
  for (std::size_t i = 0; i < eq.n(); ++i) out += (i ? ", \"" : "\"") + printer.print(eq.m_drift[i], var) + "\"";
  out += "]\n    P_drift: [";
  for (std::size_t i = 0; i < eq.n(); ++i) {
    out += i ? ", [" : "[";
    // The lower triangle written with P21-style names, to exercise them.
    for (std::size_t j = 0; j < eq.n(); ++j) {
      std::string text = printer.print(eq.P_drift(i, j), var);
      if (i > j && text.find("P12") != std::string::npos) text.replace(text.find("P12"), 3, "P21");
      out += (j ? ", \"" : "\"") + text + "\"";
    }
    out += "]";
  }
  out += "]\n    gain: [";
  for (std::size_t i = 0; i < eq.n(); ++i) {
    out += i ? ", [" : "[";
    for (std::size_t r = 0; r < eq.p; ++r) out += (r ? ", \"" : "\"") + printer.print(eq.gain[i][r], var) + "\"";
    out += "]";
  }
  return out + "]\n";
}

}  // namespace

TEST_CASE("user filters: a filter's C++ identifier has '_' for '-'", "[userfilter][unit]") {
  CHECK(filter_identifier("ekf-printed") == "ekf_printed");
}

TEST_CASE("user filters: the variables are named as FilterVariables names them", "[userfilter][unit]") {
  for (std::size_t n : {1, 2, 3, 9, 10, 12}) {
    FilterVariables vars(n);
    std::vector<std::string> names = filter_variable_names(n);
    REQUIRE(names.size() == vars.count());
    for (std::uint32_t v = 0; v < vars.count(); ++v) CHECK(names[v] == vars.text_name(v));
  }
  CHECK(filter_variable_names(1) == std::vector<std::string>{"m1", "P11"});
  CHECK(filter_variable_names(10)[10 + 9] == "P1_10");
}

TEST_CASE("user filters: paper 000's printed comparator (eqs 25-26) as written", "[userfilter][published][unit]") {
  Model model = load_model_file(example("basin2006_quadratic.yaml"));
  REQUIRE(model.user_filters.size() == 1);
  FilterEquations printed = derive_named_filter(model, "ekf-printed");
  CHECK(printed.name == "ekf-printed");
  CHECK(printed.is_user_filter());
  CHECK_THAT(printed.description, Contains("Basin, Perez & Skliar 2006 eqs 25-26 as printed"));
  CHECK_FALSE(printed.exactness.exact);
  CHECK(printed.exactness.condition == "user-defined");
  CHECK(printed.jacobian_term.empty());

  // m' = 0.1 m^2, K = P, P' = 0.4 P + 0.01 - P^2 (the textbook ekf-additive has 0.4 m P).
  CHECK(printed.m_drift[0] == poly(printed, "1/10*m1^2"));
  CHECK(printed.gain[0][0] == poly(printed, "P11"));
  CHECK(printed.P_drift(0, 0) == poly(printed, "2/5*P11 + 1/100 - P11^2"));
  FilterEquations textbook = derive_filter(model, FilterKind::EkfAdditive);
  CHECK(textbook.m_drift[0] == printed.m_drift[0]);
  CHECK(textbook.P_drift(0, 0) - printed.P_drift(0, 0) == poly(printed, "2/5*m1*P11 - 2/5*P11"));

  // At m = -1.5, P = 0.5: m' = 0.225, K = 0.5, P' = 0.2 + 0.01 - 0.25 = -0.04.
  EvaluatedFilter at = evaluate_at(model, printed, point({q(-3, 2)}, {{q(1, 2)}}));
  CHECK(at.m_drift[0] == Approx(0.225).epsilon(1e-15));
  CHECK(at.gain[0][0] == Approx(0.5).epsilon(1e-15));
  CHECK(at.P_drift[0][0] == Approx(-0.04).epsilon(1e-14));

  // The checked-in generated code computes the same.
  namespace gen = pfgen_models::basin2006_quadratic::ekf_printed;
  const double state[gen::state_size] = {-1.5, 0.5};
  double out[gen::state_size];
  double K[gen::n * gen::p];
  gen::derivatives<double>(0.0, state, gen::Params<double>{}, out);
  gen::gain<double>(0.0, state, gen::Params<double>{}, K);
  CHECK(out[0] == Approx(0.225).epsilon(1e-15));
  CHECK(out[1] == Approx(-0.04).epsilon(1e-14));
  CHECK(K[0] == 0.5);
}

TEST_CASE("user filters: paper 001's printed comparator (eqs 20-22) as written", "[userfilter][published][unit]") {
  Model model = load_model_file(example("basin_skliar_partial.yaml"));
  FilterEquations printed = derive_named_filter(model, "ekf-printed");
  CHECK(printed.m_drift[0] == poly(printed, "1/10*m1^2 + 1/10*m2"));
  CHECK(printed.m_drift[1] == poly(printed, "1/10*m2"));
  CHECK(printed.gain[0][0] == poly(printed, "P11"));
  CHECK(printed.gain[1][0] == poly(printed, "P12"));
  CHECK(printed.P_drift(0, 0) == poly(printed, "1/5*P12 - P11^2"));
  CHECK(printed.P_drift(0, 1) == poly(printed, "1/10*(P12 + P22) - P11*P12"));
  CHECK(printed.P_drift(1, 0) == printed.P_drift(0, 1));
  CHECK(printed.P_drift(1, 1) == poly(printed, "1/5*P22 - P12^2"));
  // The textbook ekf differs by exactly 0.4 m1 P11 and 0.2 m1 P12 (docs/paper-discrepancies.md rows 3-4).
  FilterEquations textbook = derive_filter(model, FilterKind::Ekf);
  CHECK(textbook.P_drift(0, 0) - printed.P_drift(0, 0) == poly(printed, "2/5*m1*P11"));
  CHECK(textbook.P_drift(0, 1) - printed.P_drift(0, 1) == poly(printed, "1/5*m1*P12"));
  CHECK(textbook.P_drift(1, 1) == printed.P_drift(1, 1));
  for (std::size_t i = 0; i < 2; ++i) CHECK(textbook.m_drift[i] == printed.m_drift[i]);

  // At m = (1, 2), P = [0.5 0.1; 0.1 0.3]: m' = (0.3, 0.2), K = (0.5, 0.1),
  // P11' = 0.02 - 0.25, P12' = 0.04 - 0.05, P22' = 0.06 - 0.01.
  EvaluatedFilter at = evaluate_at(model, printed, point({q(1), q(2)}, {{q(1, 2), q(1, 10)}, {q(1, 10), q(3, 10)}}));
  CHECK(at.m_drift == std::vector<double>{0.3, 0.2});
  CHECK(at.gain == std::vector<std::vector<double>>{{0.5}, {0.1}});
  CHECK(at.P_drift[0][0] == Approx(-0.23).epsilon(1e-15));
  CHECK(at.P_drift[0][1] == Approx(-0.01).epsilon(1e-14));
  CHECK(at.P_drift[1][0] == at.P_drift[0][1]);
  CHECK(at.P_drift[1][1] == Approx(0.05).epsilon(1e-15));

  namespace gen = pfgen_models::basin_skliar_partial::ekf_printed;
  const double state[gen::state_size] = {1, 2, 0.5, 0.1, 0.3};
  double out[gen::state_size];
  gen::derivatives<double>(0.0, state, gen::Params<double>{}, out);
  const double expected[] = {0.3, 0.2, -0.23, -0.01, 0.05};
  for (std::size_t k = 0; k < gen::state_size; ++k) CHECK(out[k] == Approx(expected[k]).epsilon(1e-14).margin(1e-16));
  // initial_state comes from the model, as for the built-in kinds.
  double initial[gen::state_size];
  gen::initial_state<double>(initial);
  CHECK(std::vector<double>(initial, initial + 5) == std::vector<double>{0.1, 0.1, 1, 1, 1});
}

TEST_CASE("user filters: the textbook EKF written as a user filter is the built-in ekf", "[userfilter][compiler]") {
  Model base = load_model_text(kRichModel, "rich.yaml");
  FilterEquations ekf = derive_filter(base, FilterKind::Ekf);
  const std::string text = with_equations_as_user_filter(kRichModel, "textbook-ekf", ekf);
  INFO(text);
  Model model = load_model_text(text, "rich.yaml");
  FilterEquations user = derive_named_filter(model, "textbook-ekf");

  SECTION("the same polynomials, and the same exact values at random points") {
    // Compared within one Model: parameters and t are its symbols.
    FilterEquations same = derive_filter(model, FilterKind::Ekf);
    for (std::size_t i = 0; i < 2; ++i) {
      CHECK(user.m_drift[i] == same.m_drift[i]);
      for (std::size_t r = 0; r < 2; ++r) CHECK(user.gain[i][r] == same.gain[i][r]);
      for (std::size_t j = 0; j < 2; ++j) CHECK(user.P_drift(i, j) == same.P_drift(i, j));
    }
    std::mt19937 rng(7);
    std::uniform_int_distribution<int> k(-2000, 2000);
    for (int sample = 0; sample < 20; ++sample) {
      EvaluationPoint at = point({q(k(rng), 1000), q(k(rng), 1000)}, {{q(3, 2), q(k(rng), 4000)}, {0, q(2)}});
      at.P[1][0] = at.P[0][1];
      at.t = q(std::abs(k(rng)), 1000);
      at.parameters["a"] = q(k(rng), 1000);
      EvaluatedFilter a = evaluate_at(model, user, at);
      EvaluatedFilter b = evaluate_at(base, ekf, at);
      CHECK(a.m_drift == b.m_drift);
      CHECK(a.gain == b.gain);
      CHECK(a.P_drift == b.P_drift);
    }
  }

  SECTION("generated derivatives and step agree with the built-in ekf's generated code") {
    TempDir dir;
    write_file(dir.file("rich.yaml"), text);
    ProcessResult r = run_pfgen({"codegen", dir.file("rich.yaml"), "-o", dir.path(), "--scalar", "double",
                                 "--filter", "ekf,textbook-ekf"});
    INFO(r.err);
    REQUIRE(r.exit_code == 0);
    CHECK(dir.entries() == std::vector<std::string>{"rich", "rich.yaml"});
    const std::string user_header = read_file(dir.file("rich/textbook_ekf.hpp"));
    CHECK_THAT(user_header, Contains("namespace pfgen_models::rich::textbook_ekf {"));
    CHECK_THAT(user_header, Contains("filter `textbook-ekf`"));
    CHECK_THAT(user_header, Contains("given in the model file"));
    write_file(dir.file("compare.cpp"), R"cpp(#include <algorithm>
#include <array>
#include <cmath>
#include <cstdio>
#include <random>
#include "rich/ekf.hpp"
#include "rich/textbook_ekf.hpp"
namespace a = pfgen_models::rich::ekf;
namespace b = pfgen_models::rich::textbook_ekf;
static_assert(a::state_size == b::state_size && a::n == b::n && a::p == b::p, "layout");
int main() {
  std::mt19937 rng(11);
  std::uniform_real_distribution<double> u(-1.5, 1.5);
  double worst = 0;
  a::Params<double> pa{};
  b::Params<double> pb{};
  for (int sample = 0; sample < 200; ++sample) {
    const double t = std::abs(u(rng));
    std::array<double, a::state_size> s{u(rng), u(rng), 1.5 + u(rng), 0.2 * u(rng), 1.5 + u(rng)};
    std::array<double, a::state_size> da{}, db{}, sa = s, sb = s;
    std::array<double, a::n * a::p> Ka{}, Kb{};
    a::derivatives(t, s.data(), pa, da.data());
    b::derivatives(t, s.data(), pb, db.data());
    a::gain(t, s.data(), pa, Ka.data());
    b::gain(t, s.data(), pb, Kb.data());
    const double dy[2] = {0.01 * u(rng), 0.01 * u(rng)};
    a::step(sa.data(), t, 0.01, dy, pa);
    b::step(sb.data(), t, 0.01, dy, pb);
    for (std::size_t k = 0; k < a::state_size; ++k) {
      worst = std::max(worst, std::abs(da[k] - db[k]) / std::max(1.0, std::abs(da[k])));
      worst = std::max(worst, std::abs(sa[k] - sb[k]) / std::max(1.0, std::abs(sa[k])));
    }
    for (std::size_t k = 0; k < a::n * a::p; ++k) worst = std::max(worst, std::abs(Ka[k] - Kb[k]));
  }
  std::printf("%.3g\n", worst);
  return worst <= 1e-14 ? 0 : 1;
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
}

TEST_CASE("user filters: every command takes them by name, after the built-in kinds", "[userfilter][cli][integration]") {
  const std::string model = example("basin_skliar_partial.yaml");
  SECTION("codegen: default set, paths, namespaces, --stats order") {
    TempDir dir;
    ProcessResult r = run_pfgen({"codegen", model, "-o", dir.path(), "--stats"});
    INFO(r.err);
    REQUIRE(r.exit_code == 0);
    CHECK(count_lines(r.out) == 3);
    CHECK(r.out.find("\"filter\": \"optimal\"") < r.out.find("\"filter\": \"ekf\""));
    CHECK(r.out.find("\"filter\": \"ekf\"") < r.out.find("\"filter\": \"ekf-printed\""));
    // Counts are integers in decimal digits (ekf's CSE count has 10 adds: not "1e+01").
    CHECK_THAT(r.out, Contains("\"cse\": {\"adds\": 10, \"muls\": 11,"));
    CHECK(r.out.find("e+") == std::string::npos);
    std::vector<std::string> files;
    for (const auto& entry : std::filesystem::directory_iterator(dir.file("basin_skliar_partial")))
      files.push_back(entry.path().filename().string());
    std::sort(files.begin(), files.end());
    CHECK(files == std::vector<std::string>{"ekf.hpp", "ekf_printed.hpp", "optimal.hpp"});
    CHECK_THAT(read_file(dir.file("basin_skliar_partial/ekf_printed.hpp")),
               Contains("namespace pfgen_models::basin_skliar_partial::ekf_printed {"));
    CHECK_THAT(read_file(dir.file("basin_skliar_partial/ekf_printed.hpp")),
               Contains("// K (n x p, row-major) = as given in the model file."));
    CHECK_THAT(read_file(dir.file("basin_skliar_partial/ekf.hpp")), Contains("= P A^T (B B^T)^-1."));

    TempDir only;
    ProcessResult one = run_pfgen({"codegen", model, "-o", only.path(), "--filter", "ekf-printed", "--eigen"});
    INFO(one.err);
    REQUIRE(one.exit_code == 0);
    CHECK(std::filesystem::exists(only.file("basin_skliar_partial/ekf_printed.hpp")));
    CHECK_THAT(read_file(only.file("basin_skliar_partial/ekf_printed_eigen.hpp")),
               Contains("#include \"ekf_printed.hpp\""));
  }
  SECTION("derive in text, json and latex") {
    ProcessResult text = run_pfgen({"derive", model, "--filter", "ekf-printed"});
    REQUIRE(text.exit_code == 0);
    CHECK_THAT(text.out, Contains("filter: ekf-printed (Basin & Skliar eqs 20-22 as printed"));
    CHECK_THAT(text.out, Contains("dP terms: as given in the model file"));
    CHECK_THAT(text.out, Contains("dP11 = (-P11^2 + 0.2*P12) dt"));
    CHECK_THAT(text.out, Contains("dP12 = (-P11*P12 + 0.1*P12 + 0.1*P22) dt"));
    ProcessResult json = run_pfgen({"derive", model, "--filter", "ekf-printed", "--format", "json"});
    REQUIRE(json.exit_code == 0);
    CHECK_THAT(json.out, Contains("\"filter\": \"ekf-printed\""));
    CHECK_THAT(json.out, Contains("\"condition\": \"user-defined\""));
    ProcessResult latex = run_pfgen({"derive", model, "--filter", "ekf-printed", "--format", "latex"});
    REQUIRE(latex.exit_code == 0);
    CHECK_THAT(latex.out, Contains("not derived by pfgen"));
  }
  SECTION("latex includes user filters by default and on request") {
    TempDir dir;
    REQUIRE(run_pfgen({"latex", model, "-o", dir.file("all.tex")}).exit_code == 0);
    const std::string all = read_file(dir.file("all.tex"));
    CHECK(all.find("\\section*{Filter \\texttt{ekf}}") < all.find("\\section*{Filter \\texttt{ekf-printed}}"));
    REQUIRE(run_pfgen({"latex", model, "--filter", "ekf-printed", "-o", dir.file("one.tex")}).exit_code == 0);
    const std::string one = read_file(dir.file("one.tex"));
    CHECK(one.find("\\section*{Filter \\texttt{ekf-printed}}") != std::string::npos);
    CHECK(one.find("\\section*{Filter \\texttt{optimal}}") == std::string::npos);
  }
  SECTION("eval") {
    ProcessResult r = run_pfgen({"eval", model, "--filter", "ekf-printed", "--m=1,2", "--P", "0.5,0.1;0.1,0.3"});
    INFO(r.err);
    REQUIRE(r.exit_code == 0);
    CHECK_THAT(r.out, Contains("\"filter\": \"ekf-printed\""));
    CHECK_THAT(r.out, Contains("\"m_drift\": [0.3, 0.2]"));
  }
  SECTION("an unknown name lists the model's own filters") {
    ProcessResult r = run_pfgen({"eval", model, "--filter", "ekf-paper", "--m=1,2", "--P", "0.5,0.1;0.1,0.3"});
    CHECK(r.exit_code == 1);
    CHECK(r.out.empty());
    // No moment filter: the model's P0 is singular, where one would stop at once.
    CHECK_THAT(r.err, Contains("unknown filter 'ekf-paper' (known: optimal, ekf, ukf, ekf-printed)"));
  }
}

TEST_CASE("user filters: output is byte-identical across separate processes", "[userfilter][determinism][integration]") {
  const std::string model = example("basin2006_quadratic.yaml");
  std::vector<std::string> runs;
  for (int run = 0; run < 3; ++run) {
    TempDir dir;
    std::string all;
    for (const std::string format : {"text", "json", "latex"})
      all += run_pfgen({"derive", model, "--filter", "ekf-printed", "--format", format}).out;
    REQUIRE(run_pfgen({"codegen", model, "-o", dir.path(), "--filter", "ekf-printed", "--scalar", "float"}).exit_code == 0);
    all += read_file(dir.file("basin2006_quadratic/ekf_printed.hpp"));
    runs.push_back(all);
  }
  CHECK(runs[0] == runs[1]);
  CHECK(runs[0] == runs[2]);
}

TEST_CASE("user filters: P21 names P12, and from n = 10 on P10_1 names P1_10", "[userfilter][unit]") {
  const std::string two = R"yaml(name: two
states: [x1, x2]
drift: ["-x1", "-x2"]
diffusion: [["1", "0"], ["0", "1"]]
observation: {A: [["1", "0"]], B: [["1"]]}
filters:
  mine:
    m_drift: ["-m1", "-m2"]
    P_drift: [["1 - 2*P11", "-2*P12"], ["-2*P21", "1 - 2*P22"]]
    gain: [["P11"], ["P21"]]
)yaml";
  Model model = load_model_text(two, "two.yaml");
  FilterEquations eq = derive_named_filter(model, "mine");
  CHECK(eq.gain[1][0] == Polynomial::variable(eq.variables.P(0, 1)));

  std::string ten = "name: ten\nstates: [";
  for (int i = 1; i <= 10; ++i) ten += (i > 1 ? ", x" : "x") + std::to_string(i);
  ten += "]\ndrift: [";
  for (int i = 1; i <= 10; ++i) ten += (i > 1 ? ", \"-x" : "\"-x") + std::to_string(i) + "\"";
  ten += "]\ndiffusion_covariance: [";
  for (int i = 1; i <= 10; ++i) {
    ten += i > 1 ? ", [" : "[";
    for (int j = 1; j <= 10; ++j) ten += std::string(j > 1 ? ", " : "") + (i == j ? "\"1\"" : "\"0\"");
    ten += "]";
  }
  ten += "]\nobservation: {A: [[\"1\", \"0\", \"0\", \"0\", \"0\", \"0\", \"0\", \"0\", \"0\", \"0\"]], B: [[\"1\"]]}\n";
  std::string P_drift = "[";
  for (int i = 1; i <= 10; ++i) {
    P_drift += i > 1 ? ", [" : "[";
    for (int j = 1; j <= 10; ++j) {
      std::string entry = "-2*P" + std::to_string(i) + "_" + std::to_string(j);
      P_drift += (j > 1 ? ", \"" : "\"") + entry + "\"";
    }
    P_drift += "]";
  }
  P_drift += "]";
  std::string filter = "filters:\n  mine:\n    m_drift: [";
  for (int i = 1; i <= 10; ++i) filter += (i > 1 ? ", \"-m" : "\"-m") + std::to_string(i) + "\"";
  filter += "]\n    P_drift: " + P_drift + "\n    gain: [";
  for (int i = 1; i <= 10; ++i) filter += (i > 1 ? ", [\"P" : "[\"P") + std::to_string(i) + "_1\"]";
  filter += "]\n";
  Model big = load_model_text(ten + filter, "ten.yaml");
  FilterEquations eq10 = derive_named_filter(big, "mine");
  CHECK(eq10.gain[9][0] == Polynomial::variable(eq10.variables.P(0, 9)));
  CHECK(eq10.P_drift(0, 9) == Polynomial::variable(eq10.variables.P(0, 9)).scaled(-2));
  // P110 (n >= 10 writes P1_10) is not a name.
  std::string bad = ten + filter;
  bad.replace(bad.find("\"P10_1\""), 7, "\"P110\"");
  CHECK_THROWS_WITH(load_model_text(bad, "ten.yaml"), Contains("unknown symbol 'P110'"));
}

TEST_CASE("user filters: ModelBuilder adds them with the same checks", "[userfilter][api][unit]") {
  auto builder = [] {
    ModelBuilder b("api_model");
    GiNaC::symbol x = b.state("x");
    GiNaC::symbol a = b.parameter("a", GiNaC::numeric(1, 10));
    b.drift({a * GiNaC::pow(x, 2)});
    b.diffusion({{GiNaC::numeric(1, 10) * GiNaC::pow(x, 2)}});
    b.observation({0}, {{1}}, {{1}});
    return b;
  };
  SECTION("the printed comparator of paper 000, floats made exact") {
    ModelBuilder b = builder();
    const auto& v = b.filter_variables();
    REQUIRE(v.size() == 2);
    CHECK(v[0].get_name() == "m1");
    CHECK(v[1].get_name() == "P11");
    b.user_filter("ekf-printed", {0.1 * GiNaC::pow(v[0], 2)}, {{0.4 * v[1] + 0.01 - GiNaC::pow(v[1], 2)}}, {{v[1]}},
                  "as printed");
    Model api = b.build();
    Model file = load_model_file(example("basin2006_quadratic.yaml"));
    FilterEquations from_api = derive_named_filter(api, "ekf-printed");
    FilterEquations from_file = derive_named_filter(file, "ekf-printed");
    CHECK(from_api.m_drift == from_file.m_drift);
    CHECK(from_api.P_drift(0, 0) == from_file.P_drift(0, 0));
    CHECK(from_api.gain == from_file.gain);
    CHECK(from_api.description == "as printed");
    CHECK(available_filter_names(api) == std::vector<std::string>{"optimal", "ekf", "ukf", "closure3", "closure4", "ekf-printed"});
    CHECK(default_filter_names(api) == std::vector<std::string>{"optimal", "ekf", "ekf-printed"});
  }
  SECTION("a state in a user filter is refused") {
    ModelBuilder b = builder();
    const auto& v = b.filter_variables();
    GiNaC::symbol x = GiNaC::ex_to<GiNaC::symbol>(b.symbols()["x"]);
    b.user_filter("mine", {x}, {{v[1]}}, {{v[1]}});
    CHECK_THROWS_WITH(b.build(), Contains("field 'filters.mine.m_drift', row 1: 'x' depends on the states"));
  }
  SECTION("variables made before the last state are refused") {
    ModelBuilder b("late");
    GiNaC::symbol x = b.state("x");
    const auto v = b.filter_variables();
    GiNaC::symbol y = b.state("y");
    b.drift({-x, -y});
    b.diffusion({{1, 0}, {0, 1}});
    b.observation({0}, {{1, 0}}, {{1}});
    b.user_filter("mine", {-v[0], 0}, {{v[1], 0}, {0, v[1]}}, {{v[1]}, {0}});
    CHECK_THROWS_WITH(b.build(), Contains("the filter's variables must be m1..m2"));
  }
  SECTION("an asymmetric P drift is refused, naming the entries") {
    ModelBuilder b("two");
    GiNaC::symbol x = b.state("x");
    GiNaC::symbol y = b.state("y");
    b.drift({-x, -y});
    b.diffusion({{1, 0}, {0, 1}});
    b.observation({0}, {{1, 0}}, {{1}});
    const auto& v = b.filter_variables();  // m1 m2 P11 P12 P22
    b.user_filter("mine", {-v[0], -v[1]}, {{v[2], v[3]}, {2 * v[3], v[4]}}, {{v[2]}, {v[3]}});
    CHECK_THROWS_WITH(b.build(), Contains("not symmetric: entry (1,2) is 'P12' but entry (2,1) is '2*P12'"));
  }
}

TEST_CASE("simulation: the examples' sections are read, with their places in the file", "[userfilter][simulation][unit]") {
  Model p000 = load_model_file(example("basin2006_quadratic.yaml"));
  const SimulationSection& s = p000.simulation;
  REQUIRE(s.T);
  CHECK(*s.T == 9.2);
  CHECK(*s.dt == 1e-4);
  CHECK(*s.runs == 200);
  CHECK(*s.seed == 1);
  CHECK(*s.filters == std::vector<std::string>{"optimal", "additive", "ekf-additive", "ekf", "ekf-printed"});
  CHECK(*s.scheme == "auto");
  CHECK(s.report_times == std::vector<double>{2, 4, 6, 8, 9.2});
  CHECK(s.windows == std::vector<std::pair<double, double>>{{0, 4}, {4, 9.2}});
  CHECK_FALSE(s.record_points);
  CHECK_FALSE(s.bound);
  CHECK_FALSE(s.shown_run);
  // "FILE:LINE:COL" of the field, as in error messages.
  const std::string where = s.location_of("T");
  CHECK(where.rfind(example("basin2006_quadratic.yaml") + ":", 0) == 0);
  const std::string text = read_file(example("basin2006_quadratic.yaml"));
  std::size_t line = 1 + static_cast<std::size_t>(std::count(text.begin(), text.begin() + text.find("  T: 9.2"), '\n'));
  CHECK(where == example("basin2006_quadratic.yaml") + ":" + std::to_string(line) + ":3");
  CHECK(s.location_of("bound") == example("basin2006_quadratic.yaml"));

  Model p001 = load_model_file(example("basin_skliar_partial.yaml"));
  CHECK(*p001.simulation.T == 6.5);
  CHECK(*p001.simulation.filters == std::vector<std::string>{"optimal", "ekf", "ekf-printed"});
  CHECK(p001.simulation.report_times == std::vector<double>{5, 6, 6.5});
  CHECK(p001.simulation.windows.empty());

  Model none = load_model_text("name: m\nstates: [x]\ndrift: [\"-x\"]\ndiffusion: [[\"1\"]]\n"
                               "observation: {A: [[\"1\"]], B: [[\"1\"]]}\n",
                               "m.yaml");
  CHECK_FALSE(none.simulation.T);
  CHECK_FALSE(none.simulation.filters);
  CHECK(none.user_filters.empty());
}

TEST_CASE("simulation: every field and its bounds", "[userfilter][simulation][unit]") {
  const std::string head = "name: m\nstates: [x]\ndrift: [\"-x\"]\ndiffusion: [[\"1\"]]\nadditive_diffusion: [[\"1\"]]\n"
                           "observation: {A: [[\"1\"]], B: [[\"1\"]]}\n";
  Model all = load_model_text(head + R"yaml(simulation:
  T: 1
  dt: 0.5
  runs: 3
  seed: 18446744073709551615
  filters: [ekf-additive]
  scheme: derivative-free-milstein
  report_times: [1]
  windows: [[0, 1]]
  record_points: 2
  bound: 1e300
  shown_run: 2
)yaml",
                              "m.yaml");
  CHECK(*all.simulation.seed == 18446744073709551615ull);
  CHECK(*all.simulation.bound == 1e300);
  CHECK(*all.simulation.shown_run == 2);
  CHECK(*all.simulation.record_points == 2);
  // Checks that need another field apply only when it is given here: the command line
  // checks the combination with its own options.
  CHECK_NOTHROW(load_model_text(head + "simulation: {shown_run: 7, report_times: [100], windows: [[3, 100]]}\n", "m.yaml"));
  CHECK_THROWS_WITH(load_model_text(head + "simulation: {T: 1e99999}\n", "m.yaml"), Contains("is not a number"));
  CHECK_THROWS_WITH(load_model_text(head + "simulation: {T: 1e999}\n", "m.yaml"), Contains("'1e999' is out of range"));
  CHECK_THROWS_WITH(load_model_text(head + "simulation: {dt: 1e-999}\n", "m.yaml"),
                    Contains("must be a number greater than 0, found 0"));
  CHECK_THROWS_WITH(load_model_text(head + "simulation: {T:}\n", "m.yaml"), Contains("field 'simulation.T': missing value"));
  CHECK_THROWS_WITH(load_model_text(head + "simulation: {T: 2, dt: 2}\n", "m.yaml"), Contains("must be smaller than T"));
  CHECK_THROWS_WITH(load_model_text(head + "simulation: {windows: [[-1, 1]]}\n", "m.yaml"), Contains("starts before t = 0"));
  CHECK(simulation_schemes().front() == "auto");
}
