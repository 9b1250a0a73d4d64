// The generated delay filters converge with first order in the grid step on one observed path
// (docs/theory.md §2.6, "Integration on a fixed grid"). Each kind is generated for the grid steps
// 0.02, 0.01, 0.005 and 0.0025, and stepped on the same observation path: the increments of the
// finest grid, summed for the coarser ones. With the differences of m(T) between successive grids
// e(dt) = RMS over paths of m_dt(T) - m_{dt/2}(T), first order gives e(dt) / e(dt/2) = 2 and order
// one half gives sqrt 2. The step that ends at t = h once took Phi*(h) at its corrector, applying
// half the gain to an increment observed before h: delay-optimal then converged like sqrt(dt).
#include <catch2/catch.hpp>

#include <cmath>
#include <filesystem>
#include <fstream>
#include <map>
#include <sstream>
#include <string>
#include <vector>

#include "pfgen/codegen/filter_codegen.hpp"
#include "pfgen/derivation/filter_equations.hpp"
#include "pfgen/model/model_builder.hpp"
#include "support/process.hpp"

using namespace pfgen;

namespace {

// dx = (a x + x^2 / 10) dt + (0.3 + x / 10) dW1, dy = x(t - 1/5) dt + dW2 / 5.
Model delayed_model() {
  ModelBuilder b("convergence");
  const GiNaC::symbol x = b.state("x");
  b.drift({GiNaC::numeric(-1, 2) * x + GiNaC::numeric(1, 10) * x * x});
  b.diffusion({{GiNaC::numeric(3, 10) + GiNaC::numeric(1, 10) * x}});
  b.delayed_observation(GiNaC::numeric(1, 5), {0}, {{1}}, {{GiNaC::numeric(1, 5)}});
  InitialConditions initial;
  initial.x0 = {1};
  initial.m0 = {GiNaC::numeric(1, 2)};
  initial.P0 = {{GiNaC::numeric(1, 4)}};
  b.initial(initial);
  return b.build();
}

}  // namespace

TEST_CASE("the generated delay filters converge with first order in dt on one observed path",
          "[codegen][delayed][compiler]") {
  const Model model = delayed_model();
  const std::filesystem::path dir = std::filesystem::temp_directory_path() / "pfgen-test-delay-convergence";
  std::filesystem::remove_all(dir);
  std::filesystem::create_directories(dir);
  const std::vector<double> steps = {0.02, 0.01, 0.005, 0.0025};  // the finest is the path's grid
  const std::vector<FilterKind> kinds = {FilterKind::DelayOptimal, FilterKind::DelayUncorrected, FilterKind::DelayEkf};
  std::string program =
      "#include <cmath>\n#include <cstdio>\n#include <random>\n#include <vector>\n";
  std::string body;
  for (std::size_t g = 0; g < steps.size(); ++g) {
    codegen::CodegenOptions options;
    options.scalar = codegen::ScalarMode::Double;
    options.grid_step = steps[g];
    options.name_space = "grid" + std::to_string(g);
    for (FilterKind kind : kinds) {
      const codegen::GeneratedFilter file = codegen::generate_filter_code(model, derive_filter(model, kind), options);
      const std::filesystem::path path = dir / ("grid" + std::to_string(g)) / file.files.at(0).relative_path;
      std::filesystem::create_directories(path.parent_path());
      std::ofstream(path) << file.files.at(0).contents;
      program += "#include \"grid" + std::to_string(g) + "/" + file.files.at(0).relative_path + "\"\n";
    }
  }
  // m(T) of each kind on each grid, for one path given as the finest grid's increments.
  program += "\ntemplate <class F>\ndouble final_m(const std::vector<double>& fine, int ratio) {\n"
             "  F filter;\n  for (std::size_t k = 0; k + ratio <= fine.size(); k += ratio) {\n"
             "    double dy[1] = {0};\n    for (int j = 0; j < ratio; ++j) dy[0] += fine[k + j];\n"
             "    filter.step(dy);\n  }\n  return filter.state[0];\n}\n\n";
  program += "int main() {\n  const double T = 1, fine_dt = 0.0025, h = 0.2;\n"
             "  const int steps = static_cast<int>(T / fine_dt + 0.5), lag = static_cast<int>(h / fine_dt + 0.5);\n"
             "  std::mt19937_64 rng(11);\n  std::normal_distribution<double> normal(0.0, 1.0);\n"
             "  const int kinds = " + std::to_string(kinds.size()) + ", grids = " + std::to_string(steps.size()) + ";\n"
             "  std::vector<double> squares(kinds * (grids - 1), 0.0);\n  const int paths = 200;\n"
             "  for (int path = 0; path < paths; ++path) {\n"
             "    std::vector<double> x(steps + 1), fine(steps);\n    x[0] = 1;\n"
             "    for (int k = 0; k < steps; ++k) {\n"
             "      const double xk = x[k];\n"
             "      x[k + 1] = xk + (-0.5 * xk + 0.1 * xk * xk) * fine_dt + (0.3 + 0.1 * xk) * std::sqrt(fine_dt) * normal(rng);\n"
             "      const double past = k >= lag ? x[k - lag] : x[0];\n"
             "      fine[k] = past * fine_dt + 0.2 * std::sqrt(fine_dt) * normal(rng);\n"
             "    }\n"
             "    double m[" + std::to_string(kinds.size()) + "][" + std::to_string(steps.size()) + "];\n";
  for (std::size_t g = 0; g < steps.size(); ++g)
    for (std::size_t k = 0; k < kinds.size(); ++k) {
      const std::string identifier = filter_identifier(filter_kind_name(kinds[k]));
      program += "    m[" + std::to_string(k) + "][" + std::to_string(g) + "] = final_m<grid" + std::to_string(g) +
                 "::convergence::" + identifier + "::Filter>(fine, " +
                 std::to_string(static_cast<int>(steps[g] / steps.back() + 0.5)) + ");\n";
    }
  program += "    for (int k = 0; k < kinds; ++k)\n      for (int g = 0; g + 1 < grids; ++g)\n"
             "        squares[k * (grids - 1) + g] += (m[k][g] - m[k][g + 1]) * (m[k][g] - m[k][g + 1]);\n"
             "  }\n"
             "  for (int k = 0; k < kinds; ++k) {\n    for (int g = 0; g + 1 < grids; ++g)\n"
             "      std::printf(\" %.6g\", std::sqrt(squares[k * (grids - 1) + g] / paths));\n"
             "    std::printf(\"\\n\");\n  }\n  return 0;\n}\n";
  std::ofstream(dir / "main.cpp") << program;
  const std::string binary = (dir / "convergence").string();
  const std::string command = "g++ -std=c++17 -O2 -Wall -Wextra -Werror -I " + pfgen_test::shell_quote(dir.string()) +
                              " " + pfgen_test::shell_quote((dir / "main.cpp").string()) + " -o " +
                              pfgen_test::shell_quote(binary);
  const auto compiled = pfgen_test::run_process(command);
  INFO(command << "\n" << compiled.err.substr(0, 4000));
  REQUIRE(compiled.exit_code == 0);
  const auto ran = pfgen_test::run_process(pfgen_test::shell_quote(binary));
  REQUIRE(ran.exit_code == 0);
  std::istringstream lines(ran.out);
  for (FilterKind kind : kinds) {
    double e[3] = {0, 0, 0};
    REQUIRE(lines >> e[0] >> e[1] >> e[2]);
    INFO(filter_kind_name(kind) << ": RMS differences of m(1) between grids 0.02|0.01|0.005|0.0025: " << e[0]
                                << " " << e[1] << " " << e[2]);
    // First order: each halving halves the difference (2); order one half would give 1.41.
    CHECK(e[0] / e[1] > 1.7);
    CHECK(e[1] / e[2] > 1.7);
    CHECK(e[0] / e[1] < 2.4);
    CHECK(e[1] / e[2] < 2.4);
  }
  std::filesystem::remove_all(dir);
}
