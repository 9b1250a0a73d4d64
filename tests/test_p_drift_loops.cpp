// P's drift in loops over dense blocks (codegen/p_drift_loops.hpp; rates() from n = 4, derivatives()
// from n = 6) and rates(), the one function a continuous filter's step calls (derivatives, gain and
// predicted observation in one body), against
// pfgen's exact evaluation of the equations (what `pfgen eval` prints): at 20 random points each,
// to 1e-12 relative to the largest entry of each output. The loops compute the same equations
// through other arithmetic (dense products of E[J], A and M = R^-1 with the full P), so an index,
// offset or block that is off shows here. Models: the dense linear benchmark systems n = 5 (the
// block summed in full) and n = 9 (its upper triangle), a dense cubic system with parameters in A
// and R (its M and A are computed, not literal, and its E[J] reads P), and one whose parameters are
// named as the loops' arrays and indices. Each is compiled as C++
// (g++ and clang++, -Wall -Wextra -Werror) and as C99 (gcc -std=c99 -Wpedantic -Werror); C's
// rates() is static, so its step is compared with C++'s. C++'s step() is also compared, bit for bit,
// with the same Heun step through rates() in loops, which step() is written out from below
// kStepWrittenOutBelow states.
#include <catch2/catch.hpp>

#include <cmath>
#include <random>
#include <regex>
#include <sstream>
#include <string>
#include <vector>

#include "pfgen/codegen/filter_codegen.hpp"
#include "pfgen/codegen/p_drift_loops.hpp"
#include "pfgen/derivation/filter_equations.hpp"
#include "pfgen/evaluation/point_evaluator.hpp"
#include "pfgen/model/yaml_model_loader.hpp"
#include "pfgen/codegen/heun_step.hpp"
#include "support/cli_helpers.hpp"
#include "support/dense_linear_system.hpp"
#include "support/process.hpp"

using namespace pfgen;
using namespace pfgen_test;

namespace {

const char* const kDenseCubicWithParameters = R"(name: dense_param_4
states: [x1, x2, x3, x4]
parameters: {a: 0.5, c: 2, r: 0.3}
drift:
  - "-x1 + a*x2 + 0.1*x3 - 0.2*x4 - 0.1*x1^3"
  - "0.3*x1 - x2 + a*x3 + 0.1*x4 + 0.05*x2*x1"
  - "0.2*x1 + 0.1*x2 - x3 + a*x4"
  - "a*x1 - 0.1*x2 + 0.2*x3 - x4 - 0.1*x4^3"
diffusion: [["0.3", "0"], ["0", "0.2*x1"], ["0.1", "0"], ["0", "0.1"]]
observation:
  A: [["c", "1", "0", "0"], ["0", "0", "1", "c"]]
  B: [["r", "0"], ["0", "2*r"]]
)";

// The loops' own names (work array, blocks, indices) taken by the model: they are chosen around them.
const char* const kLoopNamesTaken = R"(name: loop_names
states: [x1, x2, x3, x4]
parameters: {w: 0.5, i: -1, j: 0.3, u: 0.2, S: 0.1, H: 1, JP: 0.4, P_full: 0.25, K_T: 0.5, JP_T: 0.2}
drift:
  - "i*x1 + w*x2 + j*x3 - u*x4"
  - "S*x1 + i*x2 + JP*x3 + P_full*x4"
  - "u*x1 + S*x2 + i*x3 + w*x4"
  - "K_T*x1 - j*x2 + u*x3 + JP_T*x4 - 0.1*x4^3"
diffusion: [["0.3"], ["0.2"], ["0.1"], ["0.1"]]
observation:
  A: [["H", "0.5", "0", "1"], ["0", "1", "H", "0.2"]]
  B: [["w", "0"], ["0", "2*w"]]
)";

// n = 8 (the upper triangle), one observation of a sparse A (so H comes from the graph and M is
// 1 x 1), no diffusion (so nothing is added after the products).
const char* const kSparseObservationNoDiffusion = R"(name: one_sensor_8
states: [x1, x2, x3, x4, x5, x6, x7, x8]
drift:
  - "-x1 + 0.1*x2 + 0.2*x3 - 0.1*x4 + 0.3*x5 - 0.2*x6 + 0.1*x7 + 0.05*x8"
  - "0.2*x1 - x2 + 0.1*x3 + 0.3*x4 - 0.1*x5 + 0.2*x6 - 0.3*x7 + 0.1*x8"
  - "-0.1*x1 + 0.2*x2 - x3 + 0.1*x4 + 0.2*x5 + 0.1*x6 - 0.2*x7 + 0.3*x8"
  - "0.3*x1 - 0.1*x2 + 0.2*x3 - x4 + 0.1*x5 - 0.3*x6 + 0.2*x7 - 0.1*x8"
  - "0.1*x1 + 0.3*x2 - 0.2*x3 + 0.1*x4 - x5 + 0.2*x6 + 0.1*x7 - 0.2*x8"
  - "-0.2*x1 + 0.1*x2 + 0.3*x3 - 0.2*x4 + 0.1*x5 - x6 + 0.3*x7 + 0.1*x8"
  - "0.1*x1 - 0.2*x2 + 0.1*x3 + 0.2*x4 - 0.3*x5 + 0.1*x6 - x7 + 0.2*x8"
  - "0.2*x1 + 0.1*x2 - 0.1*x3 + 0.3*x4 + 0.2*x5 - 0.1*x6 + 0.1*x7 - x8 - 0.05*x8^3"
diffusion: [["0"], ["0"], ["0"], ["0"], ["0"], ["0"], ["0"], ["0"]]
observation:
  A: [["0", "0", "1", "0", "0", "0", "0", "0"]]
  B: [["0.4"]]
)";

// A random point with rational coordinates k/1000 and P = L L^T + I/10 (positive definite).
EvaluationPoint random_point(std::size_t n, std::mt19937& rng) {
  std::uniform_int_distribution<int> k(-1000, 1000);
  auto r = [&] { return GiNaC::numeric(k(rng), 1000); };
  EvaluationPoint point;
  point.t = GiNaC::numeric(1, 2);
  for (std::size_t i = 0; i < n; ++i) point.m.push_back(r());
  std::vector<std::vector<GiNaC::numeric>> L(n, std::vector<GiNaC::numeric>(n, 0));
  for (std::size_t i = 0; i < n; ++i)
    for (std::size_t j = 0; j <= i; ++j) L[i][j] = r();
  point.P.assign(n, std::vector<GiNaC::numeric>(n, 0));
  for (std::size_t i = 0; i < n; ++i)
    for (std::size_t j = 0; j < n; ++j) {
      GiNaC::numeric s = i == j ? GiNaC::numeric(1, 10) : 0;
      for (std::size_t l = 0; l < n; ++l) s += L[i][l] * L[j][l];
      point.P[i][j] = s;
    }
  return point;
}

std::vector<double> flat_state(const EvaluationPoint& point) {
  std::vector<double> state;
  for (const auto& v : point.m) state.push_back(v.to_double());
  for (std::size_t i = 0; i < point.m.size(); ++i)
    for (std::size_t j = i; j < point.m.size(); ++j) state.push_back(point.P[i][j].to_double());
  return state;
}

std::string literal(double v) {
  std::ostringstream out;
  out.precision(17);
  out << v;
  return out.str();
}

std::vector<double> numbers(const std::string& line) {
  std::istringstream in(line);
  std::vector<double> values;
  for (double v; in >> v;) values.push_back(v);
  return values;
}

// Each output's entries against the exact ones, to 1e-12 of the largest.
void check_close(const std::vector<double>& got, const std::vector<double>& exact, const std::string& what) {
  REQUIRE(got.size() == exact.size());
  double scale = 0;
  for (double v : exact) scale = std::max(scale, std::abs(v));
  for (std::size_t k = 0; k < exact.size(); ++k) {
    INFO(what << "[" << k << "]: generated " << got[k] << ", exact " << exact[k]);
    CHECK(std::abs(got[k] - exact[k]) <= 1e-12 * std::max(scale, 1e-300));
  }
}

std::string code(const Model& model, const FilterEquations& eq, codegen::Language language, std::size_t file) {
  codegen::CodegenOptions options;
  options.language = language;
  if (language == "c") options.scalar = codegen::ScalarMode::Double;
  options.name_space = "loops";
  return codegen::generate_filter_code(model, eq, options).files.at(file).contents;
}

// The program: for each state, derivatives, gain, predicted observation, rates (C++ only) and one
// step (dt = 1e-3, dy = 1e-3 (1, -1, ...)) from it, each output on its own line.
std::string program(const std::vector<std::vector<double>>& states, bool c) {
  const std::string call_prefix = c ? "PREFIX_" : "G::";
  std::string text = c ? "#include <stdio.h>\n#include \"optimal.h\"\n#define S loops_MODEL_optimal_state_size\n"
                         "#define N loops_MODEL_optimal_n\n#define P loops_MODEL_optimal_p\n"
                       : "#include <cstdio>\n#include \"filter.hpp\"\nnamespace G = loops::MODEL::optimal;\n"
                         "#define S G::state_size\n#define N G::n\n#define P G::p\n";
  text += "static void print(const double* v, int count) {\n  for (int k = 0; k < count; ++k) printf(\"%.17g \", v[k]);\n"
          "  printf(\"\\n\");\n}\n";
  text += "static const double states[" + std::to_string(states.size()) + "][S] = {\n";
  for (const auto& state : states) {
    text += "  {";
    for (double v : state) text += literal(v) + ", ";
    text += "},\n";
  }
  text += "};\n";
  if (!c)
    text += "static void loop_increment(double t, const double* state, double dt, const double* dy,\n"
            "                           const G::Params<double>& params, double* delta) {\n"
            "  double all[S + N * P + P];\n  G::rates(t, state, params, all);\n"
            "  const double* K = all + S;\n  double* innovation = all + S + N * P;\n"
            "  for (std::size_t r = 0; r < P; ++r) innovation[r] = dy[r] - innovation[r] * dt;\n"
            "  for (std::size_t i = 0; i < S; ++i) delta[i] = all[i] * dt;\n"
            "  for (std::size_t i = 0; i < N; ++i)\n"
            "    for (std::size_t r = 0; r < P; ++r) delta[i] += K[i * P + r] * innovation[r];\n}\n";
  text += "int main(void) {\n";
  text += c ? "  PARAMS params;\n  PREFIX_default_params(&params);\n" : "  const G::Params<double> params{};\n";
  const std::string params = c ? "&params" : "params";
  text += "  double dy[P];\n  for (int r = 0; r < (int)P; ++r) dy[r] = r % 2 ? -1e-3 : 1e-3;\n";
  text += "  for (int s = 0; s < " + std::to_string(states.size()) + "; ++s) {\n";
  text += "    double out[S], K[N * P], h[P], step[S];\n";
  text += "    " + call_prefix + "derivatives(0.5, states[s], " + params + ", out);\n    print(out, S);\n";
  text += "    " + call_prefix + "gain(0.5, states[s], " + params + ", K);\n    print(K, N * P);\n";
  text += "    " + call_prefix + "predicted_observation(0.5, states[s], " + params + ", h);\n    print(h, P);\n";
  if (!c) text += "    double all[S + N * P + P];\n    G::rates(0.5, states[s], params, all);\n    print(all, S + N * P + P);\n";
  text += "    for (int k = 0; k < (int)S; ++k) step[k] = states[s][k];\n";
  text += "    " + call_prefix + "step(step, 0.5, 1e-3, dy, " + params + ");\n    print(step, S);\n";
  // C++: the same Heun step again, from rates() through the loops step() had before it was written
  // out below kStepWrittenOutBelow states: its arithmetic, so the same numbers to the last bit.
  if (!c)
    text += "    {\n      double first[S], predicted[S], second[S], looped[S];\n"
            "      loop_increment(0.5, states[s], 1e-3, dy, params, first);\n"
            "      for (std::size_t i = 0; i < S; ++i) predicted[i] = states[s][i] + first[i];\n"
            "      loop_increment(0.5 + 1e-3, predicted, 1e-3, dy, params, second);\n"
            "      for (std::size_t i = 0; i < S; ++i) looped[i] = states[s][i] + (first[i] + second[i]) / 2.0;\n"
            "      print(looped, S);\n    }\n";
  text += "  }\n  return 0;\n}\n";
  return text;
}

std::string replaced(std::string text, const std::string& from, const std::string& to) {
  for (std::size_t at = text.find(from); at != std::string::npos; at = text.find(from, at + to.size()))
    text.replace(at, from.size(), to);
  return text;
}

void check_model(const Model& model, bool full_combine) {
  const FilterEquations eq = derive_named_filter(model, "optimal");
  const std::size_t n = eq.n(), p = eq.p, size = eq.variables.count();
  const std::string header = code(model, eq, "cpp", 0);
  // The loops are what is written, in the expected variant, and step() calls rates().
  REQUIRE(header.find("P's drift from dense blocks") != std::string::npos);
  // n x n local blocks: P in full and E[J] P, and below n = 8 E[J] P transposed and the full sum,
  // in rates() and, from n = kMinLoopDimensionAlone on, in derivatives() too.
  std::size_t blocks = 0;
  const std::regex block("^  Scalar \\w+\\[" + std::to_string(n * n) + "\\];$");
  std::istringstream header_lines(header);
  for (std::string line; std::getline(header_lines, line);) blocks += std::regex_match(line, block);
  CHECK(blocks == (full_combine ? 4u : 2u) * (n >= codegen::kMinLoopDimensionAlone ? 2u : 1u));
  CHECK(header.find("  rates(t, state, params, all.data());") != std::string::npos);
  // step()'s loops written out below kStepWrittenOutBelow states, loops from there on.
  CHECK((header.find("\n  predicted[0] = state[0] + first[0];\n") != std::string::npos) ==
        (n < codegen::kStepWrittenOutBelow));
  CHECK((header.find("for (std::size_t i = 0; i < state_size; ++i) predicted[i]") != std::string::npos) ==
        (n >= codegen::kStepWrittenOutBelow));

  std::mt19937 rng(2026);
  std::vector<EvaluationPoint> points;
  std::vector<std::vector<double>> states;
  for (int k = 0; k < 20; ++k) {
    points.push_back(random_point(n, rng));
    states.push_back(flat_state(points.back()));
  }

  TempDir dir;
  const std::string prefix = "loops_" + model.name + "_optimal";
  write_file(dir.file("filter.hpp"), header);
  write_file(dir.file("check.cpp"), replaced(program(states, false), "MODEL", model.name));
  write_file(dir.file("optimal.h"), code(model, eq, "c", 0));
  write_file(dir.file("filter.c"), code(model, eq, "c", 1));
  write_file(dir.file("check.c"), replaced(replaced(replaced(program(states, true), "MODEL", model.name), "PREFIX",
                                                    prefix),
                                           "PARAMS", prefix + "_params"));
  struct Build {
    std::string name, command;
  };
  const std::string include = " -I " + shell_quote(dir.path()) + " ";
  const std::vector<Build> builds = {
      {"g++", "g++ -std=c++17 -O2 -Wall -Wextra -Werror" + include + shell_quote(dir.file("check.cpp"))},
      {"clang++", "clang++ -std=c++17 -O2 -Wall -Wextra -Werror" + include + shell_quote(dir.file("check.cpp"))},
      {"gcc", "gcc -std=c99 -O2 -Wall -Wextra -Wpedantic -Werror" + include + shell_quote(dir.file("check.c")) + " " +
                  shell_quote(dir.file("filter.c")) + " -lm"},
  };
  std::vector<std::string> cpp_steps;
  for (const Build& build : builds) {
    const bool c = build.name == "gcc";
    const std::string binary = dir.file("check-" + build.name);
    const ProcessResult built = run_process(build.command + " -o " + shell_quote(binary));
    INFO(model.name << ", " << build.name << ":\n" << built.err);
    REQUIRE(built.exit_code == 0);
    const ProcessResult ran = run_process(shell_quote(binary));
    REQUIRE(ran.exit_code == 0);
    std::istringstream lines(ran.out);
    for (std::size_t s = 0; s < points.size(); ++s) {
      const EvaluatedFilter exact = evaluate_at(model, eq, points[s]);
      std::vector<double> exact_rates = exact.m_drift, exact_gain;
      for (std::size_t i = 0; i < n; ++i)
        for (std::size_t j = i; j < n; ++j) exact_rates.push_back(exact.P_drift[i][j]);
      for (const auto& row : exact.gain) exact_gain.insert(exact_gain.end(), row.begin(), row.end());
      std::string line;
      std::getline(lines, line);
      check_close(numbers(line), exact_rates, build.name + " derivatives");
      std::getline(lines, line);
      check_close(numbers(line), exact_gain, build.name + " gain");
      std::getline(lines, line);
      const std::vector<double> h = numbers(line);
      REQUIRE(h.size() == p);
      if (!c) {
        std::getline(lines, line);
        const std::vector<double> all = numbers(line);
        REQUIRE(all.size() == size + n * p + p);
        check_close(std::vector<double>(all.begin(), all.begin() + size), exact_rates, build.name + " rates: derivatives");
        check_close(std::vector<double>(all.begin() + size, all.begin() + size + n * p), exact_gain,
                    build.name + " rates: gain");
        check_close(std::vector<double>(all.end() - p, all.end()), h, build.name + " rates: predicted observation");
      }
      std::getline(lines, line);
      if (!c) {
        std::string looped;
        std::getline(lines, looped);
        INFO(build.name << ": step() against the same step in loops");
        CHECK(line == looped);
      }
      if (build.name == "g++") {
        cpp_steps.push_back(line);
      } else if (c) {
        check_close(numbers(line), numbers(cpp_steps.at(s)), "C step against C++ step");
      }
    }
  }
}

}  // namespace

TEST_CASE("P's drift in loops and rates() agree with the exact equations in C++ and C", "[compiler]") {
  SECTION("dense linear n = 5: the block summed in full") {
    check_model(load_model_text(dense_linear_yaml(dense_linear_system(5)), "dense_linear_5.yaml"), true);
  }
  SECTION("dense linear n = 9: the upper triangle") {
    check_model(load_model_text(dense_linear_yaml(dense_linear_system(9)), "dense_linear_9.yaml"), false);
  }
  SECTION("dense cubic with parameters in A and R") {
    check_model(load_model_text(kDenseCubicWithParameters, "dense_param_4.yaml"), true);
  }
  SECTION("one observation of a sparse A, no diffusion, n = 8") {
    check_model(load_model_text(kSparseObservationNoDiffusion, "one_sensor_8.yaml"), false);
  }
  SECTION("a model whose parameters have the loops' names") {
    check_model(load_model_text(kLoopNamesTaken, "loop_names.yaml"), true);
  }
}

// The dense products' rows as a loop at n = 4 and written out from kRowsWrittenOutFrom, one column
// loop per row (codegen/p_drift_loops.hpp says why, with the measurements): a later change of the
// forms has to change this test too. Dense linear systems, whose E[J] and A are dense; C++ and C
// are one text.
TEST_CASE("the dense products' rows are a loop at n = 4 and written out from n = 5 to 7", "[unit]") {
  for (const std::size_t n : {std::size_t(4), codegen::kRowsWrittenOutFrom, codegen::kFullCombineBelow - 1}) {
    CAPTURE(n);
    const Model model = load_model_text(dense_linear_yaml(dense_linear_system(n)), "dense_linear.yaml");
    const FilterEquations eq = derive_named_filter(model, "optimal");
    const std::string N = std::to_string(n), p = std::to_string(eq.p);
    for (const codegen::Language language : {"cpp", "c"}) {
      const std::string text = code(model, eq, language, language == "c" ? 1 : 0);
      const bool row_loop = n < codegen::kRowsWrittenOutFrom;
      // E[J] P and A P: the row loop, or row 1's own column loop.
      CHECK((text.find("  for (int i = 0; i < " + N + "; ++i)\n    for (int j = 0; j < " + N + "; ++j) JP[i * " + N +
                       " + j] = ") != std::string::npos) == row_loop);
      CHECK((text.find("  for (int i = 0; i < " + p + "; ++i)\n    for (int j = 0; j < " + N + "; ++j) H[i * " + N +
                       " + j] = ") != std::string::npos) == row_loop);
      CHECK((text.find("  for (int j = 0; j < " + N + "; ++j) JP[" + N + " + j] = ") != std::string::npos) == !row_loop);
      CHECK((text.find("  for (int j = 0; j < " + N + "; ++j) H[" + N + " + j] = ") != std::string::npos) == !row_loop);
    }
  }
}
