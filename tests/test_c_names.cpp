// The C backend's file-scope names (codegen/backends/c/c_names.hpp): every filter of one model
// builds into one program in every dialect a C user compiles with (C99 -pedantic, gcc's default
// gnu17, clang, the headers as C++, arm-none-eabi-gcc), and what cannot is refused with the reason
// before anything is written: a parameter named like an include guard, a model's filter whose
// names another filter declares, a gnu17 keyword, names the generator would make reserved ('__',
// a leading '_'), internal names C99 does not tell apart (63 characters). A split function's
// parts whose names would pass 63 characters get a shortened name, unique in one translation unit.
#include <catch2/catch.hpp>

#include <algorithm>
#include <filesystem>
#include <regex>
#include <set>
#include <string>
#include <vector>

#include "pfgen/codegen/backends/c/c_filter_writer.hpp"
#include "pfgen/codegen/backends/c/c_names.hpp"
#include "pfgen/codegen/observation_code.hpp"
#include "pfgen/model/yaml_model_loader.hpp"
#include "support/cli_helpers.hpp"

using namespace pfgen_test;

namespace {

// A one-state model with these parameters (each used by the drift) and this model's own filters.
std::string scalar_model(const std::string& name, const std::vector<std::string>& extra_parameters,
                         const std::string& filters = "") {
  std::string parameters = "a: 1, s: 0.5", drift = "-a*x";
  for (const std::string& p : extra_parameters) {
    parameters += ", " + p + ": 0.25";
    drift += " + " + p + "*x^3";
  }
  return "name: " + name + "\nstates: [x]\nparameters: {" + parameters + "}\ndrift: [\"" + drift +
         "\"]\ndiffusion: [[\"s*x\"]]\nadditive_diffusion: [[\"s\"]]\nobservation: {A: [[\"1\"]], B: [[\"0.1\"]]}\n"
         "initial: {m0: [0.5], P0: [[1]]}\n" + filters;
}

const char* const kOwnFilter = R"(filters:
  NAME:
    m_drift: ["-a*m1"]
    P_drift: [["-2*a*P11 + s^2*(m1^2 + P11) - P11^2/0.01"]]
    gain: [["P11/0.01"]]
)";

std::string own_filter(const std::string& name) {
  return std::regex_replace(kOwnFilter, std::regex("NAME"), name);
}

std::string delayed_model(const std::string& filters) {
  return "name: d\nstates: [x]\nparameters: {a: -0.5, s: 0.3}\ndrift: [a*x]\ndiffusion: [[s]]\n"
         "observation: {delay: 0.5, A: [[1]], B: [[0.2]]}\ninitial: {m0: [0.5], P0: [[0.25]]}\n"
         "simulation: {dt: 0.01}\n" + filters;
}

struct Refused {
  std::string what, model_text;
  std::vector<std::string> options;
  std::string message;
};

}  // namespace

TEST_CASE("C code generation refuses names that cannot build in one program, with the reason",
          "[c_names][integration]") {
  const std::string long_name(63, 'm');
  const std::vector<Refused> cases = {
      {"a parameter named like optimal's include guard", scalar_model("m", {"pfgen_models_m_optimal_h"}), {},
       "parameters.pfgen_models_m_optimal_h: 'pfgen_models_m_optimal_h' starts with 'pfgen_models_m_', the prefix "
       "of every name the generated C code declares"},
      {"the model's filter optimal-default, whose _params is optimal's default_params",
       scalar_model("m", {}, own_filter("optimal-default")), {},
       "filters.optimal-default: filters 'optimal' and 'optimal-default' would both declare the C name "
       "'pfgen_models_m_optimal_default_params'"},
      {"a delayed model's filter delay-optimal-filter, whose step is delay-optimal's filter_step",
       delayed_model(own_filter("delay-optimal-filter")), {},
       "filters.delay-optimal-filter: filters 'delay-optimal' and 'delay-optimal-filter' would both declare the C "
       "name 'pfgen_models_d_delay_optimal_filter_step'"},
      {"typeof, a keyword of gnu17", scalar_model("m", {"typeof"}), {},
       "'typeof' is a keyword of C23 and of gcc's default C (gnu17)"},
      {"a model name ending in _", scalar_model("x_", {}), {}, "'x_' ends with '_'"},
      {"a model name starting with _", scalar_model("_x", {}), {}, "'_x' starts with '_'"},
      {"a filter name ending in -", scalar_model("m", {}, own_filter("mine-")), {}, "'mine_' ends with '_'"},
      {"a namespace starting with _", scalar_model("m", {}), {"--namespace", "_a"}, "--namespace: '_a' starts with '_'"},
      {"a namespace part ending in _", scalar_model("m", {}), {"--namespace", "a_::b"},
       "--namespace: 'a_::b' gives the C names the prefix 'a__b_m_', and a name holding '__' is reserved"},
      {"a namespace part starting with _", scalar_model("m", {}), {"--namespace", "a::_b"},
       "--namespace: 'a::_b' gives the C names the prefix 'a__b_m_'"},
      {"a 63-character model name", scalar_model(long_name, {}), {},
       "agree in their first 63 characters, all that C99 promises to tell apart"},
  };
  for (const Refused& c : cases) {
    TempDir dir;
    write_file(dir.file("model.yaml"), c.model_text);
    std::vector<std::string> args = {"codegen", dir.file("model.yaml"), "-o", dir.file("out"), "--language", "c"};
    args.insert(args.end(), c.options.begin(), c.options.end());
    const auto result = run_pfgen(args);
    INFO(c.what << ": " << result.err);
    CHECK(result.exit_code == 1);
    CHECK(count_lines(result.err) == 1);
    CHECK(result.err.find(c.message) != std::string::npos);
    // The model file is named, unless the option is at fault.
    if (c.message.rfind("--", 0) != 0) CHECK(result.err.find(dir.file("model.yaml")) != std::string::npos);
    CHECK(!std::filesystem::exists(dir.file("out")));
  }
}

TEST_CASE("split functions' parts of a long model name get names within 63 characters, unique in one unity build",
          "[c_names][compiler]") {
  // A 30-character model name: <prefix>_<function>_part<k> passes 63 characters, so each part is named
  // <head>_<function>_part<k>_<hash>. The filters' heads are the same, so the hashes alone tell them apart:
  // every .c file included into one translation unit (a unity build, common on embedded targets) must build.
  // A model filter named <head>_<hash> (found by a review) would have met the hash in the middle of the name.
  TempDir dir;
  const std::string name(30, 'm');
  write_file(dir.file("model.yaml"), scalar_model(name, {}, own_filter("optimal-dflt")));
  const auto generated = run_pfgen({"codegen", dir.file("model.yaml"), "-o", dir.file("out"), "--language", "c",
                                    "--max-function-ops", "3", "--filter",
                                    "optimal,additive,ekf,ekf-additive,ukf,closure3,closure4,optimal-dflt"});
  INFO(generated.err);
  REQUIRE(generated.exit_code == 0);
  std::string unity = "#include <stddef.h>\n";
  std::set<std::string> parts;
  const std::regex part("\\b[A-Za-z0-9_]+_part[0-9]+(_[0-9a-f]{8})?\\b");
  for (const auto& entry : std::filesystem::directory_iterator(dir.file("out/" + name))) {
    if (entry.path().extension() != ".c") continue;
    unity += "#include \"" + entry.path().string() + "\"\n";
    const std::string text = read_file(entry.path().string());
    for (auto it = std::sregex_iterator(text.begin(), text.end(), part); it != std::sregex_iterator(); ++it) {
      INFO(entry.path() << ": " << it->str());
      CHECK(it->str().size() <= 63);
      CHECK(it->str().find("__") == std::string::npos);
      parts.insert(it->str());
    }
  }
  CHECK(parts.size() > 20);
  // Same head, told apart by the hash: closure3's and closure4's first part of one function differ.
  CHECK(std::count_if(parts.begin(), parts.end(), [](const std::string& p) {
          return std::regex_match(p, std::regex(".*_derivatives_part0_[0-9a-f]{8}"));
        }) >= 2);
  unity += "int main(void) { return 0; }\n";
  write_file(dir.file("unity.c"), unity);
  const auto r = run_process("gcc -std=c99 -Wall -Wextra -pedantic-errors -Werror -Wno-unused-function -I " +
                             dir.file("out") + " " + dir.file("unity.c") + " -lm -o " + dir.file("a.out"));
  INFO(r.err.substr(0, 2000));
  CHECK(r.exit_code == 0);
  // The name docs/guide/generated-code.md gives.
  const auto vdp = run_pfgen({"codegen", std::string(PFGEN_SOURCE_DIR) + "/examples/polynomial/van_der_pol_energy.yaml",
                              "-o", dir.file("vdp"), "--language", "c", "--filter", "closure4"});
  INFO(vdp.err);
  REQUIRE(vdp.exit_code == 0);
  CHECK_THAT(read_file(dir.file("vdp/van_der_pol_energy/closure4.c")),
             Catch::Matchers::Contains("pfgen_models_van_der_pol_stratonovich_correction_part0_5c742135("));
}

TEST_CASE("every name the C filters declare after their prefix is read from their module's templates",
          "[c_names][unit]") {
  // The names the checks compare come from the templates of the module's layouts and declaring
  // frames (c_module_templates): a name a template declares that the list misses would escape them.
  const auto continuous =
      pfgen::codegen::c_name_suffixes(pfgen::codegen::c_module_templates(pfgen::codegen::continuous_observation_code()));
  CHECK(continuous.external.count("default_params"));
  CHECK(continuous.external.count("step"));
  CHECK(continuous.internal.count("params"));  // a typedef
  CHECK(continuous.internal.count("state_size"));  // an enum constant
  CHECK(continuous.internal.count("h"));  // the include guard
  CHECK(continuous.internal.count("rates"));  // static in the .c
  const auto delayed = pfgen::codegen::c_name_suffixes(pfgen::codegen::c_module_templates(pfgen::codegen::delayed_observation_code()));
  CHECK(delayed.external.count("filter_step"));
  CHECK(delayed.internal.count("filter"));
  const auto sampled = pfgen::codegen::c_name_suffixes(pfgen::codegen::c_module_templates(pfgen::codegen::sampled_observation_code()));
  CHECK(sampled.external.count("euler_square"));  // from a partial
  CHECK(sampled.internal.count("packed_at"));
}

TEST_CASE("every filter of a model with hostile but valid names builds into one C program in every dialect",
          "[c_names][compiler]") {
  // Parameters whose names the generated code would take (shared, the split parts' array; tmp1 and
  // tmp_1, the temporaries), a filter whose name extends a kind's (optimal-dflt: no suffix of
  // optimal's starts with dflt), and functions split in parts (whose names stay within 63
  // characters). No name holds '__' or starts with '_'.
  TempDir dir;
  const std::string name = "hostile";
  write_file(dir.file("model.yaml"),
             scalar_model(name, {"shared", "shared_", "tmp1", "tmp_1", "shared_2"}, own_filter("optimal-dflt")));
  write_file(dir.file("delayed.yaml"), delayed_model(own_filter("delay-optimal-filtered")));
  for (const auto& [model, model_name] : {std::pair<std::string, std::string>{"model.yaml", name}, {"delayed.yaml", "d"}}) {
    const auto generated = run_pfgen({"codegen", dir.file(model), "-o", dir.file("out"), "--language", "c",
                                      "--max-function-ops", "3", "--filter", model == "model.yaml"
                                          ? "optimal,additive,ekf,ekf-additive,ukf,optimal-dflt"
                                          : "delay-optimal,delay-uncorrected,delay-ekf,delay-optimal-filtered"});
    INFO(generated.err);
    REQUIRE(generated.exit_code == 0);
    std::string main = "#include <stddef.h>\n";
    std::string sources;
    const std::regex word("\\b[A-Za-z_][A-Za-z0-9_]*\\b");
    for (const auto& entry : std::filesystem::directory_iterator(dir.file("out/" + model_name))) {
      const std::string path = entry.path().string();
      // The code without its comments, which write Phi*_ii and x*_i.
      const std::string text = std::regex_replace(read_file(path), std::regex("//[^\n]*"), "");
      for (auto it = std::sregex_iterator(text.begin(), text.end(), word); it != std::sregex_iterator(); ++it) {
        const std::string identifier = it->str();
        INFO(path << ": " << identifier);
        if (identifier == "__cplusplus") continue;
        CHECK(identifier.find("__") == std::string::npos);
        CHECK(identifier.front() != '_');
      }
      if (entry.path().extension() == ".h")
        main += "#include \"" + model_name + "/" + entry.path().filename().string() + "\"\n";
      else
        sources += " " + path;
    }
    main += "int main(void) { return 0; }\n";
    write_file(dir.file("main.c"), main);
    write_file(dir.file("main.cpp"), main);
    const std::string in = " -I " + dir.file("out") + " " + dir.file("main.c") + sources + " -lm -o " + dir.file("a.out");
    std::vector<std::string> commands = {
        "gcc -std=c99 -Wall -Wextra -pedantic-errors -Werror" + in,
        "gcc -Wall -Wextra -Werror" + in,  // gcc's default, gnu17: typeof and asm are keywords
        "clang -std=c99 -Wall -Wextra -Wpedantic -Werror" + in,
        "g++ -std=c++17 -Wall -Wextra -Werror -fsyntax-only -I " + dir.file("out") + " " + dir.file("main.cpp"),
    };
    for (const std::string& command : commands) {
      const auto r = run_process(command);
      INFO(command << "\n" << r.err.substr(0, 2000));
      CHECK(r.exit_code == 0);
    }
    // arm-none-eabi-gcc's default dialect is gnu17 too; one object per call.
    if (run_process("command -v arm-none-eabi-gcc").exit_code == 0)
      for (const auto& entry : std::filesystem::directory_iterator(dir.file("out/" + model_name)))
        if (entry.path().extension() == ".c") {
          const auto r = run_process("arm-none-eabi-gcc -mcpu=cortex-m4 -mthumb -Wall -Wextra -Werror -c -I " +
                                     dir.file("out") + " " + entry.path().string() + " -o " + dir.file("part.o"));
          INFO(entry.path() << "\n" << r.err.substr(0, 2000));
          CHECK(r.exit_code == 0);
        }
    std::filesystem::remove_all(dir.file("out"));
  }
}
