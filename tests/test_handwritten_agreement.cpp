// The baseline of benchmarks/bench_handwritten is right: for the dense linear model n = 4
// (tests/support/dense_linear_system.hpp), pfgen's generated `optimal` filter (Kalman-Bucy there)
// and the hand-written fixed-size Eigen filter (support/handwritten_kalman_bucy.hpp), stepped
// over the same 1000 increments dy, start and end in the same state to 1e-12 relative. The program
// is compiled out of process, as the benchmark compiles it, through the shared check
// (support/handwritten_agreement.hpp). No timing here.
#include <catch2/catch.hpp>

#include <sstream>
#include <string>

#include "support/cli_helpers.hpp"
#include "support/dense_linear_system.hpp"

using namespace pfgen_test;

namespace {

const char* const kProgram = R"program(#include <cstdio>

#include "dense_linear_4/optimal.hpp"
#include "support/dense_linear_system.hpp"
#include "support/handwritten_agreement.hpp"

namespace gen = hw::dense_linear_4::optimal;

int main() {
  const pfgen_test::DenseLinearSystem system = pfgen_test::dense_linear_system(4);
  const pfgen_test::HandwrittenKalmanBucy<double, 4, 3> hand(system);
  const double dt = 1e-3;
  const std::vector<double> dy = pfgen_test::dense_linear_increments(system, 1000, dt, 7);
  const gen::Params<double> params{};
  double t = 0;
  const pfgen_test::Agreement a = pfgen_test::handwritten_agreement(
      hand, [](double* state) { gen::initial_state(state); },
      [&](double* state, const double* y) { gen::step(state, t, dt, y, params); t += dt; }, dy, dt);
  std::printf("%.17g %.17g %.17g\n", a.initial, a.final, a.moved);
  return 0;
}
)program";

}  // namespace

TEST_CASE("generated optimal filter of a dense linear model steps as the hand-written Kalman-Bucy filter",
          "[codegen][handwritten][compiler]") {
  TempDir dir;
  write_file(dir.file("dense_linear_4.yaml"), dense_linear_yaml(dense_linear_system(4)));
  ProcessResult generated = run_pfgen({"codegen", dir.file("dense_linear_4.yaml"), "--filter", "optimal", "--scalar",
                                       "double", "--namespace", "hw", "-o", dir.path()});
  INFO(generated.err);
  REQUIRE(generated.exit_code == 0);
  write_file(dir.file("agreement.cpp"), kProgram);
  const std::string exe = dir.file("agreement");
  const std::string command = "g++ -std=c++17 -O1 -Wall -Wextra -Werror -I " + shell_quote(dir.path()) + " -I " +
                              shell_quote(source_dir() + "/tests") + " -isystem " +
                              shell_quote(PFGEN_EIGEN_INCLUDE_DIR) + " " + shell_quote(dir.file("agreement.cpp")) + " " +
                              shell_quote(source_dir() + "/tests/support/dense_linear_system.cpp") + " -o " +
                              shell_quote(exe);
  ProcessResult compiled = run_process(command);
  INFO(command << "\n" << compiled.err);
  REQUIRE(compiled.exit_code == 0);
  ProcessResult run = run_program({exe});
  INFO(run.out << run.err);
  REQUIRE(run.exit_code == 0);
  std::istringstream numbers(run.out);
  double initial = -1, final = -1, moved = -1;
  numbers >> initial >> final >> moved;
  REQUIRE(numbers);
  CHECK(initial == 0.0);   // m0 and P0 are exact decimals read alike
  CHECK(final <= 1e-12);
  CHECK(final >= 0.0);
  CHECK(moved > 1e-2);     // the states did move: the agreement is not that of two idle filters
}
