// Float-clean generated code (issue 4, deliverables 4 and 5): with --scalar float, and in template
// mode instantiated with float, every generated header compiles under g++ and clang++ with
// -Wall -Wextra -Wdouble-promotion -Werror -fno-exceptions -fno-rtti; the float text holds no
// double literal, no `double`, no unqualified (double) math call and no pow() for an integer
// exponent; and every header includes only <array>, <cmath> and <cstddef>. The models: every
// example (continuous and sampled), a time-varying model, and a sampled model with two
// observations (tests/data/sampled_two_observations.yaml, the 2 x 2 Cholesky solve).
// g++ and clang++ are test requirements (scripts/install-deps.sh installs both): when one is
// missing these tests fail rather than pass silently.
#include <catch2/catch.hpp>

#include <algorithm>
#include <cctype>
#include <cmath>
#include <cstdlib>
#include <filesystem>
#include <set>
#include <sstream>
#include <string>
#include <vector>

#include "pfgen/model/yaml_model_loader.hpp"
#include "support/cli_helpers.hpp"

namespace fs = std::filesystem;
using namespace pfgen_test;

namespace {

const char* const kFlags = "-std=c++17 -O2 -Wall -Wextra -Wdouble-promotion -Werror -fno-exceptions -fno-rtti -c";

// Parameters, functions of time (integer and fractional powers of them), rationals such as 1/3,
// two observations and additive noise, so that every code path of the emitter shows up.
const char* const kTimeVaryingModel = R"model(name: time_varying
states: [x1, x2]
parameters: {a: 0.1, b: 2.5}
drift: ["a*x1^3 + sin(t)*x2 + 1/3", "-b*x2 + cos(2*t)*x1^2 + exp(-t) + (1+t)^(1/3) + sin(t)^2/(1+t)^2"]
diffusion: [["0.1*x1", "0"], ["0", "a"]]
additive_diffusion: [["0.1", "0"], ["0", "0.2"]]
observation:
  A0: ["sin(t)", "0"]
  A: [["1", "1/3"], ["0", "1"]]
  B: [["1+a", "0"], ["0", "2"]]
initial: {m0: [0.1, -0.2], P0: [[1, 0.1], [0.1, 2]]}
)model";

void require_compiler(const std::string& compiler) {
  INFO(compiler << " is not on PATH: it is a test requirement (scripts/install-deps.sh installs g++ and clang)");
  REQUIRE(run_process("command -v " + compiler).exit_code == 0);
}

std::string strip_comments(const std::string& text) {
  std::istringstream in(text);
  std::string line, out;
  while (std::getline(in, line)) {
    const std::size_t comment = line.find("//");
    out += (comment == std::string::npos ? line : line.substr(0, comment)) + "\n";
  }
  return out;
}

bool identifier_char(char c) { return std::isalnum(static_cast<unsigned char>(c)) || c == '_'; }

bool contains_word(const std::string& code, const std::string& word) {
  for (std::size_t at = code.find(word); at != std::string::npos; at = code.find(word, at + 1))
    if ((at == 0 || !identifier_char(code[at - 1])) &&
        (at + word.size() == code.size() || !identifier_char(code[at + word.size()])))
      return true;
  return false;
}

struct Literal {
  std::string text;
  std::size_t position;
};

// Floating literals (with their suffix) in C++ code without comments.
std::vector<Literal> floating_literals(const std::string& code) {
  std::vector<Literal> out;
  for (std::size_t i = 0; i < code.size();) {
    const char c = code[i];
    const bool starts = std::isdigit(static_cast<unsigned char>(c)) ||
                        (c == '.' && i + 1 < code.size() && std::isdigit(static_cast<unsigned char>(code[i + 1])));
    if (!starts || (i > 0 && (identifier_char(code[i - 1]) || code[i - 1] == '.'))) {
      ++i;
      continue;
    }
    std::size_t j = i;
    while (j < code.size() &&
           (identifier_char(code[j]) || code[j] == '.' ||
            ((code[j] == '+' || code[j] == '-') && (code[j - 1] == 'e' || code[j - 1] == 'E'))))
      ++j;
    const std::string token = code.substr(i, j - i);
    const bool hex = token.size() > 1 && token[0] == '0' && (token[1] == 'x' || token[1] == 'X');
    if (!hex && token.find_first_of(".eE") != std::string::npos) out.push_back({token, i});
    i = j;
  }
  return out;
}

// The arguments of each call `name(...)` (split at top-level commas, trimmed).
std::vector<std::vector<std::string>> call_arguments(const std::string& code, const std::string& name) {
  std::vector<std::vector<std::string>> calls;
  for (std::size_t at = code.find(name + "("); at != std::string::npos; at = code.find(name + "(", at + 1)) {
    if (at > 0 && (identifier_char(code[at - 1]))) continue;
    std::vector<std::string> args(1);
    int depth = 0;
    for (std::size_t i = at + name.size() + 1; i < code.size(); ++i) {
      const char c = code[i];
      if (c == '(') ++depth;
      if (c == ')' && depth-- == 0) break;
      if (c == ',' && depth == 0) {
        args.emplace_back();
        continue;
      }
      args.back() += c;
    }
    for (auto& a : args) {
      a.erase(0, a.find_first_not_of(' '));
      a.erase(a.find_last_not_of(' ') + 1);
    }
    calls.push_back(args);
  }
  return calls;
}

// Whether `text` is a number literal (optionally parenthesised, signed, f-suffixed) with an integer value.
bool integer_valued_literal(std::string text) {
  while (text.size() >= 2 && text.front() == '(' && text.back() == ')') text = text.substr(1, text.size() - 2);
  if (!text.empty() && (text.back() == 'f' || text.back() == 'F')) text.pop_back();
  if (text.empty() || text.find_first_not_of("+-0123456789.eE") != std::string::npos) return false;
  char* end = nullptr;
  const double value = std::strtod(text.c_str(), &end);
  return *end == '\0' && std::floor(value) == value;
}

const std::vector<std::string> kMathFunctions = {"sin",  "cos",  "tan",  "exp",  "log",  "sqrt", "pow",
                                                 "sinh", "cosh", "tanh", "asin", "acos", "atan", "abs",
                                                 "fabs", "atan2"};

// Every way `code` (the text of a float-mode header) is not float-clean, one line each.
std::vector<std::string> float_problems(const std::string& text) {
  std::vector<std::string> problems;
  const std::string code = strip_comments(text);
  for (const Literal& literal : floating_literals(code)) {
    const char suffix = literal.text.back();
    if (suffix != 'f' && suffix != 'F')
      problems.push_back("floating literal without an f suffix: " + literal.text + " in `" +
                         code.substr(literal.position > 30 ? literal.position - 30 : 0, 60) + "`");
  }
  if (contains_word(code, "double")) problems.push_back("the type `double` appears");
  for (const std::string& function : kMathFunctions) {
    for (std::size_t at = code.find(function + "("); at != std::string::npos; at = code.find(function + "(", at + 1)) {
      if (at > 0 && identifier_char(code[at - 1])) continue;  // another name, such as tmp_sin(
      if (at < 5 || code.compare(at - 5, 5, "std::") != 0)
        problems.push_back("math call not qualified with std:: (the double version): " + function + "(");
    }
  }
  for (const auto& args : call_arguments(code, "pow"))
    if (args.size() != 2 || integer_valued_literal(args[1]))
      problems.push_back("pow() with an integer exponent: pow(" + args[0] + ", " + (args.size() > 1 ? args[1] : "") +
                         ")");
  return problems;
}

// Template-mode headers spell every floating literal as Scalar(literal).
std::vector<std::string> template_problems(const std::string& text) {
  std::vector<std::string> problems;
  const std::string code = strip_comments(text);
  for (const Literal& literal : floating_literals(code)) {
    std::size_t start = literal.position;
    if (start > 0 && code[start - 1] == '-') --start;
    const bool wrapped = start >= 7 && code.compare(start - 7, 7, "Scalar(") == 0 &&
                         literal.position + literal.text.size() < code.size() &&
                         code[literal.position + literal.text.size()] == ')';
    if (!wrapped) problems.push_back("floating literal outside Scalar(...): " + literal.text);
    if (literal.text.back() == 'f' || literal.text.back() == 'F')
      problems.push_back("float literal in template code (loses precision for double): " + literal.text);
  }
  if (contains_word(code, "double")) problems.push_back("the type `double` appears");
  return problems;
}

std::set<std::string> include_lines(const std::string& text) {
  std::set<std::string> includes;
  std::istringstream in(text);
  std::string line;
  while (std::getline(in, line)) {
    const std::size_t first = line.find_first_not_of(" \t");
    if (first != std::string::npos && line.compare(first, 1, "#") == 0 && line.find("include") != std::string::npos)
      includes.insert(line.substr(first));
  }
  return includes;
}

struct GeneratedModel {
  std::string name;                 // model name, also the directory
  std::vector<std::string> kinds;   // file stems: optimal, ekf_additive, ...
  bool sampled = false;             // sampled observations: predict/update instead of step/gain
  bool delayed = false;             // delayed observations: a Filter with its history, step(dy)
};

// `pfgen codegen MODEL -o DIR --scalar SCALAR` (every kind the model supports); what it wrote.
GeneratedModel generate(const std::string& model_path, const std::string& dir, const std::string& scalar) {
  ProcessResult r = run_pfgen({"codegen", model_path, "-o", dir, "--scalar", scalar});
  INFO("pfgen codegen " << model_path << " --scalar " << scalar << ": " << r.err);
  REQUIRE(r.exit_code == 0);
  GeneratedModel out;
  for (const auto& model_dir : fs::directory_iterator(dir)) {
    out.name = model_dir.path().filename().string();
    out.sampled = pfgen::load_model_file(model_path).observation.is_sampled();
    out.delayed = pfgen::load_model_file(model_path).observation.is_delayed();
    for (const auto& header : fs::directory_iterator(model_dir.path()))
      out.kinds.push_back(header.path().stem().string());
  }
  std::sort(out.kinds.begin(), out.kinds.end());
  REQUIRE(!out.kinds.empty());
  return out;
}

// A translation unit that includes every header of the model and calls every function with float.
std::string float_translation_unit(const GeneratedModel& model, bool templated) {
  const std::string f = templated ? "<float>" : "";
  std::string tu;
  for (const auto& kind : model.kinds) tu += "#include \"" + model.name + "/" + kind + ".hpp\"\n";
  for (const auto& kind : model.kinds) {
    const std::string ns = "pfgen_models::" + model.name + "::" + kind;
    tu += "\nvoid use_" + kind + "(float t, float dt, float* out);\n";
    tu += "void use_" + kind + "(float t, float dt, float* out) {\n";
    tu += "  namespace k = " + ns + ";\n";
    tu += "  const k::Params<float> params{};\n";
    tu += "  std::array<float, k::state_size> state{};\n";
    tu += "  std::array<float, k::p> dy{};\n";
    tu += "  k::initial_state" + f + "(state.data());\n";
    tu += "  for (std::size_t r = 0; r < k::p; ++r) dy[r] = dt * state[0];\n";
    if (model.sampled) {
      // A sampled filter: predict(), update() and advance() (dy stands for the sample y).
      tu += "  k::predict" + f + "(state.data(), t, dt, params);\n";
      tu += "  if (!k::update" + f + "(state.data(), t, dy.data(), params)) return;\n";
      tu += "  if (!k::advance" + f + "(state.data(), t, dy.data(), params)) return;\n";
      tu += "  k::derivatives" + f + "(t, state.data(), params, out);\n";
      tu += "  out[0] += k::period" + f + "();\n";
      tu += "  k::predicted_observation" + f + "(t, state.data(), params, out + k::state_size);\n";
    } else if (model.delayed) {
      // A delayed filter: the Filter object (state, history, step count), then the functions
      // with the delayed inputs m(t - h) and Phi*.
      tu += "  k::Filter" + f + " filter;\n";
      tu += "  filter.step(dy.data());\n";
      tu += "  std::array<float, k::delayed_size> delayed{};\n";
      tu += "  k::detail::delayed_inputs" + f + "(filter.history.data(), filter.state.data(), state.data(), 1, 0, delayed.data());\n";
      tu += "  k::derivatives" + f + "(t + filter.time(), filter.state.data(), delayed.data(), params, out);\n";
      tu += "  k::gain" + f + "(t, state.data(), delayed.data(), params, out + k::state_size);\n";
      tu += "  k::predicted_observation" + f + "(t, state.data(), delayed.data(), params, out + k::state_size + k::n * k::p);\n";
      tu += "  out[0] += dt + k::dt" + f + "() + k::delay" + f + "();\n";
    } else {
      tu += "  k::step" + f + "(state.data(), t, dt, dy.data(), params);\n";
      tu += "  k::derivatives" + f + "(t, state.data(), params, out);\n";
      tu += "  k::gain" + f + "(t, state.data(), params, out + k::state_size);\n";
      tu += "  k::predicted_observation" + f + "(t, state.data(), params, out + k::state_size + k::n * k::p);\n";
    }
    tu += "}\n";
  }
  return tu;
}

void compile(const std::string& compiler, const std::string& include_dir, const std::string& source) {
  const std::string command = compiler + " " + kFlags + " -I " + shell_quote(include_dir) + " " + shell_quote(source) +
                              " -o " + shell_quote(source + "." + compiler + ".o");
  ProcessResult r = run_process(command);
  INFO(command << "\n" << r.err.substr(0, 4000));
  CHECK(r.exit_code == 0);
  CHECK(r.err.empty());
}

std::vector<std::string> float_clean_models(const TempDir& dir) {
  std::vector<std::string> models;
  for (const auto& entry : fs::directory_iterator(source_dir() + "/examples"))
    if (entry.path().extension() == ".yaml") models.push_back(entry.path().string());
  std::sort(models.begin(), models.end());
  REQUIRE(models.size() >= 2);
  write_file(dir.file("time_varying.yaml"), kTimeVaryingModel);
  models.push_back(dir.file("time_varying.yaml"));
  // Sampled with two observations per sample: the written-out 2 x 2 Cholesky solve of update()
  // (the examples' sampled models have one).
  models.push_back(test_data_dir() + "/sampled_two_observations.yaml");
  return models;
}

}  // namespace

TEST_CASE("the float-cleanliness scan finds double code", "[codegen][float][unit]") {
  CHECK(float_problems("  const Scalar tmp0 = state[0] * 0.5f + 1e-3f + tmp12;\n  out[3] = std::pow(t, 0.33333334f);\n")
            .empty());
  CHECK(float_problems("// a comment may say double and 0.1\nconst Scalar x = 2;\n").empty());
  CHECK(float_problems("const Scalar x = y * 0.1;\n").size() == 1);
  CHECK(float_problems("const Scalar x = y * 1e-3;\n").size() == 1);
  CHECK(float_problems("const Scalar x = y * 2.;\n").size() == 1);
  CHECK(float_problems("const Scalar x = y * 1.5L;\n").size() == 1);
  CHECK(float_problems("const double x = y;\n").size() == 1);
  CHECK(float_problems("const Scalar x = sin(y);\n").size() == 1);
  CHECK(float_problems("const Scalar x = std::pow(y, 2.0f);\n").size() == 1);
  CHECK(float_problems("const Scalar x = std::pow(y, (-3.0f));\n").size() == 1);
  CHECK(template_problems("const Scalar x = y * Scalar(0.1) + Scalar(-2.5e-3);\n").empty());
  CHECK(template_problems("const Scalar x = y * 0.1;\n").size() == 1);
  CHECK(template_problems("const Scalar x = y * Scalar(0.1f);\n").size() == 1);
}

TEST_CASE("the compilers used below reject double promotion with these flags", "[codegen][float][compiler]") {
  TempDir dir;
  write_file(dir.file("promotes.cpp"), "float scale(float x);\nfloat scale(float x) { return x * 0.1; }\n");
  for (const std::string compiler : {"g++", "clang++"}) {
    require_compiler(compiler);
    ProcessResult r = run_process(compiler + " " + kFlags + " " + shell_quote(dir.file("promotes.cpp")) + " -o " +
                                  shell_quote(dir.file("promotes.o")));
    INFO(compiler << ": " << r.err);
    CHECK(r.exit_code != 0);
    CHECK(r.err.find("double-promotion") != std::string::npos);
  }
}

TEST_CASE("generated float code is float-clean and compiles warning-free under g++ and clang++", "[codegen][float][compiler]") {
  require_compiler("g++");
  require_compiler("clang++");
  TempDir dir;
  std::size_t pow_calls = 0;
  for (const std::string& model_path : float_clean_models(dir)) {
    for (const bool templated : {false, true}) {
      const std::string mode = templated ? "template" : "float";
      const std::string out = dir.file(fs::path(model_path).stem().string() + "-" + mode);
      GeneratedModel model = generate(model_path, out, mode);
      for (const auto& kind : model.kinds) {
        const std::string text = read_file(out + "/" + model.name + "/" + kind + ".hpp");
        INFO(model_path << " --scalar " << mode << ": " << kind << ".hpp");
        CHECK(include_lines(text) ==
              std::set<std::string>{"#include <array>", "#include <cmath>", "#include <cstddef>"});
        const std::string code = strip_comments(text);
        for (const char* word : {"new", "delete", "malloc", "throw", "try", "catch", "typeid", "dynamic_cast",
                                 "printf", "cout", "FILE", "Eigen"}) {
          INFO(word);
          CHECK(!contains_word(code, word));  // no heap, exceptions, RTTI, I/O or Eigen
        }
        const std::vector<std::string> problems = templated ? template_problems(text) : float_problems(text);
        std::string listed;
        for (const auto& p : problems) listed += p + "\n";
        INFO(listed);
        CHECK(problems.empty());
        if (!templated) pow_calls += call_arguments(strip_comments(text), "pow").size();
        if (!templated) CHECK(text.find("using Scalar = float;") != std::string::npos);
      }
      const std::string source = out + "/use_all.cpp";
      write_file(source, float_translation_unit(model, templated));
      INFO(model_path << " --scalar " << mode << " with float");
      compile("g++", out, source);
      compile("clang++", out, source);
    }
  }
  CHECK(pow_calls > 0);  // the fractional power of the time-varying model: the pow() check ran
}

TEST_CASE("float codegen refuses a constant beyond float's range instead of writing inf", "[codegen][float][integration]") {
  TempDir dir;
  write_file(dir.file("huge.yaml"), "name: huge\nstates: [x]\ndrift: [\"1e40*x\"]\ndiffusion: [[\"0\"]]\n"
                                    "observation:\n  A: [[\"1\"]]\n  B: [[\"1\"]]\n");
  ProcessResult r = run_pfgen({"codegen", dir.file("huge.yaml"), "-o", dir.file("out"), "--scalar", "float"});
  CHECK(r.exit_code != 0);
  CHECK(r.err.find("out of the range of float") != std::string::npos);
  CHECK(!fs::exists(dir.file("out/huge")));
  // The advice holds in every language: C and Rust have no template scalar.
  ProcessResult as_c = run_pfgen({"codegen", dir.file("huge.yaml"), "-o", dir.file("out"), "--language", "c", "--scalar", "float"});
  CHECK(as_c.exit_code != 0);
  CHECK(as_c.err.find("use --scalar double") != std::string::npos);
  CHECK(as_c.err.find("template") == std::string::npos);
  ProcessResult as_double = run_pfgen({"codegen", dir.file("huge.yaml"), "-o", dir.file("out"), "--scalar", "double"});
  INFO(as_double.err);
  CHECK(as_double.exit_code == 0);
  CHECK(read_file(dir.file("out/huge/optimal.hpp")).find("1e+40") != std::string::npos);
}

TEST_CASE("float codegen refuses a nonzero constant that would become 0, as it refuses one beyond range",
          "[codegen][float][integration]") {
  TempDir dir;
  write_file(dir.file("tiny.yaml"), "name: tiny\nstates: [x]\ndrift: [\"-1e-50*x\"]\ndiffusion: [[\"0\"]]\n"
                                    "observation:\n  A: [[\"1\"]]\n  B: [[\"1\"]]\n");
  ProcessResult r = run_pfgen({"codegen", dir.file("tiny.yaml"), "-o", dir.file("out"), "--scalar", "float"});
  INFO(r.err);
  CHECK(r.exit_code == 1);
  CHECK(count_lines(r.err) == 1);
  CHECK(r.err.find("the constant 1e-50 is below the smallest positive float") != std::string::npos);
  CHECK(!fs::exists(dir.file("out/tiny")));
  // Double holds it: the same model generates, with the constant as written.
  ProcessResult as_double = run_pfgen({"codegen", dir.file("tiny.yaml"), "-o", dir.file("out"), "--scalar", "double"});
  INFO(as_double.err);
  CHECK(as_double.exit_code == 0);
  CHECK(read_file(dir.file("out/tiny/optimal.hpp")).find("1e-50") != std::string::npos);
}
