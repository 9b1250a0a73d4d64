// Samples through a polynomial c, y_k = c(x(t_k)) + Uv v_k (observation.sampled.c, docs/theory.md
// §2.5): a c of degree <= 1 is C0 + C x byte for byte; the update's moments against an Isserlis
// expansion from their definitions (E[c], Cov(x, c), Cov(c)) and the Joseph form's C and R_c
// against P - K S K^T; the extended kind's linearisation; what the model file refuses; the
// generated update (C++ and C) against the moment-matching update formed from the evaluator's values; and
// simulate end to end, the same for 1 and 2 threads, with the particle reference.
#include <catch2/catch.hpp>

#include <sstream>

#include "pfgen/codegen/filter_codegen.hpp"
#include "pfgen/derivation/filter_equations.hpp"
#include "pfgen/evaluation/point_evaluator.hpp"
#include "pfgen/model/model_error.hpp"
#include "pfgen/model/model_filters.hpp"
#include "pfgen/model/yaml_model_loader.hpp"
#include "pfgen/printing/equation_report.hpp"
#include "support/cli_helpers.hpp"
#include "support/same_for_threads.hpp"
#include "support/isserlis_reference.hpp"
#include "support/symbolic_mismatch.hpp"
#include "support/test_paths.hpp"

using namespace pfgen;
using namespace pfgen_test;

namespace {

std::string model_text(const std::string& sampled) {
  return "name: m\nstates: [x, y]\nparameters: {a: 0.5}\ndrift: [\"-x\", \"x - y\"]\n"
         "diffusion: [[\"0.3\", \"0\"], [\"0\", \"0.3\"]]\nobservation:\n  sampled: " +
         sampled + "\ninitial: {x0: prior, m0: [1, 0.5], P0: [[0.2, 0], [0, 0.2]]}\n";
}

std::string refusal(const std::string& sampled) {
  try {
    load_model_text(model_text(sampled), "m.yaml");
  } catch (const ModelError& e) {
    return e.what();
  }
  return "accepted";
}

}  // namespace

TEST_CASE("sampled polynomial c: degree <= 1 is C0 + C x byte for byte", "[observation][sampled][polynomial][unit]") {
  const Model linear = load_model_text(
      model_text("{period: 0.5, C: [[\"2\", \"a\"], [\"0\", \"1\"]], C0: [\"1\", \"0\"], Uv: [[\"1\", \"0\"], [\"0\", \"2\"]]}"),
      "m.yaml");
  const Model written = load_model_text(
      model_text("{period: 0.5, c: [\"1 + 2*x + a*y\", \"y\"], Uv: [[\"1\", \"0\"], [\"0\", \"2\"]]}"), "m.yaml");
  CHECK(written.observation.rate().written_affine());
  for (FilterKind kind : supported_filter_kinds(linear)) {
    INFO(filter_kind_name(kind));
    const FilterEquations a = derive_filter(linear, kind), b = derive_filter(written, kind);
    CHECK(equations_text(written, b) == equations_text(linear, a));
    CHECK(equations_latex(written, b) == equations_latex(linear, a));
    CHECK(equations_json(written, b).dump() == equations_json(linear, a).dump());
    codegen::CodegenOptions options;
    options.scalar = codegen::ScalarMode::Double;
    CHECK(codegen::generate_filter_code(written, b, options).files.at(0).contents ==
          codegen::generate_filter_code(linear, a, options).files.at(0).contents);
  }
}

TEST_CASE("sampled polynomial c: the update's moments equal an Isserlis expansion of their definitions",
          "[observation][sampled][polynomial][isserlis][unit]") {
  const Model model = load_model_text(
      model_text("{period: 0.5, c: [\"x^3 - 2*x*y + a*y^2\", \"x^2*y^2 + y\"], Uv: [[\"1\", \"0\"], [\"0.5\", \"2\"]]}"),
      "m.yaml");
  REQUIRE_FALSE(model.observation.rate().affine());
  const FilterEquations eq = derive_filter(model, FilterKind::CdOptimal);
  const auto& s = eq.variables.symbols();
  const std::vector<GiNaC::symbol> x = {model.states[0], model.states[1]};
  IsserlisReference E(x, eq.variables);
  const ExVector& c = model.observation.rate().rows();
  const SampledUpdate& u = eq.update;
  REQUIRE(u.r() == 2);
  const GiNaC::ex R[2][2] = {{1, GiNaC::numeric(1, 2)}, {GiNaC::numeric(1, 2), GiNaC::numeric(17, 4)}};  // Uv Uv^T
  GiNaC::ex Ec[2];
  for (std::size_t a = 0; a < 2; ++a) {
    Ec[a] = E.expectation(c[a]);
    CHECK(mismatch(Ec[a], eq.predicted_observation[a].to_ex(s)) == "");
    for (std::size_t i = 0; i < 2; ++i)
      CHECK(mismatch(E.expectation((x[i] - E.m(i)) * c[a]), u.PCt[i][a].to_ex(s)) == "");
  }
  for (std::size_t a = 0; a < 2; ++a)
    for (std::size_t b = a; b < 2; ++b) {
      const GiNaC::ex covariance = E.expectation(c[a] * c[b]) - Ec[a] * Ec[b];
      CHECK(mismatch(covariance + R[a][b], u.S[u.upper_index(a, b)].to_ex(s)) == "");
      // The Joseph form's terms: S = C P C^T + R_c with P C^T = Cov(x, c).
      GiNaC::ex CPCt = 0;
      for (std::size_t k = 0; k < 2; ++k)
        for (std::size_t l = 0; l < 2; ++l) CPCt += u.C[a][k].to_ex(s) * E.P(k, l) * u.C[b][l].to_ex(s);
      CHECK(mismatch(u.S[u.upper_index(a, b)].to_ex(s), CPCt + u.R[u.upper_index(a, b)].to_ex(s)) == "");
    }
  for (std::size_t i = 0; i < 2; ++i)
    for (std::size_t a = 0; a < 2; ++a) {
      GiNaC::ex PCt = 0;
      for (std::size_t k = 0; k < 2; ++k) PCt += E.P(i, k) * u.C[a][k].to_ex(s);
      CHECK(mismatch(PCt, u.PCt[i][a].to_ex(s)) == "");
    }
  // The extended kind: c(m), J_c(m), S = J P J^T + Uv Uv^T.
  const FilterEquations ekf = derive_filter(model, FilterKind::CdEkf);
  GiNaC::exmap at_mean = {{x[0], E.m(0)}, {x[1], E.m(1)}};
  for (std::size_t a = 0; a < 2; ++a) {
    CHECK(mismatch(c[a].subs(at_mean), ekf.predicted_observation[a].to_ex(s)) == "");
    for (std::size_t k = 0; k < 2; ++k) CHECK(mismatch(c[a].diff(x[k]).subs(at_mean), ekf.update.C[a][k].to_ex(s)) == "");
    for (std::size_t b = a; b < 2; ++b) CHECK(mismatch(R[a][b], ekf.update.R[ekf.update.upper_index(a, b)].to_ex(s)) == "");
  }
  CHECK(eq.exactness.explanation.find("moment-matching") != std::string::npos);
  CHECK(equations_latex(model, eq).find("$R = \\mathrm{Cov}(c) - C P C^{T} + U_v U_v^{T}$") != std::string::npos);
  CHECK(equations_text(model, eq).find("y_k = c(x(t_k)) + Uv v_k, c = (-2*x*y + a*y^2 + x^3, x^2*y^2 + y)") !=
        std::string::npos);
}

TEST_CASE("sampled polynomial c: what the model file refuses", "[observation][sampled][polynomial][unit]") {
  CHECK(refusal("{period: 1, c: [\"x^2\"], C: [[\"1\", \"0\"]], Uv: [[\"1\"]]}") ==
        "m.yaml:7:36: error: field 'observation.sampled.C': samples given by c: y = c(x) + Uv v has no C0 or C (C0 + C "
        "x is c written as a linear polynomial)");
  CHECK(refusal("{period: 1, c: [], Uv: [[\"1\"]]}") ==
        "m.yaml:7:27: error: field 'observation.sampled.c': at least one observation is required");
  CHECK(refusal("{period: 1, c: [\"sin(x)\"], Uv: [[\"1\"]]}") ==
        "m.yaml:7:28: error: field 'observation.sampled.c', row 1: 'sin(x)' is not polynomial in the states (only "
        "non-negative integer powers of states are allowed; sin(x), 1/x, x^0.5 are not)");
  CHECK(refusal("{period: 1, c: [\"x^2\", \"y\"], Uv: [[\"1\"]]}") ==
        "m.yaml:7:45: error: field 'observation.sampled.Uv': expected 2 rows (one per observation, as in c), found 1");
  CHECK(refusal("{period: 1, c: [\"x*y\"], Uv: [[\"1\"]]}") == "accepted");
}

TEST_CASE("sampled polynomial c: the generated update (C++ and C) is the moment-matching update of the evaluator's values",
          "[codegen][sampled][polynomial][compiler]") {
  const Model model = load_model_file(example("polynomial/range_squared_sampled.yaml"));
  TempDir dir;
  for (FilterKind kind : {FilterKind::CdOptimal, FilterKind::CdEkf}) {
    const FilterEquations eq = derive_filter(model, kind);
    codegen::CodegenOptions options;
    options.scalar = codegen::ScalarMode::Double;
    for (const auto& file : codegen::generate_filter_code(model, eq, options).files) {
      std::filesystem::create_directories(std::filesystem::path(dir.file(file.relative_path)).parent_path());
      write_file(dir.file(file.relative_path), file.contents);
    }
    const std::string id = filter_identifier(eq.name);
    write_file(dir.file(id + ".cpp"), "#include <cstdio>\n#include \"range_squared_sampled/" + id +
                                          ".hpp\"\nint main() {\n  namespace F = pfgen_models::range_squared_sampled::" +
                                          id + ";\n  double s[5] = {1.0, 0.5, 0.2, 0.05, 0.3};\n  const double y[1] = {2.0};\n"
                                          "  if (!F::update(s, 0.1, y, F::Params<double>{})) return 1;\n"
                                          "  for (double v : s) std::printf(\"%.17g\\n\", v);\n  return 0;\n}\n");
    const ProcessResult built = run_process("g++ -std=c++17 -O2 -Wall -Wextra -Werror -I " + shell_quote(dir.path()) + " " +
                                            shell_quote(dir.file(id + ".cpp")) + " -o " + shell_quote(dir.file(id)));
    INFO(built.err.substr(0, 3000));
    REQUIRE(built.exit_code == 0);
    const ProcessResult ran = run_program({dir.file(id)});
    REQUIRE(ran.exit_code == 0);
    std::istringstream lines(ran.out);
    double updated[5];
    for (double& v : updated) lines >> v;
    REQUIRE(lines);
    // The evaluator's S and K at the same point, exact and rounded once, and E[c] (or c(m)) by hand:
    // m' = m + K (y - h), P' = P - K S K^T.
    EvaluationPoint point;
    point.t = GiNaC::numeric(1, 10);
    point.m = {1, GiNaC::numeric(1, 2)};
    point.P = {{GiNaC::numeric(1, 5), GiNaC::numeric(1, 20)}, {GiNaC::numeric(1, 20), GiNaC::numeric(3, 10)}};
    const EvaluatedFilter e = evaluate_at(model, eq, point);
    const double h = kind == FilterKind::CdEkf ? 1.25 : 1.25 + 0.5;
    const double S = e.innovation_covariance[0][0], K[2] = {e.gain[0][0], e.gain[1][0]};
    const double expected[5] = {1.0 + K[0] * (2.0 - h), 0.5 + K[1] * (2.0 - h), 0.2 - K[0] * S * K[0],
                                0.05 - K[0] * S * K[1], 0.3 - K[1] * S * K[1]};
    INFO(eq.name);
    for (int k = 0; k < 5; ++k) CHECK(updated[k] == Approx(expected[k]).epsilon(1e-12));

    // The C backend's update: the same numbers.
    options.language = "c";
    for (const auto& file : codegen::generate_filter_code(model, eq, options).files)
      write_file(dir.file(file.relative_path), file.contents);
    const std::string prefix = "pfgen_models_range_squared_sampled_" + id + "_";
    write_file(dir.file(id + "_c.c"), "#include <stdio.h>\n#include \"range_squared_sampled/" + id + ".h\"\nint main(void) {\n  " +
                                          prefix + "params params;\n  double s[5] = {1.0, 0.5, 0.2, 0.05, 0.3};\n"
                                          "  const double y[1] = {2.0};\n  " + prefix + "default_params(&params);\n  if (!" +
                                          prefix + "update(s, 0.1, y, &params)) return 1;\n"
                                          "  for (int k = 0; k < 5; ++k) printf(\"%.17g\\n\", s[k]);\n  return 0;\n}\n");
    const ProcessResult built_c =
        run_process("gcc -std=c99 -O2 -Wall -Wextra -Wpedantic -Werror -I " + shell_quote(dir.path()) + " " +
                    shell_quote(dir.file(id + "_c.c")) + " " + shell_quote(dir.file("range_squared_sampled/" + id + ".c")) +
                    " -lm -o " + shell_quote(dir.file(id + "_c")));
    INFO(built_c.err.substr(0, 3000));
    REQUIRE(built_c.exit_code == 0);
    const ProcessResult ran_c = run_program({dir.file(id + "_c")});
    REQUIRE(ran_c.exit_code == 0);
    std::istringstream c_lines(ran_c.out);
    for (int k = 0; k < 5; ++k) {
      double v = 0;
      c_lines >> v;
      CHECK(v == Approx(expected[k]).epsilon(1e-12));
    }
    REQUIRE(c_lines);
  }
}

TEST_CASE("simulate: samples through a polynomial c, with the particle reference, the same for 1 and 2 threads",
          "[simulate][sampled][polynomial][compiler]") {
  TempDir dir;
  const ProcessResult one =
      same_for_1_and_2_threads(dir, {"simulate", example("polynomial/range_squared_sampled.yaml"), "--cache-dir",
                                     dir.file("cache"), "--runs", "8", "--T", "1", "--reference", "particles:200"});
  CHECK(one.out.find("\nreference      x1     8") != std::string::npos);
  CHECK(one.out.find("Truth diverged: no run") != std::string::npos);
}
