#include "pfgen/model/reserved_names.hpp"

#include <regex>
#include <set>

namespace pfgen {
namespace {

// C++20's keywords and alternative tokens: a name the compiler reads as syntax.
const std::set<std::string>& cpp_keywords() {
  static const std::set<std::string> words = {
      "alignas", "alignof", "and", "and_eq", "asm", "auto", "bitand", "bitor", "bool", "break", "case", "catch",
      "char", "char8_t", "char16_t", "char32_t", "class", "compl", "concept", "const", "consteval", "constexpr",
      "constinit", "const_cast", "continue", "co_await", "co_return", "co_yield", "decltype", "default", "delete",
      "do", "double", "dynamic_cast", "else", "enum", "explicit", "export", "extern", "false", "float", "for",
      "friend", "goto", "if", "inline", "int", "long", "mutable", "namespace", "new", "noexcept", "not", "not_eq",
      "nullptr", "operator", "or", "or_eq", "private", "protected", "public", "register", "reinterpret_cast",
      "requires", "return", "short", "signed", "sizeof", "static", "static_assert", "static_cast", "struct",
      "switch", "template", "this", "thread_local", "throw", "true", "try", "typedef", "typeid", "typename",
      "union", "unsigned", "using", "virtual", "void", "volatile", "wchar_t", "while", "xor", "xor_eq"};
  return words;
}

// Macros of the C and C++ headers that generated code and plugins include (<cmath>, <cstddef>,
// <cstdio>, <cerrno>, <cassert>): the preprocessor replaces them before the compiler sees a name.
const std::set<std::string>& library_macros() {
  static const std::set<std::string> macros = {
      "M_E", "M_LOG2E", "M_LOG10E", "M_LN2", "M_LN10", "M_PI", "M_PI_2", "M_PI_4", "M_1_PI", "M_2_PI",
      "M_2_SQRTPI", "M_SQRT2", "M_SQRT1_2", "NAN", "INFINITY", "HUGE_VAL", "HUGE_VALF", "HUGE_VALL", "FP_NAN",
      "FP_INFINITE", "FP_ZERO", "FP_SUBNORMAL", "FP_NORMAL", "FP_FAST_FMA", "FP_FAST_FMAF", "FP_ILOGB0",
      "FP_ILOGBNAN", "MATH_ERRNO", "MATH_ERREXCEPT", "math_errhandling", "NULL", "offsetof", "errno", "assert",
      "EOF", "BUFSIZ", "stdin", "stdout", "stderr", "EDOM", "ERANGE", "EXIT_SUCCESS", "EXIT_FAILURE"};
  return macros;
}

// Types the generated code names in every function (filter.hpp.tmpl, the plugin source).
const std::set<std::string>& generated_code_types() {
  static const std::set<std::string> types = {"Scalar", "Params"};
  return types;
}

}  // namespace

std::optional<std::string> cpp_name_problem(const std::string& name) {
  if (cpp_keywords().count(name)) return "'" + name + "' is a C++ keyword, so the generated code could not use it";
  if (library_macros().count(name))
    return "'" + name + "' is a macro of the C/C++ library headers the generated code includes";
  if (generated_code_types().count(name)) return "'" + name + "' is a type the generated code uses";
  if (name.rfind("PFGEN_", 0) == 0) return "'" + name + "' starts with PFGEN_, the prefix of pfgen's own macros";
  static const std::regex underscore_capital("^_[A-Z]");
  if (name.find("__") != std::string::npos || std::regex_search(name, underscore_capital))
    return "'" + name + "' is reserved in C++ (a double underscore, or an underscore and a capital letter first)";
  return std::nullopt;
}

std::optional<std::string> namespace_name_problem(const std::string& name) {
  if (auto problem = cpp_name_problem(name)) return problem;
  if (name == "std" || name == "Eigen")
    return "'" + name + "' would hide the namespace " + name + " that the generated code uses";
  return std::nullopt;
}

std::optional<std::string> symbol_name_problem(const std::string& name) {
  if (auto problem = cpp_name_problem(name)) return problem;
  // m1, P12, m_1, P_1_2 are the filter's own variables; dm1, dP12, K1_1, dy1 and dt appear in
  // the printed equations (dm1 = (...) dt + K1_1 (dy1 - ... dt)).
  static const std::regex variables("^(m|P)_?[0-9][0-9_]*$");
  if (std::regex_match(name, variables)) return "'" + name + "' is reserved for the filter's m and P entries";
  // md1, phi1, xs1: a delayed filter's m(t - h), Phi*_11 and x*_1 (docs/theory.md §2.6).
  static const std::regex delayed("^(md|phi|xs)_?[0-9][0-9_]*$");
  if (std::regex_match(name, delayed))
    return "'" + name + "' is reserved for the delayed-observation filters' m(t - h), Phi* and x* entries";
  static const std::regex printed("^(d(m|P)_?[0-9][0-9_]*|K_?[0-9]+_[0-9]+|dy_?[0-9]+|dt)$");
  if (std::regex_match(name, printed))
    return "'" + name + "' is a name of the printed equations (dm1 = (...) dt + K1_1 (dy1 - ... dt), dP12)";
  return std::nullopt;
}

}  // namespace pfgen
