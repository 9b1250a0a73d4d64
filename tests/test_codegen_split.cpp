// A generated function above CodegenOptions::max_function_ops is written in parts (chunked_body.cpp)
// to bound compile time. The parts must compute exactly what the one function computes: the same
// operations on the same operands in the same order, so in IEEE arithmetic without contraction
// (ISO C++17 mode: g++ and clang++ do not fuse a*b+c into fma there) the results are equal, not
// merely close. The dense cubic n = 6 optimal filter (3584 ops in derivatives: 2699 in the graph, then
// P's drift in loops, which follow the parts) is generated whole and with parts of at most 500 ops,
// both compiled warning-free into one program (g++ and clang++) that evaluates both on the same
// random states and compares them bit for bit.
#include <catch2/catch.hpp>

#include <filesystem>
#include <string>

#include "pfgen/codegen/filter_codegen.hpp"
#include "pfgen/derivation/filter_equations.hpp"
#include "support/cli_helpers.hpp"
#include "support/dense_cubic_model.hpp"
#include "support/process.hpp"

namespace fs = std::filesystem;
using namespace pfgen_test;

namespace {

std::string generated_optimal(const pfgen::Model& model, const std::string& name_space, std::size_t max_ops) {
  pfgen::codegen::CodegenOptions options;
  options.name_space = name_space;
  options.max_function_ops = max_ops;
  return pfgen::codegen::generate_filter_code(model, pfgen::derive_named_filter(model, "optimal"), options).files.at(0).contents;
}

const char* const kProgram = R"(#include <cstdio>
#include <cstring>
#include <random>
#include "whole.hpp"
#include "split.hpp"
namespace W = whole::dense_cubic_6::optimal;
namespace S = split::dense_cubic_6::optimal;
int main() {
  std::mt19937_64 rng(7);
  std::uniform_real_distribution<double> uniform(-1, 1);
  int differences = 0;
  for (int run = 0; run < 20; ++run) {
    double state[W::state_size], a[W::state_size], b[W::state_size];
    for (double& v : state) v = uniform(rng);
    W::derivatives(0.5, state, W::Params<double>{}, a);
    S::derivatives(0.5, state, S::Params<double>{}, b);
    differences += std::memcmp(a, b, sizeof a) != 0;
  }
  std::printf(differences == 0 ? "equal\n" : "%d runs differ\n", differences);
  return differences != 0;
}
)";

}  // namespace

TEST_CASE("a function written in parts computes bit for bit what the whole function computes", "[compiler]") {
  const pfgen::Model model = dense_cubic_model(6);
  const std::string whole = generated_optimal(model, "whole", 0);
  const std::string split = generated_optimal(model, "split", 500);
  // The split header really is in parts (6 of at most 500 ops), the whole one is not.
  REQUIRE(split.find("  // 2699 operations in 6 parts of at most 500,") != std::string::npos);
  REQUIRE(whole.find("PFGEN_NOINLINE") == std::string::npos);
  // The operation counts do not depend on the split.
  REQUIRE(split.substr(0, split.find("#pragma once")) ==
          whole.substr(0, whole.find("#pragma once")));

  TempDir dir;
  write_file(dir.file("whole.hpp"), whole);
  write_file(dir.file("split.hpp"), split);
  write_file(dir.file("check.cpp"), kProgram);
  for (const char* compiler : {"g++", "clang++"}) {
    const std::string binary = dir.file(std::string("check-") + compiler);
    ProcessResult built = run_process(std::string(compiler) + " -std=c++17 -O1 -Wall -Wextra -Werror -I " +
                                      shell_quote(dir.path()) + " " + shell_quote(dir.file("check.cpp")) + " -o " +
                                      shell_quote(binary));
    INFO(compiler << ":\n" << built.err);
    REQUIRE(built.exit_code == 0);
    ProcessResult ran = run_process(shell_quote(binary));
    CHECK(ran.out == "equal\n");
    CHECK(ran.exit_code == 0);
  }
}
