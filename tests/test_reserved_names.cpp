// Every C++ keyword, every macro the included headers define that we know of, and every
// identifier the code templates use, tried as a parameter, a state, a model name and a filter
// name: pfgen either refuses it with one line naming the field, or the code it generates for it
// compiles (filters in every scalar mode, and the simulation plugin).
#include <catch2/catch.hpp>

#include <filesystem>
#include <regex>
#include <set>

#include "pfgen/model/reserved_names.hpp"
#include "support/cli_helpers.hpp"

using namespace pfgen_test;
namespace fs = std::filesystem;

namespace {

// The names to try: C++ keywords and alternative tokens, library macros, and every identifier
// the C++ templates contain (read from templates/cpp and the C++ backend's templates, so a new
// template name is tried at once).
std::set<std::string> candidate_names() {
  std::set<std::string> names = {
      "alignas", "alignof", "and", "and_eq", "asm", "auto", "bitand", "bitor", "bool", "break", "case", "catch",
      "char", "char8_t", "char16_t", "char32_t", "class", "compl", "concept", "const", "consteval", "constexpr",
      "constinit", "const_cast", "continue", "co_await", "co_return", "co_yield", "decltype", "default", "delete",
      "do", "double", "dynamic_cast", "else", "enum", "explicit", "export", "extern", "false", "float", "for",
      "friend", "goto", "if", "inline", "int", "long", "mutable", "namespace", "new", "noexcept", "not", "not_eq",
      "nullptr", "operator", "or", "or_eq", "private", "protected", "public", "register", "reinterpret_cast",
      "requires", "return", "short", "signed", "sizeof", "static", "static_assert", "static_cast", "struct",
      "switch", "template", "this", "thread_local", "throw", "true", "try", "typedef", "typeid", "typename",
      "union", "unsigned", "using", "virtual", "void", "volatile", "wchar_t", "while", "xor", "xor_eq", "final",
      "override", "import", "module", "M_PI", "M_E", "NAN", "INFINITY", "HUGE_VAL", "NULL", "errno", "assert",
      "EOF", "stdin", "stdout", "offsetof", "std", "size_t", "Scalar", "Params", "_Reserved", "a__b", "main", "Eigen", "NULL", "true", "no"};
  const std::regex identifier("[A-Za-z_][A-Za-z0-9_]*");
  std::vector<std::string> folders = {source_dir() + "/templates/cpp",
                                      source_dir() + "/generator/src/codegen/backends/cpp/templates"};
  for (const auto& folder : folders)
    for (const auto& entry : fs::directory_iterator(folder)) {
      std::string text = std::regex_replace(read_file(entry.path().string()), std::regex("\\{\\{[a-z_]+\\}\\}"), " ");
      for (auto it = std::sregex_iterator(text.begin(), text.end(), identifier); it != std::sregex_iterator(); ++it)
        names.insert(it->str());
    }
  // The test model's own symbols (state x, parameter a, time t) would clash for another reason.
  for (const char* own : {"x", "a", "t"}) names.erase(own);
  return names;
}

std::string model_text(const std::string& model_name, const std::string& state, const std::string& parameter,
                       const std::vector<std::string>& filters) {
  // Names quoted, so that YAML reads NULL, true or no as the string it is.
  std::string text = "name: \"" + model_name + "\"\nstates: [\"" + state + "\"]\n";
  text += "parameters: {\"" + parameter + "\": 0.5}\n";
  text += "drift: [\"-" + parameter + "*" + state + " + 0.1*" + state + "^2\"]\n";
  text += "diffusion: [[\"0.1*" + state + "\"]]\n";
  text += "observation: {A: [[\"1\"]], B: [[\"1\"]]}\n";
  text += "initial: {x0: [1], m0: [0], P0: [[1]]}\n";
  if (!filters.empty()) {
    text += "filters:\n";
    for (const auto& f : filters)
      text += "  \"" + f + "\": {m_drift: [\"-m1\"], P_drift: [[\"-P11\"]], gain: [[\"P11\"]]}\n";
  }
  return text;
}

// Runs codegen on the model; true when accepted. A refusal must be one line naming `field`.
bool accepted(const TempDir& dir, const std::string& text, const std::string& name, const std::string& field) {
  write_file(dir.file("m.yaml"), text);
  ProcessResult r = run_pfgen({"codegen", dir.file("m.yaml"), "--stats"});
  if (r.exit_code == 0) return true;
  INFO(name << " as " << field << ": " << r.err);
  CHECK(r.exit_code == 1);
  CHECK(count_lines(r.err) == 1);
  // The field, or (for names the expression parser cannot read, such as _Reserved) the
  // expression that holds the name.
  CHECK((r.err.find("field '" + field) != std::string::npos || r.err.find(name) != std::string::npos));
  CHECK(r.err.find(name) != std::string::npos);
  return false;
}

void compile_headers(const TempDir& dir, const std::string& generated, const std::string& label) {
  std::string source;
  for (const auto& entry : fs::recursive_directory_iterator(generated))
    if (entry.path().extension() == ".hpp") source += "#include \"" + entry.path().string() + "\"\n";
  source += "int main() { return 0; }\n";
  write_file(dir.file(label + ".cpp"), source);
  ProcessResult r = run_process("g++ -std=c++17 -fsyntax-only -Wall -Wextra -Werror -I " +
                                shell_quote(PFGEN_EIGEN_INCLUDE_DIR) + " " + shell_quote(dir.file(label + ".cpp")));
  INFO(label << ": " << r.err.substr(0, 3000));
  CHECK(r.exit_code == 0);
}

}  // namespace

TEST_CASE("reserved names: keywords, macros and the templates' identifiers are refused or compile",
          "[compiler][codegen]") {
  TempDir dir;
  std::vector<std::string> good_parameters, good_models, good_filters;
  for (const std::string& name : candidate_names()) {
    INFO(name);
    // The library's verdict and the command's agree.
    const bool refused_by_rule = pfgen::symbol_name_problem(name).has_value();
    const bool as_parameter = accepted(dir, model_text("ok", "x", name, {}), name, "parameters." + name);
    if (name[0] != '_') CHECK(as_parameter == !refused_by_rule);
    if (as_parameter) good_parameters.push_back(name);
    const bool as_state = accepted(dir, model_text("ok", name, "a", {}), name, "states");
    CHECK(as_state == as_parameter);
    if (accepted(dir, model_text(name, "x", "a", {}), name, "name")) good_models.push_back(name);
    if (accepted(dir, model_text("ok", "x", "a", {name}), name, "filters." + name)) good_filters.push_back(name);
  }
  // Refused: every keyword and macro tried (a sample), accepted: ordinary names the templates use.
  for (const char* refused : {"class", "return", "auto", "template", "inline", "M_PI", "Scalar", "a__b"})
    CHECK(std::find(good_parameters.begin(), good_parameters.end(), refused) == good_parameters.end());
  for (const char* fine : {"n", "p", "state", "std", "step", "gain"})
    CHECK(std::find(good_parameters.begin(), good_parameters.end(), fine) != good_parameters.end());

  // What is accepted compiles: all accepted parameters in one model, every accepted model name as
  // its own model, all accepted filter names in one model; every scalar mode.
  std::string many = "name: many\nstates: [x]\nparameters: {";
  std::string drift = "-x";
  for (std::size_t k = 0; k < good_parameters.size(); ++k) {
    many += (k ? ", " : "") + good_parameters[k] + ": 0.5";
    drift += " - " + good_parameters[k] + "*x";
  }
  many += "}\ndrift: [\"" + drift + "\"]\ndiffusion: [[\"0.1*x\"]]\nobservation: {A: [[\"1\"]], B: [[\"1\"]]}\n";
  many += "initial: {x0: [1], m0: [0], P0: [[1]]}\n";
  write_file(dir.file("many.yaml"), many);
  for (const char* scalar : {"template", "float", "double"}) {
    const std::string out = dir.file(std::string("params_") + scalar);
    REQUIRE(run_pfgen({"codegen", dir.file("many.yaml"), "-o", out, "--scalar", scalar, "--eigen"}).exit_code == 0);
    compile_headers(dir, out, std::string("params_") + scalar);
    const std::string models = dir.file(std::string("models_") + scalar);
    for (const auto& name : good_models) {
      write_file(dir.file("model.yaml"), model_text(name, "x", "a", {}));
      REQUIRE(run_pfgen({"codegen", dir.file("model.yaml"), "-o", models, "--scalar", scalar, "--eigen"}).exit_code == 0);
    }
    compile_headers(dir, models, std::string("models_") + scalar);
    write_file(dir.file("filters.yaml"), model_text("filters", "x", "a", good_filters));
    const std::string filters = dir.file(std::string("filters_") + scalar);
    REQUIRE(run_pfgen({"codegen", dir.file("filters.yaml"), "-o", filters, "--scalar", scalar, "--eigen"}).exit_code == 0);
    compile_headers(dir, filters, std::string("filters_") + scalar);
  }
  // The simulation plugin: the truth code names the parameters too.
  ProcessResult simulate = run_pfgen({"simulate", dir.file("many.yaml"), "--T", "0.02", "--dt", "0.01", "--runs", "1",
                                      "--cache-dir", dir.file("cache"), "-q"});
  INFO(simulate.err.substr(0, 3000));
  CHECK(simulate.exit_code == 0);

  // --namespace: each part is checked the same way.
  ProcessResult ns = run_pfgen({"codegen", example("basin2006_quadratic.yaml"), "--stats", "--namespace", "outer::int"});
  CHECK(ns.exit_code == 1);
  CHECK(ns.err.find("--namespace: 'int' is a C++ keyword") != std::string::npos);
}

TEST_CASE("reserved names: names of the printed equations are refused for symbols", "[unit][model]") {
  for (const char* name : {"m1", "P12", "dm1", "dP12", "K1_1", "dy1", "dt", "P1_10"})
    CHECK(pfgen::symbol_name_problem(name));
  // The moment filters' state entries (in their generated code too) and their printed names.
  for (const char* name : {"M3_111", "M4_1122", "M3_1_2_10", "dM3_111", "L11_1", "L3_111_1", "L1_10_2", "Z2_13",
                           "Z4_1_2_10_11"}) {
    INFO(name);
    CHECK(pfgen::symbol_name_problem(name));
  }
  for (const char* name : {"m", "P", "K", "dy", "dx", "y1", "tau", "t", "mu", "Kp", "M", "M3", "L", "L1", "Lx_1",
                           "M_a", "Z", "Z2", "Z_a"}) {
    INFO(name);
    CHECK(!pfgen::symbol_name_problem(name));
  }
  CHECK(pfgen::code_name_problem("namespace"));
  CHECK(!pfgen::code_name_problem("dt"));  // fine in C++, ambiguous only in the printed equations
}
