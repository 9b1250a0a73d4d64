// `pfgen latex` writes a standalone document that pdflatex compiles without
// errors. pdflatex (texlive-latex-base) is a test requirement: when it is not
// on PATH these tests fail rather than pass silently.
#include <catch2/catch.hpp>

#include <filesystem>
#include <sstream>
#include <string>
#include <vector>

#include "pfgen/kinds/filter_kinds.hpp"
#include "support/cli_helpers.hpp"

using namespace pfgen_test;

namespace {

bool pdflatex_available() { return run_process("command -v pdflatex").exit_code == 0; }

// Lines of the log that report a TeX error ("! Undefined control sequence." ...).
std::vector<std::string> error_lines(const std::string& log) {
  std::vector<std::string> out;
  std::istringstream in(log);
  std::string line;
  while (std::getline(in, line))
    if (line.rfind("! ", 0) == 0 || line == "!") out.push_back(line);
  return out;
}

// Writes MODEL's document with `pfgen latex` into `dir` and compiles it.
void check_compiles(const std::string& model, const std::string& filters, const TempDir& dir,
                    const std::string& stem) {
  INFO("model " << model << (filters.empty() ? std::string(" (every filter kind)") : " --filter " + filters));
  const std::string tex = dir.file(stem + ".tex");
  std::vector<std::string> args = {"latex", model, "-o", tex};
  if (!filters.empty()) {
    args.push_back("--filter");
    args.push_back(filters);
  }
  ProcessResult written = run_pfgen(args);
  INFO("pfgen stderr: " << written.err);
  REQUIRE(written.exit_code == 0);
  CHECK(written.out.empty());
  const std::string document = read_file(tex);
  CHECK(document.find("\\documentclass") != std::string::npos);
  CHECK(document.find("\\begin{document}") != std::string::npos);
  CHECK(document.find("\\end{document}") != std::string::npos);

  const std::string command = "cd " + shell_quote(dir.path()) +
                              " && pdflatex -interaction=nonstopmode -halt-on-error " + shell_quote(stem + ".tex") +
                              " </dev/null";
  ProcessResult compiled = run_process(command);
  const std::string log = read_file(dir.file(stem + ".log"));
  const std::vector<std::string> errors = error_lines(log);
  std::string first_errors;
  for (std::size_t k = 0; k < errors.size() && k < 5; ++k) first_errors += errors[k] + "\n";
  INFO("TeX errors:\n" << first_errors);
  INFO("pdflatex output (tail): " << compiled.out.substr(compiled.out.size() > 2000 ? compiled.out.size() - 2000 : 0));
  CHECK(compiled.exit_code == 0);
  CHECK(!log.empty());
  CHECK(errors.empty());
  CHECK(log.find("Emergency stop") == std::string::npos);
  CHECK(std::filesystem::exists(dir.file(stem + ".pdf")));
  if (std::filesystem::exists(dir.file(stem + ".pdf"))) CHECK(std::filesystem::file_size(dir.file(stem + ".pdf")) > 1000);
}

}  // namespace

TEST_CASE("pdflatex is installed for the LaTeX tests", "[latex][pdflatex][compiler]") {
  if (!pdflatex_available())
    FAIL("pdflatex is not on PATH: the LaTeX compile tests need it (install texlive-latex-base)");
  SUCCEED("pdflatex found");
}

TEST_CASE("pfgen latex documents of the examples compile with pdflatex", "[latex][pdflatex][compiler]") {
  if (!pdflatex_available())
    FAIL("pdflatex is not on PATH: the LaTeX compile tests need it (install texlive-latex-base)");
  TempDir dir;
  // Every kind each model supports (the default), then each kind on its own.
  check_compiles(example("basin2006_quadratic.yaml"), "", dir, "basin2006_all");
  check_compiles(example("basin_skliar_partial.yaml"), "", dir, "skliar_all");
  for (const auto& info : pfgen::filter_kinds())  // basin2006 supports every mean-square continuous kind
    if (info.observations.front() == pfgen::ObservationKind::Continuous &&
        info.criterion == pfgen::Criterion::MeanSquare)
      check_compiles(example("basin2006_quadratic.yaml"), info.name, dir, "basin2006_" + info.name);
  // Sampled observations: every sampled kind (the default), prediction and update apart.
  check_compiles(example("allahyani_date_example1_gamma1.yaml"), "", dir, "allahyani_gamma1_all");
  check_compiles(example("allahyani_date_example1_gamma05.yaml"), "", dir, "allahyani_gamma05_all");
  check_compiles(example("basin_skliar_partial.yaml"), "ekf", dir, "skliar_ekf");
  // Delayed observations: every delay kind (the default), with Phi* and the x* equation.
  check_compiles(example("delay_linear.yaml"), "", dir, "delay_linear_all");
  // The risk criterion: optimal, ekf and risk-sensitive, with the criterion paragraph.
  check_compiles(test_data_dir() + "/risk_scalar.yaml", "", dir, "risk_scalar_all");
  CHECK(read_file(dir.file("risk_scalar_all.tex")).find("Risk-sensitive filter for the criterion") != std::string::npos);
}

TEST_CASE("pfgen latex compiles for names, parameters and matrices that need escaping", "[latex][pdflatex][compiler]") {
  if (!pdflatex_available())
    FAIL("pdflatex is not on PATH: the LaTeX compile tests need it (install texlive-latex-base)");
  TempDir dir;
  // Underscores in every kind of name, Greek and non-Greek parameter names, a
  // renamed time, diffusion_covariance forms, two observations with a full B,
  // negative numbers and an initial condition without x0.
  write_file(dir.file("escaping.yaml"),
             "name: model_with_under_scores\n"  // a trailing _ is refused (the C names would hold __); z_ keeps one
             "states: [x_a, y2, lambda, z_]\n"
             "parameters: {alpha_1: -0.5, sigma: 0.25, k: 3, varrho: 2, Gamma: 1.5}\n"
             "time: tau\n"
             "drift: [\"alpha_1*x_a + k*x_a^2*y2 - tau\", \"-y2 + x_a^3/3\", \"-Gamma*lambda + varrho\", \"-z_\"]\n"
             "diffusion_covariance:\n"
             "  - [\"sigma^2*x_a^2\", \"sigma*x_a*y2\", \"0\", \"0\"]\n"
             "  - [\"sigma*x_a*y2\", \"1 + y2^2\", \"0\", \"0\"]\n"
             "  - [\"0\", \"0\", \"1\", \"0\"]\n"
             "  - [\"0\", \"0\", \"0\", \"2.5e-3\"]\n"
             "additive_diffusion_covariance: [[\"sigma^2\", \"0\", \"0\", \"0\"], [\"0\", \"1\", \"0\", \"0\"], "
             "[\"0\", \"0\", \"1\", \"0\"], [\"0\", \"0\", \"0\", \"1\"]]\n"
             "observation:\n"
             "  A0: [\"tau\", \"-1.5\"]\n"
             "  A: [[\"1\", \"0\", \"0\", \"0\"], [\"k\", \"1\", \"-1\", \"0\"]]\n"
             "  B: [[\"1\", \"0.5\"], [\"0\", \"sigma\"]]\n"
             "initial: {m0: [-1, 0.5, 0, 0], P0: [[1, 0.25, 0, 0], [0.25, 2, 0, 0], [0, 0, 1, 0], [0, 0, 0, 1]]}\n");
  check_compiles(dir.file("escaping.yaml"), "", dir, "escaping");
  const std::string tex = read_file(dir.file("escaping.tex"));
  CHECK(tex.find("model\\_with\\_under\\_scores") != std::string::npos);
  CHECK(tex.find("\\section*{Filter \\texttt{ekf-additive}}") != std::string::npos);
}

TEST_CASE("pfgen latex compiles for delayed observations: x(t-h), Phi* and the auxiliary ODE",
          "[latex][pdflatex][compiler]") {
  if (!pdflatex_available())
    FAIL("pdflatex is not on PATH: the LaTeX compile tests need it (install texlive-latex-base)");
  TempDir dir;
  // Two states, so the correction has phi1^2, phi1*phi2 and phi2^2 and the x* drift a square:
  // powers of \Phi^*_{1} and x^*_{2}, which need braces to be one superscript. A user filter too.
  write_file(dir.file("delayed.yaml"),
             "name: delayed_two\n"
             "states: [x, y]\n"
             "drift: [\"-x + 0.5*x*y\", \"-y^2\"]\n"
             "diffusion: [[\"0.1*x\", \"0\"], [\"0\", \"0.2\"]]\n"
             "observation:\n"
             "  delay: 0.25\n"
             "  A: [[\"1\", \"1\"], [\"0\", \"2\"]]\n"
             "  B: [[\"1\", \"0\"], [\"0\", \"1\"]]\n"
             "initial: {x0: [1, 1], m0: [0.5, 0.5], P0: [[1, 0], [0, 1]]}\n"
             "filters:\n"
             "  mine:\n"
             "    m_drift: [\"-m1\", \"-m2^2\"]\n"
             "    P_drift: [[\"-2*P11\", \"0\"], [\"0\", \"-P22\"]]\n"
             "    gain: [[\"P11\", \"0\"], [\"0\", \"P22\"]]\n");
  check_compiles(dir.file("delayed.yaml"), "", dir, "delayed");
  const std::string tex = read_file(dir.file("delayed.tex"));
  CHECK(tex.find("dy = (A_0 + A x(t-h))\\,dt + B\\,dW_2") != std::string::npos);  // the model section
  CHECK(tex.find("h = 0.25") != std::string::npos);
  CHECK(tex.find("{\\Phi^*_{1}}^{2}") != std::string::npos);
  CHECK(tex.find("\\frac{d{x^*_{2}}}{dt} &= -{x^*_{2}}^{2}") != std::string::npos);
  CHECK(tex.find("{m_{1}(t-h)}") != std::string::npos);
  for (const std::string kind : {"delay-optimal", "delay-uncorrected", "delay-ekf", "mine"})
    CHECK(tex.find("\\section*{Filter \\texttt{" + kind + "}}") != std::string::npos);
}
