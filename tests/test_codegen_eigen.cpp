// The optional Eigen convenience header: `pfgen codegen --eigen` also writes <kind>_eigen.hpp
// (m and P as Eigen matrices, pack/unpack of the flat state); without --eigen nothing mentions Eigen.
// The wrappers are compiled out of process with g++ and clang++ (-Wall -Wextra -Werror) and run:
// pack/unpack round-trip exactly and every wrapper agrees bit for bit with the flat API.
#include <catch2/catch.hpp>

#include <filesystem>
#include <string>
#include <vector>

#include "pfgen/model/model_filters.hpp"
#include "pfgen/model/yaml_model_loader.hpp"
#include "support/cli_helpers.hpp"

namespace fs = std::filesystem;
using namespace pfgen_test;

namespace {

// Three states, two observations (n != p, so a transposed gain layout would show), a parameter
// and a function of time.
const char* const kModel = R"model(name: three_two
states: [x1, x2, x3]
parameters: {a: 0.3}
drift: ["-a*x1 + 0.1*x2^2", "-x2 + sin(t)*x3", "-0.5*x3 + 0.01*x1*x2"]
diffusion: [["0.1*x1", "0"], ["0", "0.2"], ["0.1", "0.1*x3"]]
observation:
  A0: ["0", "cos(t)"]
  A: [["1", "0", "0.5"], ["0", "1", "0"]]
  B: [["1", "0"], ["0", "2"]]
initial: {m0: [0.1, -0.2, 0.3], P0: [[1, 0.1, 0], [0.1, 2, 0.2], [0, 0.2, 3]]}
)model";

// Exercises one generated namespace K (n = 3, p = 2) in scalar type S; returns the number of failures.
const char* const kProgram = R"program(#include <cstdio>

#include "float/three_two/optimal_eigen.hpp"
#include "template/three_two/ekf_eigen.hpp"
#include "template/three_two/optimal_eigen.hpp"

namespace {

int failures = 0;
void expect(bool ok, const char* what, int line) {
  if (!ok) {
    std::printf("FAILED line %d: %s\n", line, what);
    ++failures;
  }
}
#define EXPECT(x) expect((x), #x, __LINE__)

template <class S, class Step, class Pack, class Unpack, class Init, class Derivatives, class Gain, class Observe,
          class FlatStep, class FlatDerivatives, class FlatGain, class FlatObserve, class FlatInit, class Params>
void exercise(Step step, Pack pack, Unpack unpack, Init init, Derivatives derivatives, Gain gain, Observe observe,
              FlatStep flat_step, FlatDerivatives flat_derivatives, FlatGain flat_gain, FlatObserve flat_observe,
              FlatInit flat_init, const Params& params) {
  using Vec = Eigen::Matrix<S, 3, 1>;
  using Mat = Eigen::Matrix<S, 3, 3>;
  Vec m;
  Mat P;
  m << S(0.25), S(-1.5), S(3);
  P << S(2), S(0.5), S(-0.25),
       S(0.5), S(3), S(0.125),
       S(-0.25), S(0.125), S(4);
  // pack: m, then the upper triangle of P row by row.
  S state[9];
  pack(m, P, state);
  const S expected[9] = {S(0.25), S(-1.5), S(3), S(2), S(0.5), S(-0.25), S(3), S(0.125), S(4)};
  for (int k = 0; k < 9; ++k) EXPECT(state[k] == expected[k]);
  // unpack(pack(m, P)) == (m, P), P symmetric.
  Vec m2 = Vec::Constant(S(99));
  Mat P2 = Mat::Constant(S(99));
  unpack(state, m2, P2);
  EXPECT(m2 == m);
  EXPECT(P2 == P);
  // pack reads only the upper triangle.
  Mat lower_garbage = P;
  lower_garbage(2, 0) = S(77);
  lower_garbage(1, 0) = S(-77);
  S state2[9];
  pack(m, lower_garbage, state2);
  for (int k = 0; k < 9; ++k) EXPECT(state2[k] == state[k]);

  // initial_state, derivatives, gain, predicted_observation and step agree with the flat API.
  Vec mi;
  Mat Pi;
  init(mi, Pi);
  S flat[9];
  flat_init(flat);
  S packed[9];
  pack(mi, Pi, packed);
  for (int k = 0; k < 9; ++k) EXPECT(packed[k] == flat[k]);
  EXPECT(mi(2) == S(0.3) && Pi(1, 2) == S(0.2) && Pi(2, 1) == S(0.2));

  const S t = S(0.5);
  Vec md;
  Mat Pd;
  derivatives(t, m, P, params, md, Pd);
  S out[9];
  flat_derivatives(t, state, params, out);
  S packed_drift[9];
  pack(md, Pd, packed_drift);
  for (int k = 0; k < 9; ++k) EXPECT(packed_drift[k] == out[k]);
  EXPECT(Pd == Pd.transpose());

  const Eigen::Matrix<S, 3, 2> K = gain(t, m, P, params);
  S flat_K[6];
  flat_gain(t, state, params, flat_K);
  for (int i = 0; i < 3; ++i)
    for (int r = 0; r < 2; ++r) EXPECT(K(i, r) == flat_K[i * 2 + r]);

  const Eigen::Matrix<S, 2, 1> h = observe(t, m, P, params);
  S flat_h[2];
  flat_observe(t, state, params, flat_h);
  EXPECT(h(0) == flat_h[0] && h(1) == flat_h[1]);

  Eigen::Matrix<S, 2, 1> dy;
  dy << S(0.01), S(-0.02);
  for (int k = 0; k < 20; ++k) {
    step(m, P, t + S(k) * S(0.01), S(0.01), dy, params);
    flat_step(state, t + S(k) * S(0.01), S(0.01), dy.data(), params);
  }
  S stepped[9];
  pack(m, P, stepped);
  for (int k = 0; k < 9; ++k) EXPECT(stepped[k] == state[k]);
  EXPECT(P == P.transpose());
}

}  // namespace

#define KIND_ARGS(ns, S, T)                                                                                      \
  [](auto&&... a) { ns::step T(a...); }, [](auto&&... a) { ns::pack T(a...); },                                  \
      [](auto&&... a) { ns::unpack T(a...); }, [](auto&&... a) { ns::initial_state T(a...); },                  \
      [](auto&&... a) { ns::derivatives T(a...); }, [](auto&&... a) { return ns::gain T(a...); },               \
      [](auto&&... a) { return ns::predicted_observation T(a...); }, [](auto&&... a) { ns::step T(a...); },     \
      [](auto&&... a) { ns::derivatives T(a...); }, [](auto&&... a) { ns::gain T(a...); },                      \
      [](auto&&... a) { ns::predicted_observation T(a...); }, [](S* s) { ns::initial_state T(s); },             \
      ns::Params<S> {}

int main() {
  exercise<float>(KIND_ARGS(as_float::three_two::optimal, float, ));
  exercise<float>(KIND_ARGS(as_template::three_two::optimal, float, <float>));
  exercise<double>(KIND_ARGS(as_template::three_two::optimal, double, <double>));
  exercise<double>(KIND_ARGS(as_template::three_two::ekf, double, <double>));
  if (failures == 0) std::printf("eigen wrappers: OK\n");
  return failures == 0 ? 0 : 1;
}
)program";

}  // namespace

TEST_CASE("pfgen codegen writes the Eigen wrappers only with --eigen", "[codegen][eigen][integration]") {
  TempDir dir;
  write_file(dir.file("three_two.yaml"), kModel);
  ProcessResult plain = run_pfgen({"codegen", dir.file("three_two.yaml"), "-o", dir.file("plain")});
  INFO(plain.err);
  REQUIRE(plain.exit_code == 0);
  std::vector<std::string> plain_files;
  for (const auto& entry : fs::directory_iterator(dir.file("plain/three_two"))) {
    plain_files.push_back(entry.path().filename().string());
    CHECK(read_file(entry.path().string()).find("Eigen") == std::string::npos);
  }
  CHECK(plain_files.size() == 2);  // optimal, ekf: no additive diffusion in this model

  ProcessResult eigen = run_pfgen({"codegen", dir.file("three_two.yaml"), "-o", dir.file("eigen"), "--eigen"});
  INFO(eigen.err);
  REQUIRE(eigen.exit_code == 0);
  for (const std::string& kind : pfgen::default_filter_names(pfgen::load_model_file(dir.file("three_two.yaml")))) {
    INFO(kind);
    // The plain header is the same with or without --eigen; the wrapper includes it and Eigen.
    CHECK(read_file(dir.file("eigen/three_two/" + std::string(kind) + ".hpp")) ==
          read_file(dir.file("plain/three_two/" + std::string(kind) + ".hpp")));
    const std::string wrapper = read_file(dir.file("eigen/three_two/" + std::string(kind) + "_eigen.hpp"));
    CHECK(wrapper.find("#include <Eigen/Core>") != std::string::npos);
    CHECK(wrapper.find("#include \"" + std::string(kind) + ".hpp\"") != std::string::npos);
    CHECK(wrapper.find("namespace pfgen_models::three_two::" + std::string(kind) + " {") != std::string::npos);
  }
  std::size_t files = 0;
  for (const auto& entry : fs::directory_iterator(dir.file("eigen/three_two"))) files += entry.is_regular_file();
  CHECK(files == 4);
}

TEST_CASE("Eigen wrappers compile warning-free, pack/unpack round-trip and agree with the flat API", "[codegen][eigen][compiler]") {
  TempDir dir;
  write_file(dir.file("three_two.yaml"), kModel);
  using Mode = std::pair<std::string, std::string>;  // --scalar, --namespace
  for (const auto& [scalar, ns] : {Mode{"float", "as_float"}, Mode{"template", "as_template"}}) {
    ProcessResult r = run_pfgen({"codegen", dir.file("three_two.yaml"), "-o", dir.file(scalar), "--scalar", scalar,
                                 "--namespace", ns, "--eigen"});
    INFO(r.err);
    REQUIRE(r.exit_code == 0);
  }
  write_file(dir.file("eigen_wrappers.cpp"), kProgram);
  for (const std::string compiler : {"g++", "clang++"}) {
    INFO(compiler << " is a test requirement (scripts/install-deps.sh)");
    REQUIRE(run_process("command -v " + compiler).exit_code == 0);
    const std::string exe = dir.file("eigen_wrappers-" + compiler);
    const std::string command = compiler + " -std=c++17 -O1 -Wall -Wextra -Werror -fno-exceptions -fno-rtti -I " +
                                shell_quote(dir.path()) + " -isystem " + shell_quote(PFGEN_EIGEN_INCLUDE_DIR) + " " +
                                shell_quote(dir.file("eigen_wrappers.cpp")) + " -o " + shell_quote(exe);
    ProcessResult built = run_process(command);
    INFO(command << "\n" << built.err.substr(0, 4000));
    REQUIRE(built.exit_code == 0);
    ProcessResult ran = run_process(shell_quote(exe));
    INFO(ran.out);
    CHECK(ran.exit_code == 0);
    CHECK(ran.out == "eigen wrappers: OK\n");
  }
}
