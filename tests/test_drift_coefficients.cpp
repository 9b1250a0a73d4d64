// The coefficient form A, A1, A2, A3, E, E1 (derivation/drift_coefficients.hpp) and its reports
// (`pfgen derive --coefficients`). The independent check rebuilds f from the coefficients as the
// convention's sums, sum_j A1_ij x_j + sum_jk A2_ijk x_j x_k + ..., over every index (not from the
// extraction's monomials), and compares it with the model's drift symbolically; the hand-written
// cases fix the symmetric split (c x1 x2 gives c/2 to A2_i12 and to A2_i21).
#include <catch2/catch.hpp>

#include <algorithm>
#include <filesystem>
#include <random>
#include <string>
#include <vector>

#include "pfgen/derivation/drift_coefficients.hpp"
#include "pfgen/model/model_builder.hpp"
#include "pfgen/model/model_error.hpp"
#include "pfgen/model/yaml_model_loader.hpp"
#include "support/cli_helpers.hpp"
#include "support/json_reader.hpp"
#include "support/random_polynomial_system.hpp"

using namespace pfgen_test;
using pfgen::DriftCoefficients;
using pfgen::Model;

namespace {

std::string fixture(const std::string& name) { return test_data_dir() + "/coefficients/" + name; }

// f_i rebuilt as the convention writes it: dense sums over every j, k, l of the tensors' entries.
GiNaC::ex rebuilt_drift(const DriftCoefficients& c, const std::vector<GiNaC::symbol>& x, std::uint32_t i) {
  const auto n = static_cast<std::uint32_t>(c.n);
  GiNaC::ex f = c.A[i];
  for (std::uint32_t j = 0; j < n; ++j) {
    f += c.A1[i][j] * x[j];
    for (std::uint32_t k = 0; k < n; ++k) {
      f += c.A2_at(i, j, k) * x[j] * x[k];
      for (std::uint32_t l = 0; l < n; ++l) f += c.A3_at(i, j, k, l) * x[j] * x[k] * x[l];
    }
  }
  return f;
}

void check_rebuilds_drift(const Model& model) {
  INFO("model " << model.name);
  const DriftCoefficients c = pfgen::extract_drift_coefficients(model);
  REQUIRE(c.n == model.n());
  REQUIRE(c.A.size() == model.n());
  REQUIRE(c.A1.size() == model.n());
  for (std::uint32_t i = 0; i < model.n(); ++i) {
    INFO("drift[" << i + 1 << "] = " << model.drift[i]);
    CHECK((rebuilt_drift(c, model.states, i) - model.drift[i]).expand().is_zero());
  }
}

// Every stored entry is nonzero and its index symmetric: the same value under each order of the
// lower indices.
void check_symmetric(const pfgen::TensorEntries& tensor, std::size_t rank) {
  for (const auto& [index, value] : tensor) {
    REQUIRE(index.size() == rank);
    CHECK(!value.is_zero());
    std::vector<std::uint32_t> lower(index.begin() + 1, index.end());
    std::sort(lower.begin(), lower.end());
    do {
      std::vector<std::uint32_t> other{index.front()};
      other.insert(other.end(), lower.begin(), lower.end());
      auto it = tensor.find(other);
      REQUIRE(it != tensor.end());
      CHECK((it->second - value).expand().is_zero());
    } while (std::next_permutation(lower.begin(), lower.end()));
  }
}

bool same(const GiNaC::ex& a, const GiNaC::ex& b) { return (a - b).expand().is_zero(); }

}  // namespace

TEST_CASE("coefficient form of the reactor: hand-written A, A1, A2, E, E1", "[coefficients][unit]") {
  const Model model = pfgen::load_model_file(fixture("reactor.yaml"));
  const DriftCoefficients c = pfgen::extract_drift_coefficients(model);
  // f = (-2 x1, x1 - x2 - x2^2)
  CHECK(same(c.A[0], 0));
  CHECK(same(c.A[1], 0));
  CHECK(same(c.A1[0][0], -2));
  CHECK(same(c.A1[0][1], 0));
  CHECK(same(c.A1[1][0], 1));
  CHECK(same(c.A1[1][1], -1));
  REQUIRE(c.A2.size() == 1);
  CHECK(same(c.A2_at(1, 1, 1), -1));
  CHECK(c.A3.empty());
  const pfgen::ObservationCoefficients o = pfgen::extract_observation_coefficients(model);
  CHECK(o.kind == pfgen::ObservationKind::Continuous);
  REQUIRE(o.E.size() == 2);
  CHECK(same(o.E[0], 0));
  CHECK(same(o.E[1], 0));
  CHECK(same(o.E1[0][0], 1));
  CHECK(same(o.E1[0][1], 0));
  CHECK(same(o.E1[1][0], 0));
  CHECK(same(o.E1[1][1], 1));
  check_rebuilds_drift(model);
}

TEST_CASE("coefficient form of the satellite: the cubic term split over three orders", "[coefficients][unit]") {
  const Model model = pfgen::load_model_file(fixture("satellite.yaml"));
  const DriftCoefficients c = pfgen::extract_drift_coefficients(model);
  // f1 = 0.5 x2 + 0.5 x1^2 x2: A1_12 = 1/2, A3_1jkl = 1/6 d3f1 = 1/6 on (1,1,2), (1,2,1), (2,1,1).
  CHECK(same(c.A[0], 0));
  CHECK(same(c.A1[0][1], GiNaC::numeric(1, 2)));
  CHECK(same(c.A1[0][0], 0));
  CHECK(same(c.A1[1][0], 0));
  CHECK(same(c.A1[1][1], 0));
  CHECK(c.A2.empty());
  REQUIRE(c.A3.size() == 3);
  CHECK(same(c.A3_at(0, 0, 0, 1), GiNaC::numeric(1, 6)));
  CHECK(same(c.A3_at(0, 0, 1, 0), GiNaC::numeric(1, 6)));
  CHECK(same(c.A3_at(0, 1, 0, 0), GiNaC::numeric(1, 6)));
  CHECK(same(c.A3_at(0, 1, 1, 0), 0));
  const pfgen::ObservationCoefficients o = pfgen::extract_observation_coefficients(model);
  REQUIRE(o.E1.size() == 1);
  CHECK(same(o.E1[0][0], 1));
  CHECK(same(o.E1[0][1], 0));
  check_rebuilds_drift(model);
}

TEST_CASE("coefficient form with parameters and time: hand-written entries", "[coefficients][unit]") {
  const Model model = pfgen::load_model_file(fixture("mixed.yaml"));
  const DriftCoefficients c = pfgen::extract_drift_coefficients(model);
  const GiNaC::ex a = model.parameters[0].symbol, b = model.parameters[1].symbol, t = model.time;
  // f1 = a x1 - b sin(t) x2^2 + x1 x2 x3 + 1/3
  CHECK(same(c.A[0], GiNaC::numeric(1, 3)));
  CHECK(same(c.A1[0][0], a));
  CHECK(same(c.A2_at(0, 1, 1), -b * GiNaC::sin(t)));
  for (const auto& order : std::vector<std::vector<std::uint32_t>>{{0, 1, 2}, {0, 2, 1}, {1, 0, 2}, {1, 2, 0}, {2, 0, 1}, {2, 1, 0}})
    CHECK(same(c.A3_at(0, order[0], order[1], order[2]), GiNaC::numeric(1, 6)));
  // f2 = 1 + t - x1^3 + 3 x2^2 x3
  CHECK(same(c.A[1], 1 + t));
  CHECK(same(c.A3_at(1, 0, 0, 0), -1));
  CHECK(same(c.A3_at(1, 1, 1, 2), 1));
  CHECK(same(c.A3_at(1, 1, 2, 1), 1));
  CHECK(same(c.A3_at(1, 2, 1, 1), 1));
  // f3 = -x3 + a x1 x3 + t x2
  CHECK(same(c.A1[2][2], -1));
  CHECK(same(c.A1[2][1], t));
  CHECK(same(c.A2_at(2, 0, 2), a / 2));
  CHECK(same(c.A2_at(2, 2, 0), a / 2));
  CHECK(c.A2.size() == 3);
  CHECK(c.A3.size() == 6 + 1 + 3);
  const pfgen::ObservationCoefficients o = pfgen::extract_observation_coefficients(model);
  CHECK(same(o.E[0], GiNaC::numeric(1, 4)));
  CHECK(same(o.E[1], a * t));
  CHECK(same(o.E1[1][1], b));
  check_symmetric(c.A2, 3);
  check_symmetric(c.A3, 4);
  check_rebuilds_drift(model);
}

TEST_CASE("coefficient form rebuilds the drift of random systems of degree 0 to 3", "[coefficients][unit]") {
  std::mt19937 rng(20261123);
  for (int k = 0; k < 60; ++k) {
    pfgen_test::RandomSystemOptions options;
    options.n = 1 + static_cast<std::size_t>(k % 4);
    options.drift_degree = static_cast<unsigned>(k % 4);
    options.max_terms = 5;
    options.dense = k % 10 == 9;  // every monomial up to the degree
    const RandomSystem system = make_random_system(rng, options, "random_" + std::to_string(k));
    check_rebuilds_drift(system.model);
    const DriftCoefficients c = pfgen::extract_drift_coefficients(system.model);
    check_symmetric(c.A2, 3);
    check_symmetric(c.A3, 4);
  }
}

TEST_CASE("coefficient form of sampled and delayed observations", "[coefficients][unit]") {
  const Model sampled = pfgen::load_model_file(test_data_dir() + "/sampled_two_observations.yaml");
  const pfgen::ObservationCoefficients s = pfgen::extract_observation_coefficients(sampled);
  CHECK(s.kind == pfgen::ObservationKind::Sampled);
  CHECK(same(s.E[0], GiNaC::numeric(1, 10)));            // C0
  CHECK(same(s.E1[0][1], sampled.parameters[1].symbol));  // C_12 = c
  CHECK(same(s.E1[1][0], GiNaC::numeric(-3, 10)));
  check_rebuilds_drift(sampled);

  const Model delayed = pfgen::load_model_file(test_data_dir() + "/delayed_scalar.yaml");
  const pfgen::ObservationCoefficients d = pfgen::extract_observation_coefficients(delayed);
  CHECK(d.kind == pfgen::ObservationKind::Delayed);
  CHECK(same(d.E[0], GiNaC::numeric(3, 10)));  // A0
  CHECK(same(d.E1[0][0], 2));                  // A
  const DriftCoefficients c = pfgen::extract_drift_coefficients(delayed);
  CHECK(same(c.A1[0][0], -1));
  CHECK(same(c.A2_at(0, 0, 0), GiNaC::numeric(1, 2)));
}

TEST_CASE("coefficient form refuses a drift of degree 4, naming file, field and row", "[coefficients][unit]") {
  const std::string path = fixture("quartic.yaml");
  const Model model = pfgen::load_model_file(path);
  const std::string expected = path +
                               ": error: field 'drift', row 2: drift[2] has degree 4; the coefficient form A..A3 "
                               "holds degree <= 3";
  for (int attempt = 0; attempt < 2; ++attempt) {
    try {
      if (attempt == 0)
        pfgen::check_coefficient_form_degree(model);
      else
        (void)pfgen::extract_drift_coefficients(model);
      FAIL("a degree-4 drift was accepted");
    } catch (const pfgen::ModelError& e) {
      CHECK(std::string(e.what()) == expected);
      CHECK(e.field() == "drift");
      CHECK(e.row() == 2);
    }
  }
  // Degree 3 passes: the limit is the form's, not a lower one.
  pfgen::ModelBuilder b("cubic");
  const GiNaC::symbol x = b.state("x");
  b.drift({-GiNaC::pow(x, 3)});
  b.diffusion({{1}});
  b.observation({0}, {{1}}, {{1}});
  CHECK_NOTHROW(pfgen::check_coefficient_form_degree(b.build()));
}

TEST_CASE("derive --coefficients prints text, LaTeX and JSON, byte-identical run to run", "[coefficients][integration]") {
  const std::string model = fixture("mixed.yaml");
  for (const std::string format : {"text", "latex", "json"}) {
    INFO("--format " << format);
    const ProcessResult first = run_pfgen({"derive", model, "--coefficients", "--format", format});
    const ProcessResult second = run_pfgen({"derive", model, "--coefficients", "--format", format});
    INFO("stderr: " << first.err);
    REQUIRE(first.exit_code == 0);
    CHECK(first.err.empty());
    CHECK(first.out == second.out);
    CHECK(!first.out.empty());
  }

  const std::string text = run_pfgen({"derive", model, "--coefficients"}).out;
  CHECK(text.find("coefficient form: f_i(x,t) = A_i + sum_j A1_ij x_j + sum_jk A2_ijk x_j x_k") != std::string::npos);
  CHECK(text.find("A = [1/3, 1 + t, 0]\n") != std::string::npos);
  CHECK(text.find("A1 = [[a, 0, 0], [0, 0, 0], [0, t, -1]]\n") != std::string::npos);
  CHECK(text.find("A2[1][2][2] = -b*sin(t)\n") != std::string::npos);
  CHECK(text.find("A2[3][1][3] = 0.5*a\n") != std::string::npos);
  CHECK(text.find("A3[1][1][2][3] = 1/6\n") != std::string::npos);
  CHECK(text.find("A3[2][1][1][1] = -1\n") != std::string::npos);
  CHECK(text.find("E = [0.25, a*t]\n") != std::string::npos);
  CHECK(text.find("E1 = [[1, 0, 0], [0, b, 1]]\n") != std::string::npos);
  // Lexicographic order of the entries: A2[1][2][2] before A2[3][1][3] before A2[3][3][1].
  CHECK(text.find("A2[1][2][2]") < text.find("A2[3][1][3]"));
  CHECK(text.find("A2[3][1][3]") < text.find("A2[3][3][1]"));

  const JsonValue j = parse_json(run_pfgen({"derive", model, "--coefficients", "--format", "json"}).out);
  CHECK(j["model"].text == "coefficients_mixed");
  CHECK(j["index_base"].number == 1);
  REQUIRE(j["A"].items.size() == 3);
  CHECK(j["A"][1].text == "1 + t");
  REQUIRE(j["A1"].items.size() == 3);
  CHECK(j["A1"][2][1].text == "t");
  REQUIRE(j["A2"].items.size() == 3);
  CHECK(j["A2"][0]["index"][0].number == 1);
  CHECK(j["A2"][0]["index"][1].number == 2);
  CHECK(j["A2"][0]["index"][2].number == 2);
  CHECK(j["A2"][0]["value"].text == "-b*sin(t)");
  CHECK(j["A3"].items.size() == 10);
  CHECK(j["A3"][0]["index"].items.size() == 4);
  CHECK(j["observation"]["kind"].text == "continuous");
  CHECK(j["observation"]["E"][1].text == "a*t");
  CHECK(j["observation"]["E1"][1][1].text == "b");

  const std::string latex = run_pfgen({"derive", model, "--coefficients", "--format", "latex"}).out;
  CHECK(latex.find("\\paragraph{Coefficient form.}") == 0);
  CHECK(latex.find("(A_{2})_{1,2,2} &= -\\sin\\left(t\\right)\\,b") != std::string::npos);
  CHECK(latex.find("\\begin{align*}") != std::string::npos);
}

TEST_CASE("derive --coefficients names a sampled observation's C0 and C, a delayed one's h", "[coefficients][integration]") {
  const ProcessResult sampled =
      run_pfgen({"derive", test_data_dir() + "/sampled_two_observations.yaml", "--coefficients"});
  REQUIRE(sampled.exit_code == 0);
  CHECK(sampled.out.find("observation: sampled, y_k = C0 + C x(t_k) + Uv v_k; it has no rate E + E1 x") !=
        std::string::npos);
  CHECK(sampled.out.find("C0 = [0.1, -0.2]\n") != std::string::npos);
  CHECK(sampled.out.find("C = [[1, c], [-0.3, 2]]\n") != std::string::npos);
  CHECK(sampled.out.find("\nE = ") == std::string::npos);
  const JsonValue j = parse_json(
      run_pfgen({"derive", test_data_dir() + "/sampled_two_observations.yaml", "--coefficients", "--format", "json"}).out);
  CHECK(j["observation"]["kind"].text == "sampled");
  CHECK(j["observation"]["C"][0][1].text == "c");
  CHECK(!j["observation"].has("E"));

  const ProcessResult delayed = run_pfgen({"derive", test_data_dir() + "/delayed_scalar.yaml", "--coefficients"});
  REQUIRE(delayed.exit_code == 0);
  CHECK(delayed.out.find("observation: dy = (E + E1 x(t-h)) dt + B dW2 with h = 0.5; E = A0, E1 = A\n") !=
        std::string::npos);
  CHECK(delayed.out.find("A2[1][1][1] = 0.5\n") != std::string::npos);
}

TEST_CASE("derive --coefficients: one error line for degree 4 and for --filter", "[coefficients][integration]") {
  const std::string quartic = fixture("quartic.yaml");
  for (const std::string format : {"text", "latex", "json"}) {
    const ProcessResult r = run_pfgen({"derive", quartic, "--coefficients", "--format", format});
    CHECK(r.exit_code == 1);
    CHECK(r.out.empty());
    CHECK(r.err == "pfgen: " + quartic +
                       ": error: field 'drift', row 2: drift[2] has degree 4; the coefficient form A..A3 holds "
                       "degree <= 3\n");
  }
  const ProcessResult latex = run_pfgen({"latex", quartic, "--coefficients", "-o", "/nonexistent-dir/x.tex"});
  CHECK(latex.exit_code == 1);
  CHECK(latex.err.find("drift[2] has degree 4") != std::string::npos);
  // Without --coefficients the model is an ordinary one: its filters derive.
  CHECK(run_pfgen({"derive", quartic}).exit_code == 0);

  const ProcessResult both = run_pfgen({"derive", fixture("reactor.yaml"), "--coefficients", "--filter", "ekf"});
  CHECK(both.exit_code == 1);
  CHECK(both.err ==
        "pfgen: error: --coefficients: shows the model's coefficient form, not a filter's equations; drop --filter\n");
}

TEST_CASE("pfgen latex --coefficients compiles with pdflatex", "[coefficients][compiler]") {
  if (run_process("command -v pdflatex").exit_code != 0)
    FAIL("pdflatex is not on PATH: the LaTeX compile tests need it (install texlive-latex-base)");
  TempDir dir;
  // The document with the section, and derive's fragment wrapped in a minimal document.
  const std::string fragment = run_pfgen({"derive", fixture("mixed.yaml"), "--coefficients", "--format", "latex"}).out;
  write_file(dir.file("fragment.tex"), "\\documentclass{article}\n\\usepackage{amsmath}\n\\begin{document}\n" +
                                           fragment + "\\end{document}\n");
  for (const std::string& model : {fixture("mixed.yaml"), fixture("satellite.yaml"),
                                   test_data_dir() + "/sampled_two_observations.yaml"}) {
    const std::string stem = "doc_" + std::to_string(dir.entries().size());
    const ProcessResult written = run_pfgen({"latex", model, "--coefficients", "-o", dir.file(stem + ".tex")});
    INFO("pfgen stderr: " << written.err);
    REQUIRE(written.exit_code == 0);
    CHECK(read_file(dir.file(stem + ".tex")).find("\\section*{Coefficient form}") != std::string::npos);
  }
  for (const auto& name : dir.entries()) {
    if (name.size() < 4 || name.substr(name.size() - 4) != ".tex") continue;
    INFO("document " << name);
    const ProcessResult compiled = run_process("cd " + shell_quote(dir.path()) +
                                               " && pdflatex -interaction=nonstopmode -halt-on-error " +
                                               shell_quote(name) + " </dev/null");
    INFO("pdflatex output (tail): " << compiled.out.substr(compiled.out.size() > 2000 ? compiled.out.size() - 2000 : 0));
    CHECK(compiled.exit_code == 0);
    const std::string stem = name.substr(0, name.size() - 4);
    CHECK(std::filesystem::exists(dir.file(stem + ".pdf")));
  }
}
