// Generated functions name their inputs as the model does (m1, P12, parameters, states, time), so
// a model may take the names the generated code uses for itself: its arguments (state, params,
// out, K, h; the truth's x, f, g, dg, A0, ...), its temporaries (tmp0, and tmp_1 once tmp moves
// to tmp_), the time argument t. A model taking all of them must still compile warning-free in
// every scalar mode, filters and truth, and compute what the same model with harmless names
// computes. Both are compiled out of process (g++ and clang++, -Wall -Wextra -Wunused -Werror)
// into one program that evaluates the two on the same random inputs and compares them.
#include <catch2/catch.hpp>

#include <filesystem>
#include <map>
#include <string>
#include <tuple>
#include <vector>

#include "pfgen/codegen/filter_codegen.hpp"
#include "pfgen/codegen/backends/cpp/truth_codegen.hpp"
#include "pfgen/derivation/filter_equations.hpp"
#include "pfgen/model/yaml_model_loader.hpp"
#include "support/cli_helpers.hpp"

namespace fs = std::filesystem;
using namespace pfgen_test;

namespace {

// Every name a generated function declares, taken by the model (each model name is marked `@`
// here, the time `TAU`): `t` is a parameter, the time is `tau`. std, n, p, rates, dy name things the
// generated code uses too (namespace, constants, step()'s locals and arguments; dt is refused: printed equations use it).
const char* const kModelTemplate = R"model(name: NAME
states: [@x, @f, @g]
time: TAU
parameters: {@tmp0: 0.5, @tmp_1: 0.25, @state: 1.5, @state_: 0.75, @params: 2, @out: 0.3, @K: 1.25, @h: 0.2,
             @t: 0.1, @rates: 0.4, @dy: 0.6, @std: 0.7, @n: 0.8, @p: 0.9, @A0: 0.05, @dg: 0.15, @x_: 0.35, @B: 1.1}
drift: ["-@tmp0*@x + @state*@f*@g + sin(TAU)*@t", "-@params*@f + @out*@x^2 + @tmp_1", "-@K*@g + @h*@x*@f + @state_*@rates"]
diffusion: [["0.1*@x + @dy", "0"], ["0", "@std*@f"], ["@n*@g", "@p"]]
additive_diffusion: [["@dy", "0"], ["0", "@std"], ["@n", "@p"]]
observation:
  A0: ["@A0*sin(TAU)", "@dg"]
  A: [["1", "0", "@x_"], ["0", "1", "0"]]
  B: [["@B", "0"], ["0", "1"]]
initial: {x0: [1, 0.5, -0.5], m0: [0.1, 0, 0], P0: [[1, 0, 0], [0, 1, 0.2], [0, 0.2, 1]]}
filters:
  mine:
    m_drift: ["-@tmp0*m1 + @out + @t*sin(TAU)", "-m2*@state", "-m3"]
    P_drift: [["P11*@K", "0", "0"], ["0", "P22", "0"], ["0", "0", "P33"]]
    gain: [["@h", "0"], ["0", "@params"], ["0", "0"]]
)model";

std::string replaced(std::string text, const std::string& from, const std::string& to) {
  for (std::size_t at = text.find(from); at != std::string::npos; at = text.find(from, at + to.size()))
    text.replace(at, from.size(), to);
  return text;
}

// `clash`: the names as they are. `plain`: the same model with names nothing in the generated
// code uses (every model name gets a `q_` prefix, the time is `t`).
std::string model_text(bool clash) {
  const std::string text = replaced(kModelTemplate, "NAME", clash ? "clash" : "plain");
  return replaced(replaced(text, "TAU", clash ? "tau" : "t"), "@", clash ? "" : "q_");
}

const char* const kFlags = "-std=c++17 -O1 -Wall -Wextra -Wunused -Werror -fno-exceptions -fno-rtti";

// The program's part for one filter of both models: derivatives, gain, predicted_observation and
// step of `clash` and of `plain` on the same inputs, at the parameters' defaults.
std::string filter_check(const std::string& filter, const std::string& scalar) {
  const std::string c = "pfgen_models::clash::" + filter, p = "pfgen_models::plain::" + filter;
  return "  {\n    namespace C = " + c + ";\n    namespace Q = " + p + ";\n    using S = " + scalar +
         ";\n"
         "    for (int run = 0; run < 50; ++run) {\n"
         "      std::array<S, C::state_size> state{};\n"
         "      for (auto& v : state) v = S(uniform(rng));\n"
         // P diagonally dominant, so positive definite: the ukf's Cholesky factor needs it.
         "      for (std::size_t i = 0, k = C::n; i < C::n; k += C::n - i, ++i) state[k] += S(3);\n"
         "      const S t = S(2 * uniform(rng) + 2), dt = S(0.01);\n"
         "      std::array<S, C::p> dy{};\n"
         "      for (auto& v : dy) v = S(0.1 * uniform(rng));\n"
         "      std::array<S, C::state_size> a{}, b{};\n"
         "      C::derivatives(t, state.data(), C::Params<S>{}, a.data());\n"
         "      Q::derivatives(t, state.data(), Q::Params<S>{}, b.data());\n"
         "      compare(\"" + filter + " derivatives\", a.data(), b.data(), a.size());\n"
         "      std::array<S, C::n * C::p> Ka{}, Kb{};\n"
         "      C::gain(t, state.data(), C::Params<S>{}, Ka.data());\n"
         "      Q::gain(t, state.data(), Q::Params<S>{}, Kb.data());\n"
         "      compare(\"" + filter + " gain\", Ka.data(), Kb.data(), Ka.size());\n"
         "      std::array<S, C::p> ha{}, hb{};\n"
         "      C::predicted_observation(t, state.data(), C::Params<S>{}, ha.data());\n"
         "      Q::predicted_observation(t, state.data(), Q::Params<S>{}, hb.data());\n"
         "      compare(\"" + filter + " predicted_observation\", ha.data(), hb.data(), ha.size());\n"
         "      a = state;\n      b = state;\n"
         "      C::step(a.data(), t, dt, dy.data(), C::Params<S>{});\n"
         "      Q::step(b.data(), t, dt, dy.data(), Q::Params<S>{});\n"
         "      compare(\"" + filter + " step\", a.data(), b.data(), a.size());\n"
         "    }\n  }\n";
}

// The truth's functions of both models on the same inputs.
std::string truth_check() {
  return R"(  for (int run = 0; run < 50; ++run) {
    double x[3], t = 2 * uniform(rng) + 2;
    for (double& v : x) v = uniform(rng);
    double a[18] = {}, b[18] = {};
    clash_truth::drift(t, x, a);
    plain_truth::drift(t, x, b);
    compare("truth drift", a, b, 3);
    clash_truth::diffusion(t, x, a);
    plain_truth::diffusion(t, x, b);
    compare("truth diffusion", a, b, 6);
    clash_truth::diffusion_jacobian(t, x, a);
    plain_truth::diffusion_jacobian(t, x, b);
    compare("truth diffusion_jacobian", a, b, 18);
    double A0a[2], Aa[6], Ba[4], A0b[2], Ab[6], Bb[4];
    clash_truth::observation(t, A0a, Aa, Ba);
    plain_truth::observation(t, A0b, Ab, Bb);
    compare("truth A0", A0a, A0b, 2);
    compare("truth A", Aa, Ab, 6);
    compare("truth B", Ba, Bb, 4);
    clash_truth::initial_state(a);
    plain_truth::initial_state(b);
    compare("truth x0", a, b, 3);
  }
)";
}

struct Generated {
  std::map<std::string, std::string> headers;  // relative path -> text
  std::vector<std::string> identifiers;         // the filters' C++ identifiers
};

Generated generate(const pfgen::Model& model, pfgen::codegen::ScalarMode scalar) {
  pfgen::codegen::CodegenOptions options;
  options.scalar = scalar;
  Generated out;
  for (const std::string& name : pfgen::available_filter_names(model)) {
    pfgen::codegen::GeneratedFilter f =
        pfgen::codegen::generate_filter_code(model, pfgen::derive_named_filter(model, name), options);
    out.headers[f.files.at(0).relative_path] = f.files.at(0).contents;
    out.identifiers.push_back(pfgen::filter_identifier(name));
  }
  return out;
}

}  // namespace

TEST_CASE("a model may take every name of the generated code: it compiles warning-free and computes the same",
          "[compiler][codegen][names]") {
  const pfgen::Model clash = pfgen::load_model_text(model_text(true), "clash.yaml");
  const pfgen::Model plain = pfgen::load_model_text(model_text(false), "plain.yaml");
  REQUIRE(plain.time.get_name() == "t");
  REQUIRE(plain.parameters.size() == clash.parameters.size());
  REQUIRE(plain.state_names == std::vector<std::string>{"q_x", "q_f", "q_g"});

  using pfgen::codegen::ScalarMode;
  for (const auto& [scalar, mode, tolerance] :
       {std::tuple{"double", ScalarMode::Double, "1e-12"}, std::tuple{"float", ScalarMode::Float, "1e-4"},
        std::tuple{"double", ScalarMode::Template, "1e-12"}}) {
    {
      INFO("scalar mode " << pfgen::codegen::scalar_mode_name(mode));
      TempDir dir;
      std::string program = "#include <array>\n#include <cmath>\n#include <cstdio>\n#include <random>\n";
      const Generated c = generate(clash, mode), p = generate(plain, mode);
      REQUIRE(c.identifiers == p.identifiers);
      for (const auto* generated : {&c, &p})
        for (const auto& [path, text] : generated->headers) {
          fs::create_directories(fs::path(dir.file(path)).parent_path());
          write_file(dir.file(path), text);
          program += "#include \"" + path + "\"\n";
        }
      // The clash model's code renames its own names, not the model's, and never to a name holding
      // '__' (reserved in C++): state and state_ are the model's, so the argument is state_2.
      const std::string& ekf = c.headers.at("clash/ekf.hpp");
      CHECK(ekf.find("(Scalar tau, const Scalar* state_2, const Params<Scalar>& params_, Scalar* K_)") !=
            std::string::npos);
      CHECK(ekf.find("  const Scalar tmp0 = params_.tmp0;\n") != std::string::npos);
      CHECK(ekf.find("  const Scalar tmp_2_0 = ") != std::string::npos);
      CHECK(ekf.find("tmp_0") == std::string::npos);
      // The plain model keeps the usual names.
      const std::string usual = "(Scalar t, const Scalar* state, const Params<Scalar>& params, Scalar* K)";
      CHECK(p.headers.at("plain/ekf.hpp").find(usual) != std::string::npos);

      const bool with_truth = mode == ScalarMode::Double;
      if (with_truth) {
        const std::string truth = pfgen::codegen::generate_truth_code(clash).definitions;
        CHECK(truth.find("inline void drift(double tau, const double* x_2, double* f_) {") != std::string::npos);
        CHECK(truth.find("  const Scalar x = x_2[0];\n") != std::string::npos);
        program += "namespace clash_truth {\n" + truth + "}\nnamespace plain_truth {\n" +
                   pfgen::codegen::generate_truth_code(plain).definitions + "}\n";
      }
      program += std::string("\nstatic int failures = 0;\n") +
                 "template <class S> void compare(const char* what, const S* a, const S* b, std::size_t size) {\n"
                 "  for (std::size_t k = 0; k < size; ++k)\n"
                 "    if (!(std::abs(a[k] - b[k]) <= S(" + tolerance + ") * (1 + std::abs(a[k]) + std::abs(b[k]))) &&\n"
                 "        failures++ < 10)\n"
                 "      std::printf(\"%s[%zu]: %.17g != %.17g\\n\", what, k, double(a[k]), double(b[k]));\n"
                 "}\n\nint main() {\n  std::mt19937 rng(7);\n"
                 "  std::uniform_real_distribution<double> uniform(-1.0, 1.0);\n";
      for (const auto& identifier : c.identifiers) program += filter_check(identifier, scalar);
      if (with_truth) program += truth_check();
      program += "  std::printf(failures ? \"%d mismatches\\n\" : \"agree\\n\", failures);\n"
                 "  return failures != 0;\n}\n";
      write_file(dir.file("check.cpp"), program);

      for (const char* compiler : {"g++", "clang++"}) {
        const std::string binary = dir.file(std::string("check-") + compiler);
        ProcessResult built = run_process(std::string(compiler) + " " + kFlags + " -I " + shell_quote(dir.path()) +
                                          " " + shell_quote(dir.file("check.cpp")) + " -o " + shell_quote(binary));
        INFO(compiler << ":\n" << built.err);
        REQUIRE(built.exit_code == 0);
        ProcessResult ran = run_process(shell_quote(binary));
        INFO(ran.out);
        CHECK(ran.exit_code == 0);
        CHECK(ran.out == "agree\n");
      }
    }
  }
}
