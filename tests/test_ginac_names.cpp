// Names GiNaC's parser gives a meaning of its own (its constants I, Pi, Euler and Catalan, and
// every function of its parser's table, read from the installed GiNaC so that a new version's
// names are tried at once) are a model's symbols when the model names them: an SIR model's
// state I, a parameter Euler that --set changes. And the functions a model may call are those
// both backends have, so derive and eval accept what codegen and simulate generate.
#include <catch2/catch.hpp>

#include <ginac/ginac.h>

#include <filesystem>
#include <set>

#include "pfgen/kinds/model_functions.hpp"
#include "pfgen/model/reserved_names.hpp"
#include "pfgen/model/yaml_model_loader.hpp"
#include "support/cli_helpers.hpp"

using namespace pfgen_test;
namespace fs = std::filesystem;

namespace {

// I, Pi, Euler, Catalan (the literals GiNaC's lexer knows), D (GiNaC's derivative notation), and
// every name in GiNaC's parser table (sin, zeta, S, beta, lst, pow, ...).
std::set<std::string> ginac_names() {
  std::set<std::string> names = {"I", "Pi", "Euler", "Catalan", "D"};
  for (const auto& [prototype, reader] : GiNaC::get_default_reader()) names.insert(prototype.first);
  return names;
}

// A model whose state is `state` and whose parameter is `parameter`, each used in the drift, the
// diffusion and a polynomial observation.
std::string model_text(const std::string& state, const std::string& parameter) {
  return "name: names\nstates: [\"" + state + "\"]\nparameters: {\"" + parameter + "\": 0.5}\n" +
         "drift: [\"-" + parameter + "*" + state + " + 0.25*" + state + "^2\"]\n" +
         "diffusion: [[\"" + parameter + "\"]]\n" +
         "observation: {h: [\"" + state + "^3 + " + parameter + "*" + state + "\"], B: [[\"1\"]]}\n" +
         "initial: {x0: [0.5], m0: [0.5], P0: [[0.1]]}\n";
}

// A model function called with `arity` arguments of t: "atan2(t, t + 2)".
std::string call_of_t(const pfgen::ModelFunction& f) {
  // Arguments where every function is real and finite for t in (0, 1]: acosh needs >= 1.
  std::string out = f.name + (f.name == "acosh" ? "(t + 1.5" : "(t/4");
  for (std::size_t k = 1; k < f.arity; ++k) out += ", t + 2";
  return out + ")";
}

// Compiles a generated file as its users do, warnings as errors: a C source (.c, which includes
// its .h) as C99, a C++ header (.hpp) included from a source file as C++17.
void check_compiles(const TempDir& dir, const fs::path& file) {
  std::string command;
  if (file.extension() == ".c") {
    command = "gcc -std=c99 -pedantic -I " + shell_quote(file.parent_path().string()) + " " + shell_quote(file.string());
  } else if (file.extension() == ".hpp") {
    write_file(dir.file("use.cpp"), "#include \"" + file.string() + "\"\n");
    command = "g++ -std=c++17 " + shell_quote(dir.file("use.cpp"));
  } else {
    return;  // a C header: its source includes it
  }
  ProcessResult compiled = run_process(command + " -fsyntax-only -Wall -Wextra -Werror");
  INFO(file << ": " << compiled.err.substr(0, 2000));
  CHECK(compiled.exit_code == 0);
}

}  // namespace

TEST_CASE("GiNaC's names: a model's state or parameter of that name is the model's own symbol",
          "[unit][model]") {
  for (const std::string& name : ginac_names()) {
    INFO(name);
    const std::string other = name == "x" ? "y" : "x";
    const std::string k = name == "k" ? "q" : "k";
    if (auto problem = pfgen::symbol_name_problem(name)) {
      // The C backend calls it (sin, exp, ...): a variable of that name would hide the function.
      CHECK(problem->find("<math.h> function") != std::string::npos);
      CHECK_THROWS_WITH(pfgen::load_model_text(model_text(name, k), "m.yaml"),
                        Catch::Contains("'" + name + "' is a <math.h> function"));
      continue;
    }
    // As a state: the drift and h are polynomials in it (a state I was refused as not real, a
    // state Pi read as the number pi).
    const pfgen::Model as_state = pfgen::load_model_text(model_text(name, k), "m.yaml");
    const GiNaC::ex x = as_state.states.at(0), a = as_state.parameters.at(0).symbol;
    CHECK(as_state.state_names.at(0) == name);
    CHECK(GiNaC::ex_to<GiNaC::symbol>(x).get_name() == name);
    CHECK((as_state.drift.at(0) - (-a * x + GiNaC::numeric(1, 4) * GiNaC::pow(x, 2))).expand().is_zero());
    CHECK((as_state.observation.rate().rows().at(0) - (GiNaC::pow(x, 3) + a * x)).expand().is_zero());
    // As a parameter: its own symbol, whose value --set changes (Euler was read as 0.5772...).
    const pfgen::Model as_parameter = pfgen::load_model_text(model_text(other, name), "m.yaml");
    const GiNaC::ex p = as_parameter.parameters.at(0).symbol, y = as_parameter.states.at(0);
    CHECK(as_parameter.parameters.at(0).name == name);
    CHECK(GiNaC::ex_to<GiNaC::symbol>(p).get_name() == name);
    CHECK((as_parameter.drift.at(0) - (-p * y + GiNaC::numeric(1, 4) * GiNaC::pow(y, 2))).expand().is_zero());
  }
  // Outside a model's names, Pi, Euler and Catalan are GiNaC's constants and I is refused.
  const std::string constants = "name: c\nstates: [x]\ndrift: [\"-Pi*x\"]\ndiffusion: [[\"Euler\"]]\n"
                                "observation: {A: [[\"1\"]], B: [[\"1\"]]}\n";
  const pfgen::Model model = pfgen::load_model_text(constants, "c.yaml");
  CHECK((model.drift.at(0) + GiNaC::Pi * model.states.at(0)).is_zero());
  CHECK_THROWS_WITH(pfgen::load_model_text("name: c\nstates: [x]\ndrift: [\"-I*x\"]\ndiffusion: [[\"1\"]]\n"
                                           "observation: {A: [[\"1\"]], B: [[\"1\"]]}\n", "c.yaml"),
                    Catch::Contains("is not real"));
  // A parse error names the model's names, not the aliases GiNaC read.
  std::string unparsable = model_text("Pi", "k");
  unparsable.replace(unparsable.find("-k*Pi"), 5, "-k Pi");
  CHECK_THROWS_WITH(pfgen::load_model_text(unparsable, "m.yaml"), Catch::Contains("expected EOF, got: \"Pi\""));
  // And GiNaC's constant where a name is not the model's: its token has no character to print.
  CHECK_THROWS_WITH(pfgen::load_model_text("name: c\nstates: [x]\ndrift: [\"-(x I)\"]\ndiffusion: [[\"1\"]]\n"
                                           "observation: {A: [[\"1\"]], B: [[\"1\"]]}\n", "c.yaml"),
                    Catch::Contains("cannot parse '-(x I)': expected ')', got: a constant (I, Pi, Euler or Catalan)"));
}

TEST_CASE("GiNaC's names: derive, eval, codegen in C++ and C, and simulate of a model using every one",
          "[compiler][model]") {
  TempDir dir;
  // The constants as states, every other accepted name as a parameter, each used.
  std::vector<std::string> states = {"I", "Pi", "Euler", "Catalan", "D"}, parameters;
  for (const std::string& name : ginac_names())
    if (!pfgen::symbol_name_problem(name) && std::find(states.begin(), states.end(), name) == states.end())
      parameters.push_back(name);
  REQUIRE(parameters.size() > 20);  // S, G, H, beta, zeta, psi, lst, step, Order, ...
  std::string text = "name: names\nstates: [I, Pi, Euler, Catalan, D]\nparameters: {";
  std::string rate = "0";
  for (std::size_t k = 0; k < parameters.size(); ++k) {
    text += (k ? ", " : "") + parameters[k] + ": 0.5";
    rate += " + " + parameters[k];
  }
  text += "}\ndrift: [\"-(" + rate + ")*I + Pi\", \"-Pi\", \"-Euler + Catalan\", \"-Catalan\", \"-D*I\"]\n";
  text += "diffusion: [[\"0.1\", \"0\", \"0\", \"0\", \"0\"], [\"0\", \"0.1\", \"0\", \"0\", \"0\"], "
          "[\"0\", \"0\", \"0.1\", \"0\", \"0\"], [\"0\", \"0\", \"0\", \"0.1\", \"0\"], [\"0\", \"0\", \"0\", \"0\", \"0.1\"]]\n";
  text += "observation: {h: [\"I^2 + Pi + Euler + Catalan + D\"], B: [[\"1\"]]}\n";
  text += "initial: {x0: [1, 0, 0, 0, 0], m0: [1, 0, 0, 0, 0], P0: [[0.1, 0, 0, 0, 0], [0, 0.1, 0, 0, 0], "
          "[0, 0, 0.1, 0, 0], [0, 0, 0, 0.1, 0], [0, 0, 0, 0, 0.1]]}\n";
  write_file(dir.file("names.yaml"), text);

  ProcessResult derive = run_pfgen({"derive", dir.file("names.yaml"), "--filter", "optimal"});
  INFO(derive.err);
  REQUIRE(derive.exit_code == 0);
  CHECK(derive.out.find("m1 = E[I], m2 = E[Pi], m3 = E[Euler], m4 = E[Catalan], m5 = E[D]") != std::string::npos);
  CHECK(derive.out.find("dm5 = (-m1*m5 - P15) dt") != std::string::npos);  // -D*I: two states

  // eval reads each parameter's value: 0.5 each, or what --set gives (Euler was 0.5772 whatever it was set to).
  auto m1_drift = [&](const std::vector<std::string>& set) {
    std::vector<std::string> args = {"eval", dir.file("names.yaml"), "--filter", "optimal", "--t", "0",
                                     "--m", "1,2,3,4,5", "--P", "0.1,0,0,0,0;0,0.1,0,0,0;0,0,0.1,0,0;0,0,0,0.1,0;0,0,0,0,0.1"};
    for (const auto& s : set) args.insert(args.end(), {"--set", s});
    ProcessResult r = run_pfgen(args);
    INFO(r.err);
    REQUIRE(r.exit_code == 0);
    const auto at = r.out.find("\"m_drift\": [") + 12;
    return std::stod(r.out.substr(at, r.out.find(',', at) - at));
  };
  const double half = 0.5 * static_cast<double>(parameters.size());
  CHECK(m1_drift({}) == Approx(-half + 2));
  CHECK(m1_drift({"zeta=1.5"}) == Approx(-half - 1 + 2));

  // The generated code compiles in C++ and C (a parameter I stays a field: C's I is <complex.h>'s,
  // which the code does not include).
  for (const char* language : {"cpp", "c"}) {
    const std::string out = dir.file(std::string("gen_") + language);
    ProcessResult codegen = run_pfgen({"codegen", dir.file("names.yaml"), "-o", out, "--language", language,
                                       "--scalar", "double", "--filter", "optimal"});
    INFO(codegen.err);
    REQUIRE(codegen.exit_code == 0);
    for (const auto& entry : fs::recursive_directory_iterator(out))
      if (entry.is_regular_file()) check_compiles(dir, entry.path());
  }
  ProcessResult simulate = run_pfgen({"simulate", dir.file("names.yaml"), "--filters", "optimal,ekf", "--T", "0.02",
                                      "--dt", "0.01", "--runs", "2", "--cache-dir", dir.file("cache"), "-q"});
  INFO(simulate.err.substr(0, 2000));
  CHECK(simulate.exit_code == 0);
}

TEST_CASE("model functions: derive, eval, codegen in C++ and C agree on every function a model may call",
          "[compiler][model]") {
  TempDir dir;
  std::string rate = "a";
  for (const pfgen::ModelFunction& f : pfgen::model_functions()) rate += " + " + call_of_t(f);
  const std::string text = "name: functions\nstates: [x]\nparameters: {a: 1}\ndrift: [\"-(" + rate + ")*x\"]\n"
                           "diffusion: [[\"1\"]]\nobservation: {A: [[\"1\"]], B: [[\"1\"]]}\n"
                           "initial: {x0: [1], m0: [0], P0: [[1]]}\n";
  write_file(dir.file("functions.yaml"), text);
  REQUIRE(run_pfgen({"derive", dir.file("functions.yaml")}).exit_code == 0);
  ProcessResult eval = run_pfgen({"eval", dir.file("functions.yaml"), "--filter", "optimal", "--t", "0.5", "--m", "1",
                                  "--P", "1"});
  INFO(eval.err);
  REQUIRE(eval.exit_code == 0);
  for (const char* language : {"cpp", "c"})
    for (const char* scalar : {"double", "float"}) {
      const std::string out = dir.file(std::string("gen_") + language + scalar);
      ProcessResult codegen = run_pfgen({"codegen", dir.file("functions.yaml"), "-o", out, "--language", language,
                                         "--scalar", scalar});
      INFO(language << " " << scalar << ": " << codegen.err);
      REQUIRE(codegen.exit_code == 0);
      for (const auto& entry : fs::recursive_directory_iterator(out)) {
        if (!entry.is_regular_file()) continue;
        const bool c = entry.path().extension() == ".c";
        if (!c && entry.path().extension() != ".hpp") continue;
        const std::string code = read_file(entry.path().string());
        // Each function by its name in that language: std::asinh, asinhf, fabs for abs.
        for (const pfgen::ModelFunction& f : pfgen::model_functions()) {
          const std::string called = c ? f.c_name + (std::string(scalar) == "float" ? "f(" : "(") : "std::" + f.name + "(";
          CHECK(code.find(called) != std::string::npos);
        }
        check_compiles(dir, entry.path());
      }
    }
  // Functions GiNaC knows and no backend has are refused when the model is read, naming the field.
  for (const char* refused : {"zeta(t)", "psi(t)", "step(t)", "factorial(t)", "Li2(t)", "csgn(t)", "power(t, 2)",
                              "conjugate(t)", "EllipticK(t)", "lst()"}) {
    std::string bad = text;
    bad.replace(bad.find("(a + ") + 1, 1, std::string(refused) + " + a");
    write_file(dir.file("bad.yaml"), bad);
    for (const char* command : {"derive", "codegen"}) {
      ProcessResult r = run_pfgen({command, dir.file("bad.yaml"), "--stats"});
      if (std::string(command) == "derive") r = run_pfgen({command, dir.file("bad.yaml")});
      INFO(refused << ": " << r.err);
      CHECK(r.exit_code == 1);
      CHECK(count_lines(r.err) == 1);
      CHECK(r.err.find("bad.yaml:4:") != std::string::npos);
      // lst() is refused before: a function needs an argument.
      CHECK(r.err.find(std::string("field 'drift', row 1: ") + (refused[0] == 'l' ? "" : "unknown function")) !=
            std::string::npos);
    }
  }
}

TEST_CASE("model functions: lgamma is C's log|Gamma| in eval too, and a pole is named", "[integration][model]") {
  TempDir dir;
  write_file(dir.file("g.yaml"), "name: g\nstates: [x]\ndrift: [\"-lgamma(t)*x\"]\ndiffusion: [[\"1\"]]\n"
                                 "observation: {A: [[\"1\"]], B: [[\"1\"]]}\n");
  // Gamma(-0.5) = -2 sqrt(pi) < 0: GiNaC's complex log Gamma was refused as not real.
  ProcessResult r = run_pfgen({"eval", dir.file("g.yaml"), "--filter", "ekf", "--t", "-0.5", "--m", "1", "--P", "1"});
  INFO(r.err);
  REQUIRE(r.exit_code == 0);
  const auto at = r.out.find("\"m_drift\": [") + 12;
  CHECK(std::stod(r.out.substr(at)) == Approx(-std::lgamma(-0.5)).epsilon(1e-14));
  ProcessResult pole = run_pfgen({"eval", dir.file("g.yaml"), "--filter", "ekf", "--t", "-1", "--m", "1", "--P", "1"});
  CHECK(pole.exit_code == 1);
  CHECK(pole.err == "pfgen: error: m_drift[1] cannot be computed at this point (a pole of a function, a division by "
                    "zero or an overflow)\n");
}
