// The exactness diagnostic (generator/src/derivation/exactness.cpp): which
// published condition makes the Gaussian closure exact for a model, or which
// conditions failed and why. One model per branch, built with ModelBuilder,
// plus the example files, plus the diagnostic as `pfgen derive` prints it in
// text, LaTeX and JSON.
#include <catch2/catch.hpp>

#include <cstdio>
#include <cstdlib>
#include <fstream>
#include <string>
#include <unistd.h>
#include <vector>

#include "pfgen/derivation/exactness.hpp"
#include "pfgen/derivation/filter_equations.hpp"
#include "pfgen/model/model_builder.hpp"
#include "pfgen/model/yaml_model_loader.hpp"
#include "pfgen/notation/rich_text.hpp"
#include "support/process.hpp"
#include "support/test_paths.hpp"

using namespace pfgen;
using Catch::Matchers::Contains;
using Catch::Matchers::StartsWith;
using GiNaC::ex;
using GiNaC::numeric;

namespace {

const ex tenth = numeric(1, 10);

// Checks the report says `exact` under `condition` with nothing failed.
void require_exact(const ExactnessReport& r, const std::string& condition) {
  INFO("explanation: " << r.explanation);
  CHECK(r.exact);
  CHECK(r.condition == condition);
  CHECK(r.failed.empty());
  CHECK_THAT(rich_text_plain(r.explanation), StartsWith("exact:"));
}

// One expected failure: the condition's name and a fragment of its reason (as text, and as
// LaTeX where the reason has math).
struct Failure {
  std::string condition;
  std::string reason;
  std::string latex_reason = reason;
};

// Checks an approximation report lists exactly these failures, in order.
void require_approximation(const ExactnessReport& r, const std::vector<Failure>& failures) {
  INFO("explanation: " << r.explanation);
  CHECK_FALSE(r.exact);
  CHECK(r.condition == "none");
  CHECK_THAT(rich_text_plain(r.explanation), StartsWith("approximation:"));
  REQUIRE(r.failed.size() == failures.size());
  for (std::size_t k = 0; k < failures.size(); ++k) {
    INFO("failed[" << k << "] = " << r.failed[k]);
    CHECK_THAT(rich_text_plain(r.failed[k]), StartsWith(failures[k].condition + ": "));
    CHECK_THAT(rich_text_plain(r.failed[k]), Contains(failures[k].reason));
  }
}

// Basin & Skliar's example (x1' = 0.1(x1^2 + x2), x2' = 0.1 x2, y = x1) with its
// pieces replaceable, so each variant breaks exactly one paper-001 condition.
struct Paper001Variant {
  std::string f2 = "linear";        // "linear": 0.1 x2; "coupled": 0.1 x2 + 0.1 x1
  bool mixed_observation = false;   // A = [1 1] instead of [1 0]
  bool multiplicative = false;      // g = [0.1 x1; 0] instead of 0
  bool additive = false;            // also give additive g = [0.1; 0]
};

Model paper001_variant(const Paper001Variant& v) {
  ModelBuilder b("paper001_variant");
  GiNaC::symbol x1 = b.state("x1"), x2 = b.state("x2");
  ex f2 = tenth * x2;
  if (v.f2 == "coupled") f2 += tenth * x1;
  b.drift({tenth * (x1 * x1 + x2), f2});
  b.diffusion({{v.multiplicative ? ex(tenth * x1) : ex(0)}, {0}});
  if (v.additive) b.additive_diffusion({{tenth}, {0}});
  b.observation({0}, {{1, v.mixed_observation ? 1 : 0}}, {{1}});
  return b.build();
}

// The approximation model of the brief: quadratic f, x2 with nonlinear
// dynamics (so no linear block to leave unmeasured), A = [1 0].
const char* approximation_yaml =
    "name: approximation_two_state\n"
    "states: [x1, x2]\n"
    "drift: [\"0.1*x1^2 + x2\", \"0.1*x1*x2\"]\n"
    "diffusion: [[\"0.1\"], [\"0\"]]\n"
    "observation:\n"
    "  A0: [\"0\"]\n"
    "  A: [[\"1\", \"0\"]]\n"
    "  B: [[\"1\"]]\n";

const std::vector<Failure> approximation_failures = {
    {"Kalman-Bucy", "drift of x1 has degree 2"},
    {"Basin-Perez-Skliar 2006", "A is 1 x 2, not square", "$A$ is $1 \\times 2$, not square"},
    {"Basin-Perez-Skliar 2006 linear case", "drift of x1 has degree 2"},
    {"Basin-Skliar", "no components with their own linear dynamics to leave unmeasured"}};

// A model file in a fresh temporary path, removed again on destruction.
class TemporaryModelFile {
 public:
  explicit TemporaryModelFile(const std::string& text) {
    char name[] = "/tmp/pfgen-test-exactness-XXXXXX.yaml";
    int fd = mkstemps(name, 5);
    REQUIRE(fd >= 0);
    close(fd);
    path_ = name;
    std::ofstream(path_) << text;
  }
  ~TemporaryModelFile() { std::remove(path_.c_str()); }
  const std::string& path() const { return path_; }

 private:
  std::string path_;
};

// Runs `pfgen derive` and returns its stdout, requiring success.
std::string derive_output(const std::string& model_path, const std::string& filter, const std::string& format) {
  const std::string command = pfgen_test::shell_quote(pfgen_test::pfgen_executable()) + " derive " +
                              pfgen_test::shell_quote(model_path) + " --filter " + filter + " --format " + format;
  pfgen_test::ProcessResult r = pfgen_test::run_process(command);
  INFO(command << "\nstderr: " << r.err);
  REQUIRE(r.exit_code == 0);
  return r.out;
}

// JSON text without the whitespace outside strings, so the checks below do not
// depend on the writer's indentation.
std::string compact_json(const std::string& json) {
  std::string out;
  bool in_string = false, escaped = false;
  for (char c : json) {
    if (in_string) {
      out += c;
      if (escaped) escaped = false;
      else if (c == '\\') escaped = true;
      else if (c == '"') in_string = false;
    } else if (c == '"') {
      in_string = true;
      out += c;
    } else if (c != ' ' && c != '\n' && c != '\t' && c != '\r') {
      out += c;
    }
  }
  return out;
}

}  // namespace

// ---------------------------------------------------------------------------
// Kalman-Bucy: f affine, g free of x (time-dependent coefficients allowed),
// exact for any A, here a non-square one; the EKF coincides with it.
// ---------------------------------------------------------------------------
TEST_CASE("exactness: Kalman-Bucy for affine f and state-free g", "[exactness][unit]") {
  ModelBuilder b("kalman_bucy");
  GiNaC::symbol x1 = b.state("x1"), x2 = b.state("x2");
  GiNaC::symbol t = b.time();
  b.drift({x2, -t * x1 + numeric(1, 2)})
      .diffusion({{t}, {numeric(1, 5)}})
      .additive_diffusion({{1}, {0}})
      .observation({0}, {{1, 0}}, {{1}});
  Model model = b.build();
  for (FilterKind kind : {FilterKind::Optimal, FilterKind::Ekf, FilterKind::Additive, FilterKind::EkfAdditive}) {
    INFO("kind " << filter_kind_name(kind));
    ExactnessReport r = assess_exactness(model, kind);
    require_exact(r, "Kalman-Bucy");
    // derive_filter carries the same report.
    CHECK(derive_filter(model, kind).exactness.condition == "Kalman-Bucy");
  }
  // The additive kinds say which diffusion the statement is about.
  CHECK_THAT(assess_exactness(model, FilterKind::Additive).explanation, Contains("additive diffusion"));
  CHECK_THAT(assess_exactness(model, FilterKind::Optimal).explanation, !Contains("additive diffusion"));
}

// ---------------------------------------------------------------------------
// Basin, Perez & Skliar 2006: any polynomial f and g when A is square and invertible.
// ---------------------------------------------------------------------------
TEST_CASE("exactness: paper 000 for quadratic f and g with square invertible A", "[exactness][unit]") {
  ModelBuilder b("paper000_square");
  GiNaC::symbol x1 = b.state("x1"), x2 = b.state("x2");
  b.drift({tenth * x1 * x1, x1 * x2})
      .diffusion({{tenth * x1 * x1}, {x2}})
      .observation({0, 0}, {{1, 1}, {0, 1}}, {{1, 0}, {0, 1}});  // det A = 1, A not diagonal
  Model model = b.build();
  require_exact(assess_exactness(model, FilterKind::Optimal), "Basin-Perez-Skliar 2006");

  // The example file (scalar, A = 1), for the optimal and the additive kind.
  Model example = load_model_file(pfgen_test::example("basin2006_quadratic.yaml"));
  require_exact(assess_exactness(example, FilterKind::Optimal), "Basin-Perez-Skliar 2006");
  require_exact(assess_exactness(example, FilterKind::Additive), "Basin-Perez-Skliar 2006");
}

TEST_CASE("exactness: a square but singular A fails paper 000", "[exactness][unit]") {
  ModelBuilder b("paper000_singular");
  GiNaC::symbol x1 = b.state("x1"), x2 = b.state("x2");
  // Both rows see x1 only: A is singular, and the paper-001 block A1 (the rows
  // seeing x1) is 2 x 1.
  b.drift({tenth * x1 * x1, tenth * x2}).diffusion({{1}, {1}}).observation({0, 0}, {{1, 0}, {2, 0}}, {{1, 0}, {0, 1}});
  Model model = b.build();
  require_approximation(assess_exactness(model, FilterKind::Optimal),
                        {{"Kalman-Bucy", "drift of x1 has degree 2"},
                         {"Basin-Perez-Skliar 2006", "A is singular"},
                         {"Basin-Perez-Skliar 2006 linear case", "drift of x1 has degree 2"},
                         {"Basin-Skliar", "the nonlinear components (x1) are seen by 2 observation rows, so A1 is not square"}});
}

// ---------------------------------------------------------------------------
// Basin, Perez & Skliar 2006's linear case (eqs 10-11): f affine and g affine, for any A.
// ---------------------------------------------------------------------------
TEST_CASE("exactness: paper 000 linear case for affine f and affine multiplicative g", "[exactness][unit]") {
  ModelBuilder b("paper000_linear");
  GiNaC::symbol x1 = b.state("x1"), x2 = b.state("x2");
  b.drift({x2, -x1 + 1}).diffusion({{tenth * x1 + 1}, {numeric(1, 5) * x2}}).observation({0}, {{1, 0}}, {{1}});
  Model model = b.build();
  require_exact(assess_exactness(model, FilterKind::Optimal), "Basin-Perez-Skliar 2006 linear case");
  // The EKF uses g(m) g(m)^T where E[g g^T] has the extra b1 P b1^T: not exact.
  require_approximation(assess_exactness(model, FilterKind::Ekf),
                        {{"Kalman-Bucy", "the diffusion depends on the state (multiplicative noise)"}});
}

TEST_CASE("exactness: paper 000 linear case with G = g g^T given directly", "[exactness][unit]") {
  SECTION("G of degree 2 (g affine) is exact") {
    ModelBuilder b("paper000_linear_G");
    GiNaC::symbol x1 = b.state("x1"), x2 = b.state("x2");
    b.drift({x2, -x1})
        .diffusion_covariance({{x1 * x1 + 1, x1 * x2}, {x1 * x2, x2 * x2}})
        .observation({0}, {{1, 0}}, {{1}});
    require_exact(assess_exactness(b.build(), FilterKind::Optimal), "Basin-Perez-Skliar 2006 linear case");
  }
  SECTION("G of degree 3 is not") {
    ModelBuilder b("paper000_cubic_G");
    GiNaC::symbol x1 = b.state("x1"), x2 = b.state("x2");
    b.drift({x2, -x1}).diffusion_covariance({{x1 * x1 * x2 + 1, 0}, {0, 1}}).observation({0}, {{1, 0}}, {{1}});
    require_approximation(assess_exactness(b.build(), FilterKind::Optimal),
                          {{"Kalman-Bucy", "the diffusion depends on the state (multiplicative noise)"},
                           {"Basin-Perez-Skliar 2006", "A is 1 x 2, not square"},
                           {"Basin-Perez-Skliar 2006 linear case", "G = g g^T has degree above 2 (g not affine)"},
                           {"Basin-Skliar", "no nonlinear components"}});
  }
}

TEST_CASE("exactness: affine f with quadratic g and non-square A is an approximation", "[exactness][unit]") {
  ModelBuilder b("linear_quadratic_noise");
  GiNaC::symbol x1 = b.state("x1"), x2 = b.state("x2");
  b.drift({x2, -x1}).diffusion({{tenth * x1 * x1}, {0}}).observation({0}, {{1, 0}}, {{1}});
  require_approximation(assess_exactness(b.build(), FilterKind::Optimal),
                        {{"Kalman-Bucy", "the diffusion depends on the state (multiplicative noise)"},
                         {"Basin-Perez-Skliar 2006", "A is 1 x 2, not square"},
                         {"Basin-Perez-Skliar 2006 linear case", "g is not affine in the state"},
                         {"Basin-Skliar", "no nonlinear components"}});
}

// ---------------------------------------------------------------------------
// Basin & Skliar: nonlinear x1 measured through a square invertible block, linear
// self-contained x2, block-diagonal A and B B^T, additive noise.
// ---------------------------------------------------------------------------
TEST_CASE("exactness: paper 001 for the example file", "[exactness][unit]") {
  Model model = load_model_file(pfgen_test::example("basin_skliar_partial.yaml"));
  require_exact(assess_exactness(model, FilterKind::Optimal), "Basin-Skliar");
  CHECK(derive_filter(model, FilterKind::Optimal).exactness.condition == "Basin-Skliar");
  // The same model built in code.
  require_exact(assess_exactness(paper001_variant({}), FilterKind::Optimal), "Basin-Skliar");
}

TEST_CASE("exactness: paper 001 allows f1 nonlinear in x2 and a partly measured linear block", "[exactness][unit]") {
  ModelBuilder b("paper001_three_states");
  GiNaC::symbol x1 = b.state("x1"), x2 = b.state("x2"), x3 = b.state("x3");
  // x1 nonlinear (also in x2), (x2, x3) linear and self-contained; y1 sees x1,
  // y2 sees x3, x2 unmeasured.
  b.drift({x1 * x1 + x2 * x2, tenth * x2 + x3, -x2})
      .diffusion({{1, 0}, {0, 1}, {0, 0}})
      .observation({0, 0}, {{1, 0, 0}, {0, 0, 1}}, {{1, 0}, {0, 2}});
  require_exact(assess_exactness(b.build(), FilterKind::Optimal), "Basin-Skliar");
}

TEST_CASE("exactness: paper 001 variants that break one condition each", "[exactness][unit]") {
  const Failure kalman{"Kalman-Bucy", "drift of x1 has degree 2"};
  const Failure p000{"Basin-Perez-Skliar 2006", "A is 1 x 2, not square"};
  const Failure p000_linear{"Basin-Perez-Skliar 2006 linear case", "drift of x1 has degree 2"};

  SECTION("the linear block depends on x1") {
    Paper001Variant v;
    v.f2 = "coupled";
    require_approximation(assess_exactness(paper001_variant(v), FilterKind::Optimal),
                          {kalman, p000, p000_linear,
                           {"Basin-Skliar", "no components with their own linear dynamics to leave unmeasured"}});
  }
  SECTION("A mixes x1 and x2") {
    Paper001Variant v;
    v.mixed_observation = true;
    require_approximation(
        assess_exactness(paper001_variant(v), FilterKind::Optimal),
        {kalman, p000, p000_linear,
         {"Basin-Skliar", "observation row 1 mixes nonlinear (x1) and linear (x2) components: A is not block-diagonal"}});
  }
  SECTION("multiplicative noise") {
    Paper001Variant v;
    v.multiplicative = true;
    require_approximation(assess_exactness(paper001_variant(v), FilterKind::Optimal),
                          {kalman, p000, p000_linear,
                           {"Basin-Skliar", "the diffusion depends on the state (multiplicative noise)"}});
  }
  SECTION("multiplicative noise, but the additive kinds use the additive g") {
    Paper001Variant v;
    v.multiplicative = true;
    v.additive = true;
    Model model = paper001_variant(v);
    CHECK_FALSE(assess_exactness(model, FilterKind::Optimal).exact);
    ExactnessReport additive = assess_exactness(model, FilterKind::Additive);
    require_exact(additive, "Basin-Skliar");
    CHECK_THAT(additive.explanation, Contains("additive diffusion"));
  }
}

TEST_CASE("exactness: paper 001 fails on a singular A1 block and on correlated observation noise", "[exactness][unit]") {
  SECTION("A1 singular") {
    ModelBuilder b("paper001_singular_block");
    GiNaC::symbol x1 = b.state("x1"), x2 = b.state("x2"), x3 = b.state("x3");
    b.drift({tenth * x1 * x1 + x3, tenth * x2 * x2, tenth * x3})
        .diffusion({{1}, {1}, {1}})
        .observation({0, 0}, {{1, 1, 0}, {2, 2, 0}}, {{1, 0}, {0, 1}});
    require_approximation(assess_exactness(b.build(), FilterKind::Optimal),
                          {{"Kalman-Bucy", "drift of x1 has degree 2"},
                           {"Basin-Perez-Skliar 2006", "A is 2 x 3, not square"},
                           {"Basin-Perez-Skliar 2006 linear case", "drift of x1 has degree 2"},
                           {"Basin-Skliar", "the block A1 measuring (x1, x2) is singular"}});
  }
  SECTION("y1 and y2 correlated") {
    ModelBuilder b("paper001_correlated");
    GiNaC::symbol x1 = b.state("x1"), x2 = b.state("x2"), x3 = b.state("x3");
    b.drift({tenth * x1 * x1 + x2, tenth * x2, tenth * x3})
        .diffusion({{1}, {1}, {1}})
        .observation({0, 0}, {{1, 0, 0}, {0, 1, 0}}, {{1, 0}, {1, 1}});  // B B^T = [1 1; 1 2]
    require_approximation(assess_exactness(b.build(), FilterKind::Optimal),
                          {{"Kalman-Bucy", "drift of x1 has degree 2"},
                           {"Basin-Perez-Skliar 2006", "A is 2 x 3, not square"},
                           {"Basin-Perez-Skliar 2006 linear case", "drift of x1 has degree 2"},
                           {"Basin-Skliar", "observation noises of y1 and y2 are correlated"}});
  }
}

// ---------------------------------------------------------------------------
// No condition holds: the report names each failed condition.
// ---------------------------------------------------------------------------
TEST_CASE("exactness: approximation names every failed condition", "[exactness][unit]") {
  Model model = load_model_text(approximation_yaml, "<approximation>");
  require_approximation(assess_exactness(model, FilterKind::Optimal), approximation_failures);
  // The same model built in code gives the same report.
  ModelBuilder b("approximation_two_state");
  GiNaC::symbol x1 = b.state("x1"), x2 = b.state("x2");
  b.drift({tenth * x1 * x1 + x2, tenth * x1 * x2}).diffusion({{tenth}, {0}}).observation({0}, {{1, 0}}, {{1}});
  ExactnessReport built = assess_exactness(b.build(), FilterKind::Optimal);
  require_approximation(built, approximation_failures);
  CHECK(derive_filter(model, FilterKind::Optimal).exactness.failed == built.failed);
}

// ---------------------------------------------------------------------------
// Extended Kalman-Bucy kinds: exact only in the Kalman-Bucy case, even where
// the optimal filter is exact under Basin, Perez & Skliar 2006 or Basin & Skliar.
// ---------------------------------------------------------------------------
TEST_CASE("exactness: ekf kinds are approximations unless Kalman-Bucy", "[exactness][ekf][unit]") {
  Model p000 = load_model_file(pfgen_test::example("basin2006_quadratic.yaml"));
  for (FilterKind kind : {FilterKind::Ekf, FilterKind::EkfAdditive}) {
    INFO("kind " << filter_kind_name(kind));
    require_approximation(assess_exactness(p000, kind), {{"Kalman-Bucy", "drift of x has degree 2"}});
    CHECK_FALSE(derive_filter(p000, kind).exactness.exact);
  }
  Model p001 = load_model_file(pfgen_test::example("basin_skliar_partial.yaml"));
  require_approximation(assess_exactness(p001, FilterKind::Ekf), {{"Kalman-Bucy", "drift of x1 has degree 2"}});
  // Kalman-Bucy models are covered in the first test case (ekf kinds exact there).
}

// ---------------------------------------------------------------------------
// The diagnostic as `pfgen derive` prints it.
// ---------------------------------------------------------------------------
TEST_CASE("exactness: pfgen derive prints the diagnostic in text, latex and json", "[exactness][cli][integration]") {
  TemporaryModelFile approximation(approximation_yaml);
  const std::string paper000 = pfgen_test::example("basin2006_quadratic.yaml");

  SECTION("text") {
    std::string out = derive_output(approximation.path(), "optimal", "text");
    CHECK_THAT(out, Contains("exactness: approximation:"));
    for (const auto& f : approximation_failures)
      CHECK_THAT(out, Contains("\n  failed: " + f.condition + ": " + f.reason + "\n"));

    std::string exact = derive_output(paper000, "optimal", "text");
    CHECK_THAT(exact, Contains("exactness: exact:"));
    CHECK_THAT(exact, Contains("(Basin, Perez & Skliar 2006)"));
    CHECK_THAT(exact, !Contains("paper 0"));
    CHECK_THAT(exact, !Contains("failed:"));

    std::string ekf = derive_output(paper000, "ekf", "text");
    CHECK_THAT(ekf, Contains("exactness: approximation:"));
    CHECK_THAT(ekf, Contains("\n  failed: Kalman-Bucy: drift of x has degree 2\n"));
  }
  SECTION("latex") {
    std::string out = derive_output(approximation.path(), "optimal", "latex");
    CHECK_THAT(out, Contains("\\textbf{Exactness:} approximation:"));
    CHECK_THAT(out, Contains("\\begin{itemize}"));
    for (const auto& f : approximation_failures)
      CHECK_THAT(out, Contains("\\item " + f.condition + ": " + f.latex_reason + "\n"));

    std::string exact = derive_output(paper000, "optimal", "latex");
    CHECK_THAT(exact, Contains("\\textbf{Exactness:} exact: $A$ is square and invertible, so $x - m$ is "
                               "conditionally Gaussian (Basin, Perez \\& Skliar 2006)"));
    CHECK_THAT(exact, !Contains("\\begin{itemize}"));
  }
  SECTION("json") {
    std::string out = compact_json(derive_output(approximation.path(), "optimal", "json"));
    CHECK_THAT(out, Contains("\"exact\":false"));
    CHECK_THAT(out, Contains("\"condition\":\"none\""));
    std::string failed = "\"failed\":[";
    for (std::size_t k = 0; k < approximation_failures.size(); ++k)
      failed += std::string(k ? "," : "") + "\"" + approximation_failures[k].condition + ": " +
                approximation_failures[k].reason + "\"";
    CHECK_THAT(out, Contains(failed + "]"));

    std::string exact = compact_json(derive_output(paper000, "optimal", "json"));
    CHECK_THAT(exact, Contains("\"exact\":true"));
    CHECK_THAT(exact, Contains("\"condition\":\"Basin-Perez-Skliar 2006\""));
    CHECK_THAT(exact, Contains("\"failed\":[]"));

    std::string ekf = compact_json(derive_output(paper000, "ekf-additive", "json"));
    CHECK_THAT(ekf, Contains("\"exact\":false"));
    CHECK_THAT(ekf, Contains("\"failed\":[\"Kalman-Bucy: drift of x has degree 2\"]"));
  }
}
